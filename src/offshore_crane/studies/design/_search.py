"""The search: pymoo's NSGA-II asks for candidates generation by generation, the
:class:`~._evaluate.Evaluator` runs them, until the budget of evaluations is spent; the
front is the non-dominated set of every feasible candidate evaluated.

Reproducible: the algorithm draws from its own generator seeded by ``seed``, and a
candidate's objectives come from its cases' rows, which are bit-identical however they
run and whether they are run or read back from the store. So a rerun on the same results
directory replays the same candidates, reads the stored ones instead of running them, and
ends on the front an uninterrupted run gives.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field

import numpy as np

from offshore_crane.errors import InputError, NoFeasibleDesignError
from offshore_crane.studies.design._evaluate import Candidate, Evaluator
from offshore_crane.studies.design._space import Space, check_space, load_space

#: Candidates per generation unless given: 20, or 5 per variable when there are more
#: than 4 (NSGA-II's population). On the two-variable test problem, budgets of 60 reached
#: 0.99 or more of a 5 x 5 grid's hypervolume for seeds 0-4 with 20, down to 0.96 with 10.
MIN_POPULATION, PER_VARIABLE = 20, 5


def pymoo():
    from offshore_crane.errors import require

    return require("pymoo", "pymoo (or: pip install offshore-crane[design])",
                   "offshore-crane design (NSGA-II)")


@dataclass
class Design:
    """A finished search.

    Attributes:
        space: The :class:`~._space.Space` searched.
        candidates: Every :class:`~._evaluate.Candidate` evaluated, in the order asked.
        front: The non-dominated feasible candidates, by the first objective's value.
        stats: ``evaluated``, ``ran`` (cases run), ``stored`` (cases read from the store),
            ``generations``, ``population``, ``seconds`` (wall time of the search).
    """

    space: Space
    candidates: list
    front: list
    stats: dict = field(default_factory=dict)

    def least_violating(self) -> Candidate | None:
        """The candidate nearest to feasible (smallest violation; failed ones last)."""
        return min(self.candidates, key=lambda c: (c.violation, c.index), default=None)


def run(scene, space, budget: int = 100, seed: int = 0, workers: int | None = 1,
        scheduler: str | None = None, out=None, *, progress: bool = False,
        population: int | None = None, exposure: float | None = None,
        where: str = "space") -> Design:
    """Search ``space`` on ``scene`` with NSGA-II for at most ``budget`` evaluations.

    Args:
        scene: A :class:`~offshore_crane.scenes.Scene` or a scene file path.
        space: A :class:`~._space.Space`, a dict of its tables, or a space file path.
        budget: The most candidates evaluated (≥ 1).
        seed: The optimiser's seed (an integer ≥ 0): the same seed, the same front.
        workers: Local worker processes (with ``scheduler = "local"`` the cluster's size).
        scheduler: None, ``"local"`` (a Dask ``LocalCluster``) or ``tcp://HOST:PORT``.
        out: The results directory of the candidates' cases (a sweep store: resumable),
            or None.
        progress: Show a progress bar of the candidates.
        population: Candidates per generation (default: :data:`MIN_POPULATION`, or
            :data:`PER_VARIABLE` per variable; at most ``budget``).
        exposure: Full-scale exposure of the verdicts [s] (default: the scene's).

    Returns:
        :class:`Design`.

    Raises:
        SpaceError, GridError, InputError: a bad space, budget, seed or workers (before
            anything runs or is written).
        ResultsDirectoryError, SchedulerError: as :func:`offshore_crane.studies.sweep.run`.
        NoFeasibleDesignError: no candidate met every constraint (its ``candidate`` the
            least violating); the cases stay in ``out``.
    """
    from offshore_crane import progress as shown
    from offshore_crane import scenes
    from offshore_crane.studies import sweep
    from offshore_crane.studies.sweep.scheduler import check_scheduler

    scene = scenes.load_scene(scene) if isinstance(scene, (str, os.PathLike)) else scene
    if not isinstance(space, Space):
        given = isinstance(space, (str, os.PathLike))
        space = check_space(scene, load_space(space) if given else space,
                            os.fspath(space) if given else where)
    for name, value, low in (("budget", budget, 1), ("seed", seed, 0),
                             ("workers", workers or 1, 1), ("population", population or 2, 2)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
            raise InputError(f"--{name} {value!r}: must be an integer ≥ {low}", name=name)
    scheduler = check_scheduler(scheduler)
    mo = pymoo()
    if exposure is None and scene.trajectory == "sea":
        from offshore_crane.scenes.exposure import extremes_option

        exposure = extremes_option(scene, "exposure") * 3600.0
    if out is not None:
        sweep.ResultsStore.open(out, scene)             # refused before anything runs
    size = min(budget, population or max(MIN_POPULATION, PER_VARIABLE * len(space.variables)))
    client = cluster = None
    if scheduler is not None:
        client, cluster = sweep.connect(scheduler, workers)
        if cluster is None:
            from offshore_crane.studies.sweep.backends import warm_up_workers

            warm_up_workers(client, scene)
    evaluate = Evaluator(scene, space, workers or 1, client, out, exposure)
    candidates: list = []
    t0 = time.perf_counter()
    generations = 0
    try:
        with shown.bar(budget, "candidate", "design", enabled=bool(progress)) as bar:
            for batch in _generations(mo, space, size, budget, seed, evaluate):
                candidates += batch
                generations += 1
                bar.update(len(batch))
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    stats = {"evaluated": len(candidates), "ran": evaluate.ran, "stored": evaluate.stored,
             "generations": generations, "population": size,
             "seconds": time.perf_counter() - t0, "case_seconds": evaluate.seconds}
    design = Design(space, candidates, front(space, candidates), stats)
    if not design.front:
        raise NoFeasibleDesignError(_infeasible(design), design.least_violating(),
                                    len(candidates))
    return design


def _generations(mo, space: Space, size: int, budget: int, seed: int, evaluate):
    """NSGA-II's generations, evaluated: yields each generation's candidates (the last
    cut to the budget)."""
    import importlib

    NSGA2 = importlib.import_module("pymoo.algorithms.moo.nsga2").NSGA2
    Problem = importlib.import_module("pymoo.core.problem").Problem
    Evaluator_ = importlib.import_module("pymoo.core.evaluator").Evaluator
    StaticProblem = importlib.import_module("pymoo.problems.static").StaticProblem
    NoTermination = importlib.import_module("pymoo.core.termination").NoTermination

    bounds = np.array([v.bounds for v in space.variables], dtype=float)
    problem = Problem(n_var=len(space.variables), n_obj=len(space.objectives),
                      n_ieq_constr=len(space.constraints), xl=bounds[:, 0], xu=bounds[:, 1])
    algorithm = NSGA2(pop_size=size, sampling=_start())
    algorithm.setup(problem, termination=NoTermination(), seed=int(seed), verbose=False)
    done = 0
    while done < budget:
        pop = algorithm.ask()
        pop = pop[:budget - done]
        X = pop.get("X")
        batch = evaluate([{v.name: v.decode(x) for v, x in zip(space.variables, row)}
                          for row in X], done)
        F, G = _minimised(space, batch)
        Evaluator_().eval(StaticProblem(problem, F=F, G=G), pop)
        algorithm.tell(infills=pop)
        done += len(batch)
        yield batch


def _start():
    """The first generation's sampling: the box's corners when they fill at most half of
    it (a design often lies on its bounds: reach grows with every length, a utilisation
    too; a random start seldom draws them, and the search then spends generations
    creeping towards them), the rest a Latin hypercube (pymoo's, drawn from the
    algorithm's seeded generator)."""
    import importlib
    import itertools

    Sampling = importlib.import_module("pymoo.core.sampling").Sampling
    LHS = importlib.import_module("pymoo.operators.sampling.lhs").LatinHypercubeSampling

    class Start(Sampling):
        def _do(self, problem, n_samples, *args, random_state=None, **kwargs):
            corners = np.array(list(itertools.product(*zip(problem.xl, problem.xu))))
            if len(corners) > n_samples // 2:
                corners = corners[:0]
            rest = n_samples - len(corners)
            drawn = (LHS()._do(problem, rest, random_state=random_state) if rest else
                     np.empty((0, problem.n_var)))
            return np.vstack([corners, drawn])

    return Start()


#: What the optimiser sees of a candidate that failed or that the description refuses:
#: finite (pymoo sorts by it), far beyond any real objective or violation.
FAILED = 1e30


def _minimised(space: Space, batch: list) -> tuple[np.ndarray, np.ndarray]:
    """``(F, G)`` for pymoo: objectives to minimise (maximised ones negated), constraints
    as ``g <= 0``."""
    sign = np.array([1.0 if o.sense == "minimise" else -1.0 for o in space.objectives])
    F = np.array([[FAILED] * len(sign) if c.status != "ok" else sign * np.array(c.objectives)
                  for c in batch], dtype=float)
    G = np.array([[FAILED] * len(space.constraints) if c.status != "ok" else
                  [x - k.bound if k.op == "<=" else k.bound - x
                   for k, x in zip(space.constraints, c.constraints)] for c in batch],
                 dtype=float)
    return F, G


def front(space: Space, candidates: list) -> list:
    """The non-dominated feasible candidates (each design once: the first evaluation of
    its values), ordered by their objectives as written."""
    seen: dict = {}
    for c in candidates:
        if c.feasible:
            seen.setdefault(tuple(c.values.values()), c)
    feasible = list(seen.values())
    if not feasible:
        return []
    F, _ = _minimised(space, feasible)
    keep = [i for i in range(len(F))
            if not any(np.all(F[j] <= F[i]) and np.any(F[j] < F[i]) for j in range(len(F)))]
    return sorted((feasible[i] for i in keep), key=lambda c: (c.objectives, c.index))


def _infeasible(design: Design) -> str:
    """The message of a search without a feasible design: the least-violating candidate,
    its worst constraint and by how much."""
    c = design.least_violating()
    n = len(design.candidates)
    head = f"no feasible design among the {n} candidates evaluated"
    if c is None:
        return head
    if c.status != "ok":
        return (f"{head}: every candidate failed or was refused; the first, {c.describe()}"
                f": {c.error}")
    worst = max(zip(design.space.constraints, c.constraints),
                key=lambda p: p[0].violation(p[1]))
    k, x = worst
    why = (f" ({c.governing})" if c.governing and k.quantity.text in ("worst_util",
                                                                       "overall_util")
           else "")
    return (f"{head}: the least violating, {c.describe()}, has {k.quantity.text} = "
            f"{x:.6g}{why} against {k.describe()} (total violation {c.violation:.6g}): "
            "relax the constraint, widen the variables' bounds or raise --budget")
