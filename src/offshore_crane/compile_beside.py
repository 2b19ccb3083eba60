"""Compile the big passes a kernel calls by address in helper processes, beside it.

A kernel that calls big compiled passes by address (:mod:`offshore_crane.kernel_calls`)
needs only their symbols to compile; their code must be loaded before the kernel runs.
When neither the kernel nor its passes are in the disk cache, :func:`start` runs the
passes' compile in helper processes (``python -m offshore_crane.compile_beside
module:entry ...``; a helper compiles its passes, writes them to the disk cache and loads
nothing) while this process compiles the kernel; :meth:`Beside.wait` then waits for
them, and the passes load from the cache. Numba compiles under one lock per process:
other processes are what use the other cores (a first ``simulate`` of the rigid robot:
its loop, the explicit pass and the law at once). There is one helper per usable core
at most, the passes dealt longest first (their last compile times,
:func:`offshore_crane.compile_times.seconds`) to the helper with the least to do; as
many helpers as make the whole wait shortest (:func:`plan`: with the kernel's own
compile, more processes than cores share them and slow the kernel down).

Nothing runs beside when there is one usable core, when ``OFFSHORE_CRANE_COMPILE_BESIDE``
is ``0`` (:func:`off`), in a helper, or when a helper cannot be started; a helper that
fails or outlives :data:`TIMEOUT` is stopped with a warning and the passes compile in
this process, as they would without it.
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import tempfile
import warnings

#: The environment variable of the helpers: unset or ``1``, on; any other value (``0``),
#: off.
SWITCH = "OFFSHORE_CRANE_COMPILE_BESIDE"
#: The environment variable that hands a helper this process's ``sys.path``.
PATH = "OFFSHORE_CRANE_COMPILE_BESIDE_PATH"
#: The switch's value in a helper's environment.
HELPER = "helper"
#: The compile time counted for a pass no record knows [s] (a small kernel's).
UNKNOWN = 1.0
#: The longest wait for a helper [s]: far beyond any compile measured (the whole kernel
#: set in one process: about 250 s on a busy 2-core machine); past it the helper is
#: stopped and the passes compile here.
TIMEOUT = 1800.0


class CompileBesideWarning(UserWarning):
    """The helper process failed or timed out; its passes compiled in this process."""


def usable_cores() -> int:
    """The cores this process may run on (its affinity where the OS tells it)."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


class Beside:
    """Helper processes compiling entries (:class:`~offshore_crane.kernel_calls.Entry`);
    each helper's command line names its entries."""

    def __init__(self, processes):
        self._processes = processes                   # [(process, log), ...]

    def wait(self) -> bool:
        """Wait for the helpers (at most :data:`TIMEOUT` in all); True when each
        compiled its entries. A failure is reported as a :class:`CompileBesideWarning`
        naming the entries and the helper's last line of error."""
        import time

        end, ok = time.monotonic() + TIMEOUT, True
        for process, log in self._processes:
            try:
                code = process.wait(timeout=max(end - time.monotonic(), 0.0))
                why = None if code == 0 else f"exit status {code}"
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
                why = f"no answer in {TIMEOUT:.0f} s"
            last = _last_line(log)
            if why is not None:
                ok = False
                names = ", ".join(a.split(":")[-1] for a in process.args[3:])
                warnings.warn(CompileBesideWarning(
                    f"the helper process compiling {names} beside this one failed ({why}"
                    f"{': ' + last if last else ''}): compiling them here instead"),
                    stacklevel=2)
        return ok

    def stop(self) -> None:
        """Stop the helpers now (this process was interrupted)."""
        for process, log in self._processes:
            if process.poll() is None:
                process.kill()
                process.wait()
            _last_line(log)


def _last_line(log) -> str:
    """The last non-empty line a helper wrote (and its log closed)."""
    try:
        log.seek(0)
        lines = [x for x in log.read().decode(errors="replace").splitlines() if x.strip()]
        log.close()
        return lines[-1].strip() if lines else ""
    except (OSError, ValueError):
        return ""


def helping() -> bool:
    """This process is a helper (it compiles and writes, it loads nothing)."""
    return os.environ.get(SWITCH) == HELPER


@contextlib.contextmanager
def off():
    """No helper while the block runs, in this process and those it starts (a caller
    that runs its own processes: ``offshore-crane compile``'s workers)."""
    before = os.environ.get(SWITCH)
    os.environ[SWITCH] = "0"
    try:
        yield
    finally:
        if before is None:
            os.environ.pop(SWITCH, None)
        else:
            os.environ[SWITCH] = before


def start(entries, own: float | None = None) -> Beside | None:
    """Start compiling ``entries`` in helper processes, or None (nothing to compile, the
    switch off, in a helper, one usable core, or no process could start). ``own``: the
    kernel's own compile time [s] (its last, :func:`offshore_crane.compile_times.seconds`;
    None: not known, as many helpers as cores), what :func:`plan` weighs them against."""
    from offshore_crane import compile_times

    cores = usable_cores()
    if os.environ.get(SWITCH, "1") != "1" or cores < 2:
        return None
    entries = [e for e in entries if e.module and e.module != "__main__"]  # importable
    if not entries:
        return None
    shares, loads = plan(entries, cores, [compile_times.seconds(e.kernel()) for e in entries],
                         own)
    # the helper imports the entries' modules from where this process finds them: its
    # sys.path, set once the helper has started (as PYTHONPATH, a folder of the user's
    # could hide a module of the standard library from the interpreter's own start)
    path = [os.path.abspath(p) if p else os.getcwd() for p in sys.path if isinstance(p, str)]
    env = dict(os.environ, **{SWITCH: HELPER, PATH: os.pathsep.join(path)})
    processes = []
    for share in shares:
        log = tempfile.TemporaryFile()
        try:
            processes.append((subprocess.Popen(
                [sys.executable, "-m", __name__, *(f"{e.module}:{e.name}" for e in share)],
                stdin=subprocess.DEVNULL, stdout=log, stderr=log, env=env), log))
        except OSError:
            log.close()
    if not processes:
        return None
    compile_times.beside(loads, cores)
    return Beside(processes)


def deal(entries, n: int, seconds) -> tuple[list[list], list[float]]:
    """``entries`` dealt to at most ``n`` helpers, longest first to the one with the
    least to do, by their compile ``seconds`` (None: unknown, counted as
    :data:`UNKNOWN`): each helper's share (in the entries' order of length) and its load
    [s]."""
    cost = [UNKNOWN if s is None else s for s in seconds]
    shares: list = [[] for _ in range(min(n, len(entries)))]
    loads = [0.0] * len(shares)
    for i in sorted(range(len(entries)), key=lambda i: -cost[i]):
        k = loads.index(min(loads))
        shares[k].append(entries[i])
        loads[k] += cost[i]
    return shares, loads


def plan(entries, cores: int, seconds, own: float | None) -> tuple[list[list], list[float]]:
    """``entries`` dealt (:func:`deal`) to the number of helpers, at most ``cores``, whose
    compiles end first beside the kernel's own of ``own`` [s]
    (:func:`~offshore_crane.compile_times.finish`; the fewer on a tie; ``own`` None:
    ``cores`` helpers). Measured on 2 cores: the rigid robot's first ``simulate`` waited
    16.5 s with 2 helpers beside its loop's 10.5 s compile, which 3 processes slowed down
    (its passes: 6.5 s in all)."""
    from offshore_crane.compile_times import finish

    if own is None:
        return deal(entries, cores, seconds)
    best = None
    for n in range(1, min(cores, len(entries)) + 1):
        shares, loads = deal(entries, n, seconds)
        end = finish([own, *loads], cores)
        if best is None or end < best[0]:
            best = (end, shares, loads)
    return (best[1], best[2]) if best is not None else ([], [])


def main(specs: list[str]) -> int:
    """The helper: import each ``module:entry`` and compile the entry into the disk
    cache (or find it there)."""
    import importlib

    if os.environ.get(PATH):
        sys.path[:] = os.environ[PATH].split(os.pathsep)
    from offshore_crane import kernel_calls

    for spec in specs:
        module, name = spec.split(":")
        importlib.import_module(module)
        kernel_calls.named(name).compile()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
