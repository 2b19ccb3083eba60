"""What a sweep's results mean: sizing verdicts per group of seeds, and operability against a
wave scatter diagram.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np

from offshore_crane.studies.sweep.cases import CASE_COLUMNS
from offshore_crane.studies.sweep.grid import install_hint


#: Columns of :func:`verdicts` besides the parameters and the utilisations.
VERDICT_COLUMNS = ("seeds", "failed", "record_s", "exposure_s", "basis", "error_type",
                   "error", "load_governing", "overall_util", "overall_governing")
#: The criteria an operability diagram can be drawn for: the verdict column it reads.
CRITERIA = {"actuators": "worst_util", "no slack": "slack_util", "load": "load_util",
            "all": "overall_util"}


# =========================================================================== verdicts
def verdict_quantities() -> tuple:
    """The numeric columns of :func:`verdicts` that judge a case (what a design's
    objectives and constraints may name): each actuator's ``{actuator}_util`` and
    ``{actuator}_util_{capacity}``, ``worst_util``, the hanging load's criteria
    (``sway_util``, ``slack_util``, ...), ``tension_ratio_min``, ``load_util`` and
    ``overall_util``."""
    from offshore_crane.conventions import ACTUATORS
    from offshore_crane.studies.sizing import CAPACITIES, LOAD_CRITERIA
    from offshore_crane.studies.sizing.loads import util_column

    return (tuple(f"{a}_util" for a in ACTUATORS)
            + tuple(f"{a}_util_{c}" for a in ACTUATORS for c in CAPACITIES)
            + ("worst_util",) + tuple(util_column(c) for c in LOAD_CRITERIA)
            + ("tension_ratio_min", "load_util", "overall_util"))


def group_keys(df) -> list:
    """The parameter columns of a results table but ``seed`` (a case's seeds form one
    group)."""
    from offshore_crane.studies.sizing import row_columns

    skip = {"case", "case_id", "seed", *(n for n, _ in CASE_COLUMNS),
            *(n for n, _ in row_columns()), *VERDICT_COLUMNS}
    return [c for c in df.columns if c not in skip]


def verdicts(df, scene, exposure: float | None = None):
    """One verdict per case over its seeds (:func:`offshore_crane.studies.sizing.verdict`'s
    rule — the Gumbel most probable maximum of at least 5 records that each cover the
    exposure, else the largest observed — applied to the rows' utilisation columns: a
    capacity is constant over a case's seeds and the Gumbel fit is location-scale
    equivariant, so the most probable maximum of a utilisation is that of the peak
    divided by the capacity).

    Args:
        df: Rows of :func:`run`.
        scene: The scene swept (its ``[sea] scale`` when the grid does not vary it).
        exposure: Full-scale exposure [s] (default 3 h).

    Returns:
        ``pandas.DataFrame``: the group's parameters, ``seeds``, ``failed`` (seeds whose
        case failed), ``basis`` (``gumbel``, ``observed`` or ``failed``), ``record_s``,
        ``exposure_s``, ``{actuator}_util``, each capacity's ``{actuator}_util_{capacity}``
        (on the same basis; NaN when a seed failed or the capacity is not given) and
        ``worst_util`` (inf when a seed failed:
        not operable), ``governing``, ``governing_capacity``, ``error_type`` and
        ``error`` (of the first failed seed, else empty); with a hanging load
        (:mod:`offshore_crane.studies.sizing.loads`, NaN without) ``tension_ratio_min``
        (the most probable minimum of ``T_min / m|g|``), ``{criterion}_util`` of its
        criteria on the same basis, ``load_util`` their worst and ``load_governing``;
        ``overall_util`` (the worst of ``worst_util`` and ``load_util``) and
        ``overall_governing`` (an actuator's ``"{actuator} {capacity}"`` or a load
        criterion).
    """
    from offshore_crane.conventions import ACTUATORS
    from offshore_crane.studies.sizing import (CAPACITIES, EXPOSURE, MIN_SEEDS, covers_exposure,
                                               most_probable_maximum)

    pd = install_hint("pandas", "A sweep's results table")
    exposure = EXPOSURE if exposure is None else exposure
    keys = group_keys(df)
    sea = scene.trajectory == "sea"
    out = []
    groups = df.groupby(keys, sort=False, dropna=False) if keys else [((), df)]
    for values, g in groups:
        values = values if isinstance(values, tuple) else (values,)
        row = dict(zip(keys, values))
        ok = g[g["status"] == "ok"]
        scale = float(row.get("scale", scene.sea.get("scale", math.nan))) if sea else None
        n = len(g)
        record_s = (float(ok["duration_s"].iloc[0]) * math.sqrt(scale)
                    if sea and len(ok) else math.nan)
        gumbel = (sea and len(ok) == n and n >= MIN_SEEDS and covers_exposure(
            float(ok["duration_s"].iloc[0]), int(ok["samples"].iloc[0]), scale, exposure))
        row.update(seeds=n, failed=n - len(ok), record_s=record_s,
                   exposure_s=exposure if gumbel else math.nan,
                   basis="failed" if len(ok) < n else ("gumbel" if gumbel else "observed"))
        bad = g[g["status"] != "ok"]
        row.update(error_type=bad["error_type"].iloc[0] if len(bad) else "",
                   error=bad["error"].iloc[0] if len(bad) else "")
        util = np.full((9, len(CAPACITIES)), np.nan)
        for k, a in enumerate(ACTUATORS):
            for c, cap in enumerate(CAPACITIES):
                col = ok[f"{a}_util_{cap}"].to_numpy(dtype=float)
                if len(ok) < n or not len(col) or np.isnan(col).any():
                    continue
                util[k, c] = (most_probable_maximum(col, record_s, max(exposure, record_s))
                              if gumbel else col.max())
        for k, a in enumerate(ACTUATORS):
            u = util[k]
            row[f"{a}_util"] = math.nan if np.isnan(u).all() else float(np.nanmax(u))
            row.update({f"{a}_util_{cap}": float(u[c]) for c, cap in enumerate(CAPACITIES)})
        if len(ok) < n:
            row.update(worst_util=math.inf, governing="", governing_capacity="")
        elif np.isnan(util).all():
            row.update(worst_util=math.nan, governing="", governing_capacity="")
        else:
            k, c = np.unravel_index(np.nanargmax(util), util.shape)
            row.update(worst_util=float(util[k, c]), governing=ACTUATORS[k],
                       governing_capacity=CAPACITIES[c])
        row.update(_load_columns(ok, len(ok) == n, gumbel, record_s,
                                 max(exposure, record_s) if gumbel else exposure))
        actuators = (f"{row['governing']} {row['governing_capacity']}"
                     if row["governing"] else "")
        pairs = [(row["worst_util"], actuators), (row["load_util"], row["load_governing"])]
        judged = [p for p in pairs if not math.isnan(p[0])]
        row["overall_util"], row["overall_governing"] = (max(judged, key=lambda p: p[0])
                                                         if judged else (math.nan, ""))
        out.append(row)
    return pd.DataFrame(out)


def _load_columns(ok, complete: bool, gumbel: bool, record: float, exposure: float) -> dict:
    """A group's hanging-load verdict columns from its rows' :data:`LIFT` columns: each
    utilisation's most probable maximum (or observed), the slack criterion's of the
    most probable minimum of the tension ratio; every utilisation inf when a seed failed
    (not operable)."""
    from offshore_crane.studies.sizing import (LOAD_CRITERIA, most_probable_extreme,
                                               slack_utilisation)
    from offshore_crane.studies.sizing.loads import util_column, worst_load

    out = {util_column(c): math.nan for c in LOAD_CRITERIA}
    out.update(tension_ratio_min=math.nan, load_util=math.nan, load_governing="")
    if "sway_max" not in ok or (len(ok) and ok["sway_max"].isna().all()):
        return out                                       # no hanging load
    if not complete or not len(ok):                      # not operable by any criterion
        out.update({k: math.inf for k in out if k.endswith("_util")}, load_governing="failed")
        return out

    def extreme(column: str, sign: float = 1.0) -> float:
        values = ok[column].to_numpy(dtype=float)
        return math.nan if np.isnan(values).all() else most_probable_extreme(
            values, record, exposure, gumbel, sign)

    ratio = extreme("tension_ratio_min", -1.0)
    util = {c: extreme(util_column(c)) for c in LOAD_CRITERIA if c != "slack"}
    util["slack"] = slack_utilisation(float(ok["tension_ratio_limit"].iloc[0]), ratio)
    out.update({util_column(c): u for c, u in util.items()})
    out["tension_ratio_min"] = ratio
    out["load_util"], out["load_governing"] = worst_load(util)
    return out


# =========================================================================== operability
@dataclass(frozen=True)
class Scatter:
    """A wave scatter diagram: occurrence of (Hs, Tp) cells, full scale.

    Attributes:
        hs: ``(m,)`` Hs of the rows (cell centres) [m], increasing.
        tp: ``(n,)`` Tp of the columns [s], increasing.
        p: ``(m, n)`` probabilities (normalised to sum 1).
        path: The file read, or None.
    """

    hs: np.ndarray
    tp: np.ndarray
    p: np.ndarray
    path: str | None = None


def load_scatter(path) -> Scatter:
    """Read a wave scatter diagram (CSV): lines starting with ``#`` are comments; the
    first other line is the header, its first cell a label (``hs_m/tp_s``) and the others
    the Tp of each column [s]; each further line an Hs [m] then the occurrences of its
    cells (probabilities, per mille or counts: normalised to sum 1).

    Raises:
        InputError: naming the file, the line and the cell (not a number, negative,
            not increasing, rows of different lengths, all zero).
    """
    from offshore_crane.errors import InputError
    from offshore_crane.io import read_text

    where = os.fspath(path)
    text = read_text(where, "scatter diagram")
    lines = [(i + 1, l) for i, l in enumerate(text.splitlines())
             if l.strip() and not l.lstrip().startswith("#")]
    if len(lines) < 2:
        raise InputError(f"{where}: a scatter diagram needs a header line (label, Tp "
                         "values [s]) and at least one row (Hs [m], occurrences)",
                         name=where)

    def numbers(lineno, cells, what):
        out = []
        for j, c in enumerate(cells):
            try:
                x = float(c)
            except ValueError:
                x = math.nan
            if not math.isfinite(x) or x < 0:
                raise InputError(f"{where}, line {lineno}, cell {j + 2}: {c.strip()!r} is "
                                 f"not a finite number ≥ 0 ({what})", name=where)
            out.append(x)
        return out

    head_line, head = lines[0]
    tp = numbers(head_line, head.split(",")[1:], "Tp [s]")
    hs, p = [], []
    for lineno, line in lines[1:]:
        cells = line.split(",")
        if len(cells) != len(tp) + 1:
            raise InputError(f"{where}, line {lineno}: {len(cells)} cells, but the header "
                             f"has {len(tp) + 1} (Hs then one per Tp)", name=where)
        h = numbers(lineno, cells[:1], "Hs [m]")[0]
        hs.append(h)
        p.append(numbers(lineno, cells[1:], "occurrence"))
    hs, tp, p = np.array(hs), np.array(tp), np.array(p)
    for name, a, line in (("Hs", hs, "rows"), ("Tp", tp, "header")):
        if len(a) > 1 and not (np.diff(a) > 0).all():
            raise InputError(f"{where}: the {name} values of the {line} must increase",
                             name=where)
    if (hs <= 0).any() or (tp <= 0).any():
        raise InputError(f"{where}: Hs and Tp must be > 0", name=where)
    if p.sum() <= 0:
        raise InputError(f"{where}: every occurrence is 0", name=where)
    return Scatter(hs, tp, p / p.sum(), where)


def limiting_hs(hs, util) -> float:
    """The largest Hs [m] up to which the utilisation stays ≤ 1, from utilisations at
    increasing ``hs``: linear interpolation between the last Hs within capacity and the
    first beyond; 0 when the smallest already exceeds; the largest swept Hs when none
    exceeds (beyond it nothing is known). A failed case counts as beyond (inf)."""
    hs, util = np.asarray(hs, float), np.asarray(util, float)
    order = np.argsort(hs)
    hs, util = hs[order], np.where(np.isnan(util[order]), 0.0, util[order])
    over = np.flatnonzero(util > 1.0)
    if not len(over):
        return float(hs[-1])
    j = int(over[0])
    if j == 0:
        return 0.0
    u0, u1 = util[j - 1], util[j]
    if not math.isfinite(u1):
        return float(hs[j - 1])
    return float(hs[j - 1] + (1.0 - u0) / (u1 - u0) * (hs[j] - hs[j - 1]))


def operability(table, scatter: Scatter, scene, criterion: str = "actuators"):
    """Operability over a scatter diagram, per heading and overall, for one of
    :data:`CRITERIA`: the actuators' capacities (``worst_util``), the slack criterion
    alone (``"no slack"``), the hanging load's limits (``"load"``) or all of them.

    For each heading (and combination of other swept parameters), the limiting Hs of each
    swept Tp (:func:`limiting_hs` on the criterion's utilisation of :func:`verdicts`) is
    interpolated linearly in Tp; a scatter cell is operable when its Hs ≤ that limit. Cells
    whose Tp lies outside the swept Tp range are not covered and count as not operable
    (their share is reported). Overall: the mean over the headings (equally likely).

    Returns:
        ``pandas.DataFrame``: the other parameters, ``heading``, ``operability_pct``,
        ``uncovered_pct``; and a row with ``heading = NaN`` (overall) per combination.
    """
    from offshore_crane.errors import InputError

    pd = install_hint("pandas", "A sweep's results table")
    if criterion not in CRITERIA:
        raise InputError(f"operability: criterion {criterion!r} is not one of "
                         f"{', '.join(CRITERIA)}", name="criterion")
    column = CRITERIA[criterion]
    v = table.copy()
    for key in ("hs", "tp", "heading"):
        if key not in v.columns:
            v[key] = float(scene.sea.get(key, math.nan))
    others = [k for k in group_keys(v) if k not in ("hs", "tp", "heading")]
    out = []
    combos = v.groupby(others, sort=False, dropna=False) if others else [((), v)]
    for values, g in combos:
        values = values if isinstance(values, tuple) else (values,)
        base = dict(zip(others, values))
        per_heading = []
        for heading, h in g.groupby("heading", sort=True):
            tps = np.sort(h["tp"].unique())
            limits = np.array([limiting_hs(h.loc[h["tp"] == tp, "hs"],
                                           h.loc[h["tp"] == tp, column]) for tp in tps])
            covered = (scatter.tp >= tps[0] - 1e-9) & (scatter.tp <= tps[-1] + 1e-9)
            lim = np.interp(scatter.tp, tps, limits)
            ok = (scatter.hs[:, None] <= lim[None, :] + 1e-12) & covered[None, :]
            pct = 100.0 * float((scatter.p * ok).sum())
            uncovered = 100.0 * float(scatter.p[:, ~covered].sum())
            per_heading.append(pct)
            out.append({**base, "heading": float(heading), "operability_pct": pct,
                        "uncovered_pct": uncovered})
        out.append({**base, "heading": math.nan,
                    "operability_pct": float(np.mean(per_heading)),
                    "uncovered_pct": float(np.mean([r["uncovered_pct"] for r in out[-len(
                        per_heading):]]))})
    return pd.DataFrame(out)
