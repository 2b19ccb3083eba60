"""Evaluating candidates: each candidate's sea cases run as sweep cases (local workers or
a Dask cluster, into the results store: a case already stored is read, not run), its
verdicts over seeds, and its objectives and constraints.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import SpaceError


@dataclass(frozen=True)
class Candidate:
    """One evaluated design.

    Attributes:
        values: ``{variable's dotted name: value}``.
        objectives: Each objective's value, as written (not negated), in the space's
            order; NaN when the candidate failed.
        constraints: Each constraint's quantity value, in the space's order.
        violation: The sum of the constraints' violations (0: feasible; inf: failed).
        status: ``"ok"``, ``"failed"`` (a case failed: workspace, singularity, ...) or
            ``"invalid"`` (the description refuses the combination).
        error: Why it failed, or ``""``.
        index: Its position in the order the optimiser asked (0-based).
        governing: What governs its worst utilisation over its sea states (``"Fl6
            speed"``: the actuator and the capacity), or ``""``.
    """

    values: dict
    objectives: tuple
    constraints: tuple
    violation: float
    status: str = "ok"
    error: str = ""
    index: int = 0
    governing: str = ""

    @property
    def feasible(self) -> bool:
        return self.status == "ok" and self.violation == 0.0

    def describe(self) -> str:
        return ", ".join(f"{k} = {v:.6g}" for k, v in self.values.items())


class Evaluator:
    """Runs candidates of ``space`` on ``scene`` through the sweep engine.

    Args:
        scene: The scene (with the command's robot overrides).
        space: The :class:`~._space.Space`.
        workers: Local worker processes (or the cluster's size).
        client: A connected ``dask.distributed.Client`` or None.
        out: The results store directory (the candidates' cases) or None.
        exposure: Full-scale exposure of the verdicts [s].
    """

    def __init__(self, scene, space, workers: int = 1, client=None, out=None,
                 exposure: float | None = None):
        from offshore_crane.studies import sweep

        self.scene, self.space = scene, space
        self.workers, self.client, self.out, self.exposure = workers, client, out, exposure
        self.ids = sweep.CaseIds(scene)
        self.keys = space.names + tuple(dict.fromkeys(k for s in space.sea for k in s))
        self.ran = self.stored = 0
        self.seconds = 0.0

    def __call__(self, batch: list, start: int = 0) -> list:
        """Evaluate ``batch`` (``[{name: value}, ...]``): the candidates in order,
        numbered from ``start``."""
        from offshore_crane.errors import DescriptionError
        from offshore_crane.studies import sweep

        rows, cases, invalid = [], [], {}
        for i, values in enumerate(batch):
            try:
                self.ids.robot_digest(values)            # resolves it: checked
            except DescriptionError as exc:
                invalid[i] = str(exc)
                cases.append(None)
                continue
            params = [{**values, **sea} for sea in self.space.sea]
            cases.append([self.ids(p) for p in params])
            rows += [tuple(p[k] for k in self.keys) for p in params]
        df = None
        if rows:
            stats: dict = {}
            df = sweep.run(self.scene, sweep.Grid.listed(self.keys, rows, "design"),
                           workers=self.workers, scheduler=self.client, out=self.out,
                           stats=stats)
            self.ran += stats["ran"]
            self.stored += stats["skipped"]
            self.seconds += stats.get("seconds", 0.0)
            df = df.set_index("case_id", drop=False)
        out = []
        for i, values in enumerate(batch):
            if i in invalid:
                out.append(self._failed(values, "invalid", invalid[i], start + i))
                continue
            sub = df.loc[list(dict.fromkeys(cases[i]))].copy()
            for name, value in values.items():       # a case another candidate shares
                sub[name] = value
            out.append(self._judged(values, sub, start + i))
        return out

    def _failed(self, values: dict, status: str, error: str, index: int) -> Candidate:
        nan = math.nan
        return Candidate(dict(values), tuple(nan for _ in self.space.objectives),
                         tuple(nan for _ in self.space.constraints), math.inf, status,
                         error, index)

    def _judged(self, values: dict, rows, index: int) -> Candidate:
        from offshore_crane.studies import sweep

        v = sweep.verdicts(rows.reset_index(drop=True), self.scene, self.exposure)
        failed = v[v["basis"] == "failed"]
        if len(failed):
            r = failed.iloc[0]
            return self._failed(values, "failed", f"{r['error_type']}: {r['error']}", index)
        cache: dict = {}

        def value(q) -> float:
            if q not in cache:
                cache[q] = self.quantity(q, values, v)
            return cache[q]

        objectives = tuple(value(o.quantity) for o in self.space.objectives)
        constraints = tuple(value(c.quantity) for c in self.space.constraints)
        violation = sum(c.violation(x) for c, x in zip(self.space.constraints, constraints))
        worst = v.loc[v["worst_util"].idxmax()] if v["worst_util"].notna().any() else None
        governing = ("" if worst is None or not worst["governing"] else
                     f"{worst['governing']} {worst['governing_capacity']}")
        return Candidate(dict(values), objectives, constraints, float(violation),
                         "ok", "", index, governing)

    def quantity(self, q, values: dict, verdicts) -> float:
        """A quantity of a candidate: a verdict column's worst over its sea states, or an
        expression of its description's fields.

        Raises:
            SpaceError: the column is undefined (NaN) for a candidate whose cases ran:
                e.g. a capacity its description does not give, a load criterion without
                a hanging load.
        """
        if q.kind == "expression":
            from offshore_crane.robot.description import resolve
            from offshore_crane.robot.expressions import evaluate

            known = resolve(self.scene.robot_description, {**self.scene.robot,
                                                           **values}).values
            return evaluate(q.text, known.__getitem__)
        column = verdicts[q.text].to_numpy(dtype=float)
        if np.isnan(column).any():
            raise SpaceError(f"{self.space.where}: {q.text} is undefined (NaN) for the "
                             f"candidate {', '.join(f'{k} = {x:g}' for k, x in values.items())}"
                             ": its description gives no such capacity, or the scene no "
                             "hanging load with limits: judge another quantity",
                             path=self.space.where, key=q.text)
        return float(column.min() if q.smallest else column.max())
