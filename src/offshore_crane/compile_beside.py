"""Compile the big passes a kernel calls by address in a second process, beside it.

A kernel that calls big compiled passes by address (:mod:`offshore_crane.kernel_calls`)
needs only their symbols to compile; their code must be loaded before the kernel runs.
When neither the kernel nor its passes are in the disk cache, :func:`start` runs the
passes' compile in a helper process (``python -m offshore_crane.compile_beside
module:entry ...``, which writes them to the disk cache) while this process compiles the
kernel; :meth:`Beside.wait` then waits for it, and the passes load from the cache. Numba
compiles under one lock per process: a second process is what uses a second core (a
first ``simulate`` of the rigid robot: its loop and the explicit pass at once).

Nothing runs beside when there is one usable core, when ``OFFSHORE_CRANE_COMPILE_BESIDE``
is ``0`` (the helper sets it for itself), or when the helper cannot be started; a helper
that fails or outlives :data:`TIMEOUT` is stopped with a warning and the passes compile
in this process, as they would without it.
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import tempfile
import warnings

#: The environment variable that turns the helper off (``0``).
SWITCH = "OFFSHORE_CRANE_COMPILE_BESIDE"
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
    """A helper process compiling ``entries`` (:class:`~offshore_crane.kernel_calls.
    Entry`)."""

    def __init__(self, entries, process, log):
        self.entries, self._process, self._log = entries, process, log

    def wait(self) -> bool:
        """Wait for the helper (at most :data:`TIMEOUT`); True when it compiled every
        entry. A failure is reported as a :class:`CompileBesideWarning` naming the
        entries and the helper's last line of error."""
        try:
            code = self._process.wait(timeout=TIMEOUT)
            why = None if code == 0 else f"exit status {code}"
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()
            why = f"no answer in {TIMEOUT:.0f} s"
        last = self._last_line()
        if why is not None:
            names = ", ".join(e.name for e in self.entries)
            warnings.warn(CompileBesideWarning(
                f"the helper process compiling {names} beside this one failed ({why}"
                f"{': ' + last if last else ''}): compiling them here instead"),
                stacklevel=2)
        return why is None

    def stop(self) -> None:
        """Stop the helper now (this process was interrupted)."""
        if self._process.poll() is None:
            self._process.kill()
            self._process.wait()
        self._last_line()

    def _last_line(self) -> str:
        try:
            self._log.seek(0)
            lines = [x for x in self._log.read().decode(errors="replace").splitlines()
                     if x.strip()]
            self._log.close()
            return lines[-1].strip() if lines else ""
        except (OSError, ValueError):
            return ""


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


def start(entries) -> Beside | None:
    """Start compiling ``entries`` in a helper process, or None (nothing to compile, the
    switch off, one usable core, or the process could not start)."""
    if os.environ.get(SWITCH, "1") == "0" or usable_cores() < 2:
        return None
    entries = [e for e in entries if e.module]
    if not entries:
        return None
    env = dict(os.environ, **{SWITCH: "0"})
    log = tempfile.TemporaryFile()
    try:
        process = subprocess.Popen(
            [sys.executable, "-m", __name__, *(f"{e.module}:{e.name}" for e in entries)],
            stdin=subprocess.DEVNULL, stdout=log, stderr=log, env=env)
    except OSError:
        log.close()
        return None
    return Beside(entries, process, log)


def main(specs: list[str]) -> int:
    """The helper: import each ``module:entry`` and compile (or load) the entry."""
    import importlib

    from offshore_crane import kernel_calls

    for spec in specs:
        module, name = spec.split(":")
        importlib.import_module(module)
        kernel_calls.named(name).ensure()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
