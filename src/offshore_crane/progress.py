"""Progress of long jobs and notices of one-off waits: one mechanism for every command.

Every job that can take more than a couple of seconds (a simulation, a hanging-load run,
``size``'s seeds, ``compensate``'s modes, an animation, ``compile``, a sweep, ``excite``'s optimisation,
``identify``'s regressor and consistent lift) reports through :func:`bar` — a
``tqdm`` bar on standard error with rate and ETA, shown only after :data:`DELAY` s so
that short runs print nothing — or :func:`run_polled` for a compiled loop running in a
thread (its counter polled). Bars are off in the library by default (a notebook asks
for them with ``configure(True)``); the command line turns them on when standard error
is a terminal, so piped output stays clean.

:func:`notice` writes a one-line message to whoever listens (:func:`listen`: the command
line prints it on standard error): the kernels' compile notice
(:mod:`offshore_crane.kernel_cache`) uses it, so that the first run says why it waits.
"""

from __future__ import annotations

import contextlib
import sys
import threading

#: A bar appears once its job has run this long [s] (tqdm's ``delay``).
DELAY = 2.0
#: How often a polled job's counter is read [s].
POLL = 0.1
#: How often it is read when there is work to do meanwhile (``run_polled``'s
#: ``meanwhile``) [s].
MEANWHILE_POLL = 0.01

_state = {"enabled": False, "listener": None}
_noticed: set = set()
_lock = threading.Lock()


def configure(enabled: bool | None) -> None:
    """Bars on (True), off (False), or on when standard error is a terminal (None)."""
    if enabled is None:
        enabled = bool(getattr(sys.stderr, "isatty", lambda: False)())
    _state["enabled"] = bool(enabled)


@contextlib.contextmanager
def suspended():
    """No bars inside (a job that is one unit of another's bar: a sweep's case)."""
    before = _state["enabled"]
    _state["enabled"] = False
    try:
        yield
    finally:
        _state["enabled"] = before


def is_enabled() -> bool:
    """Whether :func:`bar` draws."""
    return _state["enabled"]


class _Silent:
    """A bar that draws nothing (bars off)."""

    n = 0

    def update(self, n: int = 1) -> None:
        self.n += n

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def bar(total: int | None, unit: str, desc: str, enabled: bool | None = None):
    """A progress bar (context manager with ``update(n)``): tqdm on standard error with
    rate and ETA when bars are on (``enabled`` overrides :func:`is_enabled`), else a
    silent stand-in. Appears after :data:`DELAY` s; cleared when closed."""
    if not (is_enabled() if enabled is None else enabled):
        return _Silent()
    try:
        import tqdm
    except ImportError:                 # tqdm missing: no bar, never an error
        return _Silent()
    return tqdm.tqdm(total=total, unit=unit, desc=desc, file=sys.stderr, leave=False,
                     delay=DELAY, dynamic_ncols=True)


def run_polled(job, done, total: int, unit: str, desc: str, stop=None, meanwhile=None):
    """Run ``job()`` (a compiled loop that releases the GIL) and return its result; with
    bars on, in a thread while this one shows ``done()`` (its own counter of finished
    units, read every :data:`POLL` s) against ``total``. Exceptions come back here.

    ``stop``: a ``(1,)`` array the loop reads between its steps, ending early when it is
    not zero (its own stop code). Given, the loop runs in a thread whenever this is the
    main thread, bars or not: Python runs the handlers of SIGINT and SIGTERM only in the
    main thread and between its bytecodes, so a loop run here would hold them until it
    ends. The exception they raise sets ``stop``, waits for the loop to return (within
    one of its steps) and is raised: a run stops within :data:`POLL` s and a step. Without
    ``stop``, a Ctrl-C stops waiting (the loop's thread is a daemon: it ends with the
    process).

    ``meanwhile``: called here with ``done()`` every :data:`MEANWHILE_POLL` s while the
    job runs in its thread (work on what the job has finished, on this core); never
    called when the job runs in this thread (its caller then does that work after)."""
    main = threading.current_thread() is threading.main_thread()
    if not (is_enabled() or (stop is not None and main)):
        return job()
    box = in_thread(job, desc)[1]
    try:
        with bar(total, unit, desc) as b:
            finished = False
            while not finished:
                finished = box["done"].wait(POLL if meanwhile is None else MEANWHILE_POLL)
                n = int(done())
                b.update(max(0, min(n, total) - b.n))
                if meanwhile is not None and not finished:
                    meanwhile(n)
    except BaseException:
        halt(stop, box)
        raise
    if "error" in box:
        raise box["error"]
    return box.get("value")


def halt(stop, box) -> None:
    """Ask a compiled loop to end (``stop[0] = 1``, its flag) and wait until its thread
    (:func:`in_thread`'s ``box``) has finished; a no-op without a flag. Waits on the
    box's event, not ``Thread.join``: a join that a signal interrupted marks the thread
    ended while it runs (CPython's bpo-45274), and joins after it return at once."""
    if stop is None:
        return
    stop[0] = 1
    box["done"].wait()


def stop_flag():
    """A fresh ``(1,)`` int64 array of zeros: the flag :func:`run_polled` sets."""
    import numpy as np

    return np.zeros(1, dtype=np.int64)


def in_thread(job, desc: str):
    """Start ``job()`` in a daemon thread (a Ctrl-C in the caller ends the process, not
    waiting for it): ``(thread, box)``; once the thread has ended, ``box`` holds
    ``"value"`` (the result) or ``"error"`` (the exception, for the caller to raise),
    and its event ``box["done"]`` is set (what to wait on)."""
    box: dict = {"done": threading.Event()}

    def target():
        try:
            box["value"] = job()
        except BaseException as exc:     # re-raised in the caller's thread
            box["error"] = exc
        finally:
            box["done"].set()

    worker = threading.Thread(target=target, daemon=True, name=f"offshore-crane {desc}")
    worker.start()
    return worker, box


def filled_rows(Y) -> int:
    """Rows of ``Y`` (NumPy, ``(n, ...)``) a loop has written, when it fills them in order
    over NaN: the counter of :func:`run_polled` for such loops, found by bisection on
    column 0 while the loop runs."""
    import numpy as np

    lo, hi = 0, len(Y)
    while lo < hi:
        mid = (lo + hi) // 2
        if np.isnan(Y[mid, 0]):
            hi = mid
        else:
            lo = mid + 1
    return lo


def listen(listener) -> None:
    """Send :func:`notice` lines to ``listener(text)`` (None: to nobody)."""
    _state["listener"] = listener


def first_time(key) -> bool:
    """True the first time this process asks for ``key`` (any hashable), False after: the
    one "say it once" of the package (notices, cache warnings); thread-safe."""
    with _lock:
        if key in _noticed:
            return False
        _noticed.add(key)
        return True


def notice(key: str, text: str) -> None:
    """Say ``text`` once per process for ``key`` (e.g. "compile"), to the listener."""
    if not first_time(("notice", key)):
        return
    listener = _state["listener"]
    if listener is not None:
        listener(text)
