"""Where the cases run: in this process, on joblib workers, or on a Dask cluster (reached
after the handshake check of :mod:`.scheduler`), the kernels warmed up once per process.
"""

from __future__ import annotations

from offshore_crane.errors import SchedulerError
from offshore_crane.studies.sweep.cases import run_task
from offshore_crane.studies.sweep.grid import install_hint
from offshore_crane.studies.sweep.scheduler import CONNECT_TIMEOUT, handshake


#: Default Dask ``LocalCluster`` size (``--scheduler local``) when ``workers`` is not given.
LOCAL_WORKERS = 2


# =========================================================================== backends
def connect(scheduler: str, workers: int | None = None, timeout: float = CONNECT_TIMEOUT):
    """A ``dask.distributed.Client``: on a new ``LocalCluster`` (``"local"``: processes,
    ``workers`` of one thread each, no dashboard) or connected to ``tcp://HOST:PORT``
    (after a handshake check bounded by ``timeout``).

    Returns:
        ``(client, cluster or None)``.

    Raises:
        SchedulerError: the scheduler cannot be reached within ``timeout`` [s], the
            address answers but not as Dask, or the local cluster does not start.
    """
    distributed = install_hint("distributed", "--scheduler (Dask)")
    import logging

    if scheduler != "local":
        handshake(scheduler, timeout)
    try:
        if scheduler == "local":
            # no dashboard; the scheduler's own HTTP routes (health) still listen, on
            # a free port of this machine only, not on 8787 (a second sweep warned that
            # "Port 8787 is already in use")
            cluster = distributed.LocalCluster(n_workers=workers or LOCAL_WORKERS,
                                               threads_per_worker=1, processes=True,
                                               dashboard_address=None,
                                               scheduler_kwargs={
                                                   "dashboard_address": "127.0.0.1:0"})
            return distributed.Client(cluster), cluster
        logging.getLogger("distributed").setLevel(logging.CRITICAL)
        return distributed.Client(scheduler, timeout=f"{timeout}s"), None
    except (OSError, TimeoutError) as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise SchedulerError(f"--scheduler {scheduler}: cannot reach the Dask scheduler "
                             f"within {timeout:g} s ({reason}): start it (dask scheduler) or "
                             "check the address; nothing was run or written",
                             address=scheduler, reason=reason) from None


def run_in_process(payloads):
    for p in payloads:
        yield run_task(p)


#: Most cases a forked worker receives at a time: a few, so that dispatching costs little
#: against a case (~5 ms); fewer when the run has few cases, so that every worker gets
#: at least 4 tasks and the last ones balance between them.
FORK_BATCH = 8


def can_fork() -> bool:
    """True where local workers are forked from the sweep's process (Linux): they start in
    milliseconds with its modules and compiled kernels already loaded."""
    import multiprocessing
    import sys

    return sys.platform == "linux" and "fork" in multiprocessing.get_all_start_methods()


def run_batch(payloads: list) -> list:
    """:func:`~offshore_crane.studies.sweep.cases.run_task` of each payload, in order."""
    return [run_task(p) for p in payloads]


def _forked_worker() -> None:
    """A forked worker's start: Ctrl-C is the sweep's to handle (the terminal sends it to
    the whole process group); SIGTERM (the sweep terminating its pool) ends the worker
    quietly, not through the handler it inherited from the command line (which raised an
    exception and printed a traceback); the orphan watchdog runs."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    start_watchdog()


def run_on_forks(payloads, workers: int):
    """The payloads on ``workers`` processes forked from this one, up to
    :data:`FORK_BATCH` at a time; results as they finish. The pool lives for this run only (forking costs
    milliseconds: there is nothing to keep warm); stopped early (an error, Ctrl-C), its
    workers are terminated."""
    import multiprocessing

    size = max(1, min(FORK_BATCH, len(payloads) // (4 * workers)))
    chunks = [payloads[i:i + size] for i in range(0, len(payloads), size)]
    pool = multiprocessing.get_context("fork").Pool(workers, initializer=_forked_worker)
    finished = False
    try:
        for batch in pool.imap_unordered(run_batch, chunks):
            yield from batch
        finished = True
    finally:
        if finished:
            pool.close()
        else:
            pool.terminate()
        pool.join()


def run_on_joblib(payloads, workers: int):
    joblib = install_hint("joblib", "--workers (parallel cases)")
    parallel = joblib.Parallel(n_jobs=workers, backend="loky",
                               return_as="generator_unordered", batch_size=1)
    yield from parallel(joblib.delayed(run_in_worker)(p) for p in payloads)


def shutdown_pool() -> None:
    """Stop joblib's worker pool if this process started one (for a program about to
    end: the pool is otherwise kept for the next sweep and joined at the interpreter's
    exit, where a Ctrl-C printed an "Exception ignored" traceback). Imports nothing."""
    import sys

    module = sys.modules.get("joblib.externals.loky.reusable_executor")
    executor = getattr(module, "_executor", None) if module is not None else None
    if executor is not None:
        executor.shutdown(wait=True)


#: How often a joblib worker looks whether the sweep that started it still lives [s].
ORPHAN_POLL = 0.5
_watching: list = []


def run_in_worker(payload):
    """:func:`~offshore_crane.studies.sweep.cases.run_task` on a joblib worker, which
    first starts a watchdog: when the sweep process dies (SIGKILL leaves no time to stop
    the pool), the worker is re-parented and exits within :data:`ORPHAN_POLL` s instead
    of idling for loky's 300 s with ~180 MB each. Workers only compute; the sweep's
    process writes every row, so nothing is half-written by the exit."""
    start_watchdog()
    return run_task(payload)


def start_watchdog() -> None:
    """In a worker: a thread that exits the process within :data:`ORPHAN_POLL` s of its
    parent's death (once per process)."""
    if not _watching:
        import os
        import threading
        import time

        parent = os.getppid()

        def watch():
            while os.getppid() == parent:
                time.sleep(ORPHAN_POLL)
            os._exit(1)

        _watching.append(threading.Thread(target=watch, daemon=True,
                                          name="offshore-crane orphan watchdog"))
        _watching[0].start()


def run_on_dask(payloads, client):
    distributed = install_hint("distributed", "--scheduler (Dask)")
    if not payloads:
        return
    futures = client.map(run_task, payloads, pure=False)
    try:
        for _, result in distributed.as_completed(futures, with_results=True):
            yield result
    finally:
        client.cancel(futures)


def warm_up_scene(scene) -> None:
    """Compile or load, once in this process, the kernels this sweep's cases use: the
    inverse dynamics of the scene's first method (and Kane's, which a simulated case
    uses for its condition numbers; not the RNEA path's Pinocchio unless the scene asks
    for it), the hanging load's kernels, the simulation loops for a scene with
    ``[control]`` -- each by its column's own ``warm_up``."""
    from offshore_crane import scenes
    from offshore_crane.dynamics import numba_available, warm_up

    if not numba_available():
        return
    from offshore_crane.dynamics.cable import warm_up as warm_up_cable

    robot = scenes.load_robot(scene).without_hanging_payload()
    warm_up(robot, methods=(scene.methods[0], "kane"), forward=False)
    warm_up_cable()            # any case may hang its payload (a grid's cable_length)
    if scene.simulated:
        from offshore_crane.simulation.rigid import warm_up as warm_up_simulation

        warm_up_simulation()


def warm_up_workers(client, scene) -> None:
    """Load (or compile) the kernels on a remote cluster's workers one at a time, so
    that workers sharing a cache never compile it at once (the first compiles, the others
    load)."""
    for address in sorted(client.scheduler_info()["workers"]):
        client.run(warm_up_scene, scene, workers=[address])
