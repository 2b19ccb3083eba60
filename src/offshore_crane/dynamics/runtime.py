"""Where the dynamics run: the compiled backend's availability and kernels, the choice of
backend, and the split of samples into contiguous blocks run in threads.

Shared by inverse dynamics (:mod:`.inverse`), forward dynamics (:mod:`.forward`), the
hanging load (:mod:`.cable`) and the simulation loops.
"""

from __future__ import annotations

import contextlib
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from offshore_crane.errors import BackendMissingError, InputError
from offshore_crane.robot.kinematics import workspace as ws

BACKENDS = ("auto", "numpy", "numba")


def numba_available() -> bool:
    """True when Numba is installed (looked up once, without importing it)."""
    if not _NUMBA:
        import importlib.util

        _NUMBA.append(importlib.util.find_spec("numba") is not None)
    return _NUMBA[0]


_NUMBA: list = []


def compiled_kernels():
    """The compiled kernels module (:mod:`.compiled`), imported on first use.

    Raises:
        BackendMissingError: Numba is not installed.
    """
    if not _COMPILED:
        if not numba_available():
            raise BackendMissingError("backend='numba' needs Numba: pip install numba",
                                      package="numba")
        from offshore_crane.dynamics import compiled

        _COMPILED.append(compiled)
    return _COMPILED[0]


_COMPILED: list = []


def blocks(N: int, threads: int) -> list[tuple[int, int]]:
    """``min(threads, N)`` contiguous ``(start, stop)`` ranges covering samples 0..N-1."""
    edges = np.linspace(0, N, min(threads, N) + 1).astype(int)
    return list(zip(edges[:-1], edges[1:]))


#: Samples a compiled pass takes in one call (:func:`run_threaded`): ~0.1 s of the
#: explicit pass's 2-5 µs a sample (Kane's fused one: 1.5 µs), so that a signal's handler,
#: which Python runs only between calls, acts within that on a long record; a call's
#: overhead (~10 µs) is then < 1e-4 of its work.
BLOCK = 1 << 15


def run_threaded(run, N: int, threads: int) -> np.ndarray:
    """Run ``run(start, stop, health)`` on blocks of at most :data:`BLOCK` samples,
    in ``threads`` threads; the merged health record (every sample is computed on its
    own: the same numbers however the samples are split). An exception (a signal's)
    cancels the blocks not begun and waits for those running."""
    ranges = [(a, min(a + BLOCK, b)) for a0, b in blocks(N, threads)
              for a in range(a0, b, BLOCK)]
    if len(ranges) <= 1:
        health = ws.new_health()
        run(0, N, health)
        return health
    records = [ws.new_health() for _ in ranges]
    if threads == 1:
        for (a, b), health in zip(ranges, records):
            run(a, b, health)
        return ws.merge(records)
    pool = ThreadPoolExecutor(threads)
    try:
        list(pool.map(lambda r: run(*r[0], r[1]), zip(ranges, records)))
    finally:
        pool.shutdown(cancel_futures=True)
    return ws.merge(records)


def quick_backend(n: int) -> str:
    """The backend that finishes ``n`` samples first in a process that may not have loaded
    Numba yet: ``"numba"`` when it is loaded already or ``n ≥`` :data:`NUMBA_MIN` (and
    installed), else ``"numpy"``. For one-off evaluations (a command's run, a workspace
    check); long-lived callers keep ``"auto"``."""
    import sys

    from offshore_crane.conventions import NUMBA_MIN

    if "numba" in sys.modules or n >= NUMBA_MIN:
        return "numba" if numba_available() else "numpy"
    return "numpy"


def resolve_backend(backend: str) -> str:
    """``"auto"`` → ``"numba"`` (installed: it is a dependency) else ``"numpy"``."""
    if backend not in BACKENDS:
        raise InputError(f"unknown backend {backend!r}: use one of {', '.join(BACKENDS)}",
                         name="backend")
    if backend == "auto":
        return "numba" if numba_available() else "numpy"
    return backend



@contextlib.contextmanager
def one_blas_thread():
    """Inside: NumPy's and SciPy's BLAS and LAPACK on one thread (threadpoolctl; without
    it, nothing changes). For loops of many small factorisations (identification's
    regressors, QR and SVD of a few thousand rows by 100 columns): on 2 busy cores
    OpenBLAS's threads made each such call 50-100× slower than one thread (a 2700 × 100
    SVD: 0.9 s against 8 ms, measured on this project's machine), and on an idle machine
    they gain nothing at these sizes. SciPy is imported first so that its own BLAS is
    limited too (threadpoolctl limits the libraries loaded when it is entered)."""
    import importlib
    import importlib.util

    if importlib.util.find_spec("scipy") is not None:
        importlib.import_module("scipy.linalg")        # loads SciPy's BLAS before the limit
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:                 # threadpoolctl missing: threads as they are
        yield
        return
    with threadpool_limits(limits=1, user_api="blas"):
        yield
