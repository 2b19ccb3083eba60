"""Running a sweep: every case of a grid through a backend into the store, with progress and
resume.
"""

from __future__ import annotations

import os
import time

from offshore_crane import progress as shown
from offshore_crane.errors import SchedulerError
from offshore_crane.studies.sweep.backends import (can_fork, connect, run_in_process,
                                                   run_on_forks, run_on_dask, run_on_joblib,
                                                   warm_up_scene, warm_up_workers)
from offshore_crane.studies.sweep.cases import row_schema
from offshore_crane.studies.sweep.grid import (MAX_CASES, CaseIds, Grid, check_grid,
                                               install_hint, load_grid, scene_values)
from offshore_crane.studies.sweep.rowfiles import batch_seconds
from offshore_crane.studies.sweep.scheduler import check_scheduler, handshake
from offshore_crane.studies.sweep.store import (ResultsStore, conform, results_table,
                                                with_values)


#: Rows of a run held as Python dicts before they are packed into an Arrow table.
HELD_ROWS = 2000


def run(scene, grid, workers: int | None = 1, scheduler: str | None = None, out=None, *,
        progress: bool = False, stats: dict | None = None, backend: str = "auto",
        where: str = "grid", max_cases: int = MAX_CASES):
    """Run a sweep: every case of ``grid`` on ``scene``, one row per case.

    Args:
        scene: A :class:`~offshore_crane.scenes.Scene` (or a scene file path).
        grid: ``{key: list}`` (:func:`load_grid`), a grid file path, or a :class:`Grid`.
        workers: Parallel processes: 1 (serially, in this process), N > 1 (worker
            processes forked from this one on Linux, a few cases a task; joblib's loky
            workers elsewhere), or with ``scheduler = "local"`` the cluster's size
            (default 2).
        scheduler: None (joblib or serial), ``"local"`` (a Dask ``LocalCluster``), a
            Dask scheduler address ``tcp://HOST:PORT``, or a connected
            ``dask.distributed.Client`` (from :func:`connect`, its workers warmed up by
            the caller: a design's generations share one), which the run uses and leaves
            open.
        out: A results directory (resumable: finished cases are skipped), or None to
            keep the rows in memory only.
        progress: Show a progress bar (tqdm) on standard error.
        stats: A dict filled with ``cases``, ``skipped``, ``ran``, ``failed``, ``backend``
            (where the cases ran, in words),
            ``seconds`` (wall time from the dispatch to the last row written),
            ``case_seconds`` (each case's run time in its worker, :func:`run_case` whole)
            and ``compute_seconds`` (each case's own computation: trajectory and
            dynamics) — for benchmarks.
        backend: Kernels of every case (``"auto"``: compiled when Numba is installed),
            resolved once here so that every worker runs the same code.
        where: The grid's name in messages when it is a dict.
        max_cases: The most cases the grid may make (:data:`MAX_CASES` by default).

    Returns:
        ``pandas.DataFrame``: one row per case of the grid in grid order (column ``case``,
        its index), with the columns of :func:`row_schema`.

    Raises:
        GridError, SceneError: bad grid or scene (before anything runs or is written).
        ResultsDirectoryError: ``out`` is not a results directory of this scene.
        SchedulerError: the scheduler cannot be reached (nothing written).
    """
    from offshore_crane import scenes
    from offshore_crane.dynamics import resolve_backend
    from offshore_crane.errors import InputError

    if isinstance(scene, (str, os.PathLike)):
        scene = scenes.load_scene(scene)
    if isinstance(grid, (str, os.PathLike)):
        where = os.fspath(grid)
        grid = load_grid(grid)
    if not isinstance(grid, Grid):
        grid = check_grid(scene, grid, where, max_cases)
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise InputError(f"workers = {workers!r}: must be an integer ≥ 1", name="workers")
    given = scheduler if hasattr(scheduler, "submit") else None      # a Client
    scheduler = check_scheduler(None if given is not None else scheduler)
    batch_seconds()                     # a bad OFFSHORE_CRANE_BATCH_SECONDS: refused now
    backend = resolve_backend(backend)
    install_hint("pandas", "A sweep's results table")
    schema = row_schema(grid)
    identify = CaseIds(scene)
    store = ResultsStore.open(out, scene) if out is not None else None
    if scheduler not in (None, "local"):
        handshake(scheduler)            # an address that is no Dask scheduler: nothing written
    client, cluster = given, None
    held: list = []                     # this run's rows: Arrow tables of HELD_ROWS, and
    rows: list = []                     # the dicts since the last one
    info = {"cases": 0, "skipped": 0, "ran": 0, "failed": 0, "backend": "in this process",
            "case_seconds": [], "compute_seconds": []}
    order: dict = {}                    # case id -> its first index in the grid
    earlier: dict = {}                  # case id -> values, of cases found in the store
    try:
        finished: set = set()
        if store is not None:           # the directory is this run's, its manifest on
            store.lock(scene)           # disk, before a cluster starts or a case runs
            finished = store.done()
            store.create(grid, scene_values(scene, grid.keys))
        pending = []
        for i, params in enumerate(grid.cases()):       # made one at a time
            cid = identify(params)
            if cid in order:
                continue                                # the same resolved case again
            order[cid] = i
            if cid in finished:
                earlier[cid] = params
            else:
                pending.append((scene, params, backend, cid))
        info.update(cases=len(order), skipped=len(earlier))
        if scheduler is not None and client is None and pending:
            try:
                client, cluster = connect(scheduler, workers)
            except SchedulerError:
                if store is not None:
                    store.discard_if_new()      # "nothing was run or written" holds
                raise
        if pending:
            warm_up_scene(scene)
            if client is not None and cluster is None and given is None:
                warm_up_workers(client, scene)
        t0 = time.perf_counter()
        n = min(workers or 1, len(pending))        # processes worth starting
        if client is not None:
            results = run_on_dask(pending, client)
            info["backend"] = "on the Dask cluster"
        elif n > 1 and can_fork():
            results = run_on_forks(pending, n)
            info["backend"] = f"on {n} forked workers"
        elif n > 1:
            results = run_on_joblib(pending, n)
            info["backend"] = f"on {n} joblib workers"
        else:
            results = run_in_process(pending)
        bar = shown.bar(len(pending), "case", "sweep", enabled=bool(progress))
        writer = store.writer(schema) if store is not None else None
        try:
            for cid, row, seconds, compute in results:
                if writer is not None:
                    writer.add(row)
                rows.append(row)
                if len(rows) >= HELD_ROWS:      # 1.3 kB a row as Arrow, 7 kB as a dict
                    held.append(results_table(rows, schema))
                    rows = []
                info["ran"] += 1
                info["failed"] += row["status"] != "ok"
                info["case_seconds"].append(seconds)
                info["compute_seconds"].append(compute)
                bar.update()
        finally:
            bar.close()
            if writer is not None:
                writer.flush()          # whatever stops the run, what it computed stays
        if writer is not None:
            writer.finish()             # this run's batches into one file
        info["seconds"] = time.perf_counter() - t0
    finally:
        if store is not None:
            store.release()
        if client is not None and given is None:
            client.close()
        if cluster is not None:
            cluster.close()
    if stats is not None:
        stats.update(info)
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")
    table = pa.concat_tables(held + [results_table(rows, schema)])   # rows of this run
    if earlier:                                                  # and those run before
        before = store.read(set(earlier))
        if before is not None:
            table = pa.concat_tables([table, with_values(conform(before, schema), grid,
                                                         earlier)])
    df = table.to_pandas()
    df.insert(0, "case", df["case_id"].map(order).astype("int64"))
    return df.sort_values("case", kind="stable").reset_index(drop=True)
