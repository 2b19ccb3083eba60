"""``offshore-crane sweep``: a scene over a grid of sea states and robot parameters.

Every case of the grid (the product of its lists) runs the scene and yields one row: its
values, its envelope against the actuators' capacities, its status (a failing case
records its error and the sweep goes on). Cases run on joblib workers (``--workers``) or
a Dask cluster (``--scheduler``); with ``--out`` the rows are stored as they finish (a
Parquet dataset; rerun to resume). Then one verdict per case over its seeds, the
operability over a wave scatter diagram (``--scatter``), and the diagrams (``--plot``).
"""

from __future__ import annotations

import math
import os

from offshore_crane.errors import InputError


def add_parser(sub) -> None:
    from offshore_crane.cli.common import (add_extremes_options, add_parallel_options,
                                           add_robot_options)

    doc = __doc__.splitlines()
    p = sub.add_parser("sweep", help="sizing over a grid of sea states and parameters",
                       description=doc[0].split(": ", 1)[1] + " " + " ".join(
                           line.strip() for line in doc[2:8]))
    p.add_argument("--scene", metavar="FILE.toml", required=True,
                   help="the scene every case runs (a sea scene for hs, tp, heading, "
                   "scale, seed)")
    p.add_argument("--grid", metavar="GRID.toml", required=True,
                   help="lists of values: hs, tp, heading, scale, seed and robot fields by "
                   "their dotted names (see scenes/grids/sweep_grid.toml)")
    p.add_argument("--max-cases", type=int, metavar="N",
                   help="the most cases the grid may make (default 1000000)")
    add_parallel_options(p)
    p.add_argument("--out", metavar="RESULTS_DIR",
                   help="store one Parquet row per case as it finishes; rerun with the same "
                   "directory to resume (finished cases are skipped)")
    p.add_argument("--csv", metavar="FILE.csv", help="also write every row to this CSV")
    p.add_argument("--plot", metavar="DIR",
                   help="write the operability diagram(s) and the utilisation chart of the "
                   "worst case into this directory")
    p.add_argument("--scatter", metavar="FILE.csv",
                   help="a wave scatter diagram (Hs x Tp occurrences): print the "
                   "operability in percent of time per heading and overall")
    add_extremes_options(p, "the verdicts' most probable maximum")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_robot_options(p)
    p.set_defaults(run=run)


def _label(values: dict) -> str:
    return ", ".join(f"{k} = {v:g}" for k, v in values.items())


def run(args) -> int:
    import sys

    from offshore_crane import scenes
    from offshore_crane.studies import sweep
    from offshore_crane.io import plan_outputs, refuse_inside
    from offshore_crane.studies.sizing import CAPACITIES
    from offshore_crane.cli.common import extremes_scene, robot_scene
    from offshore_crane.cli.common import plot_dir as checked_plot_dir

    if args.workers is not None and args.workers < 1:
        raise InputError(f"--workers {args.workers}: must be ≥ 1", name="--workers")
    scene = extremes_scene(args, robot_scene(args, scenes.load_scene(args.scene)))
    grid = sweep.check_grid(scene, sweep.load_grid(args.grid), args.grid,
                            sweep.MAX_CASES if args.max_cases is None else args.max_cases)
    scatter = sweep.load_scatter(args.scatter) if args.scatter else None
    refuse_inside({"--csv": args.csv, "--plot": args.plot}, args.out, "--out")
    planned = plan_outputs({"--csv": args.csv}, [args.scene, args.grid, args.scatter,
                                                 *scene.inputs()])
    plot_dir = checked_plot_dir(args.plot)
    if args.out is not None:
        sweep.ResultsStore.open(args.out, scene)            # refuse before running
    progress = not args.no_progress and sys.stderr.isatty()
    stats: dict = {}
    df = sweep.run(scene, grid, workers=args.workers or 1, scheduler=args.scheduler,
                   out=args.out, progress=progress, stats=stats)
    print(f"offshore-crane sweep: scene {scene.name} ({args.scene}), {len(df)} cases "
          f"({stats['skipped']} already in {args.out}, " if args.out else
          f"offshore-crane sweep: scene {scene.name} ({args.scene}), {len(df)} cases (",
          end="")
    print(f"{stats['ran']} run in {stats.get('seconds', 0.0):.2f} s"
          + (f" {stats['backend']}" if stats["ran"] else "")
          + f", {int((df['status'] != 'ok').sum())} failed)")
    from offshore_crane.scenes.exposure import extremes_option

    hours = extremes_option(scene, "exposure") if scene.trajectory == "sea" else 3.0
    v = sweep.verdicts(df, scene, hours * 3600.0)
    keys = sweep.group_keys(df)
    criteria = _criteria(v)
    _print_verdicts(v, keys, "all" in criteria)
    print(_bases(v, hours))
    op = {}
    if scatter is not None:
        op = {c: sweep.operability(v, scatter, scene, c) for c in criteria}
        _print_operability(op, args.scatter)
    if "--csv" in planned:
        from offshore_crane.io import write_text

        write_text(planned["--csv"], df.to_csv(index=False))
        print(f"wrote {args.csv}")
    if plot_dir is not None:
        _plots(plot_dir, df, v, op, scene, CAPACITIES, criteria, _bases(v, hours))
    return 0


def _bases(v, hours: float) -> str:
    """What the verdicts' bases mean, as printed under their table and on the diagrams."""
    from offshore_crane.studies.sizing import MIN_SEEDS

    text = {"gumbel": f"gumbel: most probable maximum over {hours:g} h full scale (Gumbel "
                      f"fit of the maxima of the seeds' stationary {hours:g}-hour records)",
            "observed": f"observed: the largest observed peak, not extrapolated (fewer "
                        f"than {MIN_SEEDS} seeds, records shorter than the exposure, or no "
                        "sea)",
            "failed": "failed: a seed's case failed (not operable)"}
    return "(" + "; ".join(text[b] for b in text if b in set(v["basis"])) + ")"


#: What each operability criterion judges, as printed.
_CRITERION_TEXT = {"actuators": "actuators' capacities", "no slack": "no slack (the "
                   "slack criterion: smallest tension over the static tension)",
                   "load": "the hanging load's limits (sway, slack, tension, winch)",
                   "all": "actuators and hanging load together"}


def _criteria(v) -> list[str]:
    """The operability criteria a verdict table supports: the actuators', and with a
    hanging load whose limits are given the slack criterion, the load's and all."""
    out = ["actuators"]
    if v["load_util"].notna().any():
        if v["slack_util"].notna().any():
            out.append("no slack")
        out += ["load", "all"]
    return out


def _print_verdicts(v, keys: list, load: bool) -> None:
    """The verdict table: per case its seeds, basis, worst actuator utilisation and what
    governs it; with a hanging load its worst load criterion too."""
    def percent(x) -> str:
        return "failed" if math.isinf(x) else "—" if math.isnan(x) else f"{100 * x:.1f}"

    head = "".join(f"{k:>14}" for k in keys)
    print(f"{head}{'seeds':>7}{'basis':>10}{'worst %':>9}"
          + (f"{'load %':>8}" if load else "") + "  governing")
    for _, r in v.iterrows():
        who = (f"{r['governing']} {r['governing_capacity']}" if r["governing"] else
               f"{r['error_type']}: {r['error'][:72]}..." if r["error"] else "")
        if load and r["load_governing"] and r["load_governing"] != "failed":
            who += ("; " if who else "") + f"load: {r['load_governing']}"
        print("".join(f"{r[k]:>14g}" for k in keys)
              + f"{r['seeds']:>7}{r['basis']:>10}{percent(r['worst_util']):>9}"
              + (f"{percent(r['load_util']):>8}" if load else "") + f"  {who}")


def _print_operability(op: dict, scatter: str) -> None:
    """``{criterion: operability table}`` per heading and overall, a block per criterion
    when there are several."""
    print(f"operability over {scatter} (a cell is operable below the limiting Hs of its "
          "Tp; headings equally likely overall):")
    for criterion, table in op.items():
        if len(op) > 1:
            print(f" {_CRITERION_TEXT[criterion]}:")
        for _, r in table.iterrows():
            others = {k: r[k] for k in table.columns if k not in
                      ("heading", "operability_pct", "uncovered_pct")}
            where = (_label(others) + ", ") if others else ""
            what = "overall" if math.isnan(r["heading"]) else f"heading {r['heading']:g}°"
            print(f"  {where}{what}: {r['operability_pct']:.1f} % of the time"
                  + (f" ({r['uncovered_pct']:.1f} % of the time outside the swept Tp)"
                     if r["uncovered_pct"] > 0 else ""))


def _plots(plot_dir, df, v, op, scene, capacities, criteria, bases: str) -> None:
    import numpy as np

    from offshore_crane.studies import sweep
    from offshore_crane.conventions import ACTUATORS
    from offshore_crane.outputs.sizing_plots import operability_diagram, utilisation_chart

    os.makedirs(plot_dir, exist_ok=True)
    table = v.copy()
    for key in ("hs", "tp", "heading"):
        if key not in table.columns:
            table[key] = float(scene.sea.get(key, math.nan))
    others = [k for k in sweep.group_keys(table) if k not in ("hs", "tp", "heading")]
    combos = table.groupby(others, sort=False) if others else [((), table)]
    for values, g in combos:
        values = values if isinstance(values, tuple) else (values,)
        label = dict(zip(others, values))
        for criterion in criteria:
            name = ("operability" + ("" if criterion == "actuators" else
                                     "-" + criterion.replace(" ", "-"))
                    + "".join(f"-{k}={val:g}" for k, val in label.items()))
            path = os.path.join(plot_dir, f"{name}.png")
            percent = None
            if criterion in op:
                o = op[criterion]
                mask = np.ones(len(o), bool)
                for k, val in label.items():
                    mask &= o[k].to_numpy() == val
                sel = o[mask & o["heading"].notna().to_numpy()]
                percent = dict(zip(sel["heading"], sel["operability_pct"]))
            what = "worst utilisation" if criterion == "actuators" else criterion
            operability_diagram(path, g, title=f"{scene.name}: {what}"
                                + (f" ({_label(label)})" if label else "") + f" {bases}",
                                operability=percent, criterion=criterion)
            print(f"wrote {path}")
    ok = df[df["status"] == "ok"]
    if len(ok):
        r = ok.loc[ok["worst_util"].idxmax()]
        util = np.array([[r[f"{a}_util_{c}"] for c in capacities] for a in ACTUATORS])
        params = {k: r[k] for k in sweep.group_keys(df) + (["seed"] if "seed" in df else [])}
        path = os.path.join(plot_dir, "utilisation-worst-case.png")
        full = r["duration_s"] * math.sqrt(float(r.get("scale", scene.sea.get("scale", 1.0))))
        utilisation_chart(path, util, title=f"worst case ({_label(params)}): "
                          f"{r['governing']} {r['governing_capacity']} at "
                          f"{100 * r['worst_util']:.1f} %, observed over its one record "
                          f"({full:.6g} s full scale), not the verdict's extreme")
        print(f"wrote {path}")
