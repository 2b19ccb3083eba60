import contextlib
import time

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.motion import trajectories


@pytest.fixture(scope="session")
def robot():
    return oc.load_robot()


@pytest.fixture(scope="session")
def table1():
    """Default Table 1 span: t (3142,), q, qd, qdd (3142, 9)."""
    t = trajectories.time_grid()
    return (t, *trajectories.table1(t))


def package_sources(package) -> list:
    """The package's source files under ``package`` (a Path), not the generated kernels
    of its caches (``__pycache__``)."""
    return [p for p in sorted(package.rglob("*.py")) if "__pycache__" not in p.parts]


def relative_error(X, Y) -> float:
    """max |X - Y| / max |Y|."""
    return float(np.abs(np.asarray(X) - np.asarray(Y)).max() / np.abs(np.asarray(Y)).max())


@contextlib.contextmanager
def deadline(seconds: float):
    """Fail instead of hanging: SIGALRM after ``seconds`` raises TimeoutError in the main
    thread (a blocking ``open`` of a FIFO or a wait on a socket is interrupted too; a
    forked worker inherits no timer). For tests of what must not hang, as pytest has no
    timeout of its own here."""
    import signal

    def expired(signum, frame):
        raise TimeoutError(f"still running after {seconds} s")

    previous = signal.signal(signal.SIGALRM, expired)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


_COMPILE: dict = {}


def pytest_sessionstart(session):
    """Compile (or load) the Numba kernels once, timed: on a fresh clone (CI) this is the
    cold compile of everything the tests need, reported at the end of the run. The
    controlling process compiles the groups in parallel processes (``offshore-crane
    compile``'s way); xdist's workers then load them."""
    from offshore_crane.cli.compile import compile_all

    say = session.config.pluginmanager.get_plugin("terminalreporter")
    if say is not None:
        say.write_line("Numba kernels: loading them, or compiling them first on a fresh "
                       "clone (minutes on a cold cache) ...", flush=True)
    t0 = time.perf_counter()
    worker = hasattr(session.config, "workerinput")
    _COMPILE["parts"] = compile_all(jobs=1 if worker else None)
    _COMPILE["total"] = time.perf_counter() - t0
    if say is not None:
        say.write_line(f"Numba kernels ready in {_COMPILE['total']:.1f} s", flush=True)


def pytest_terminal_summary(terminalreporter):
    if _COMPILE:
        parts = ", ".join(f"{name} {s:.1f} s" for name, s in _COMPILE["parts"])
        terminalreporter.write_line(f"Numba kernels compiled or loaded in "
                                    f"{_COMPILE['total']:.1f} s ({parts})")
