"""How long a cold compile of a kernel took, so that the next wait for it can be told
ahead (:mod:`offshore_crane.kernel_cache` says it before the first kernel of a process
compiles).

Each compile that starts in a process from nothing cached is timed from the first
kernel that misses the cache to the moment that kernel (the outermost one: it links what
it calls) is saved, and kept under its name in this machine's record,
``$XDG_CACHE_HOME/offshore-crane/compile_times.json`` (``~/.cache`` by default). A
machine without a record of a kernel falls back to the package's own table,
``compile_times.json`` beside this module, which ``benchmarks/compile.py --save`` writes
from its cold compiles on a fresh copy (the machine and date it was measured on come
with it). Neither is needed: without them the notice gives no time. A record that cannot
be read or written is ignored (it only ever shortens a message).
"""

from __future__ import annotations

import json
import os
import threading
import time
from pathlib import Path

#: The package's table (written by ``benchmarks/compile.py --save``).
SHIPPED = Path(__file__).resolve().parent / "compile_times.json"
#: Compiles in progress: ``{thread id: (kernel name, start [s])}``.
_OPEN: dict = {}
_lock = threading.Lock()


def record_path() -> Path:
    """This machine's record (``$XDG_CACHE_HOME/offshore-crane/compile_times.json``)."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "offshore-crane" / "compile_times.json"


def _read(path: Path) -> dict:
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
        return data if isinstance(data, dict) else {}
    except (OSError, ValueError):
        return {}


def _wait(seconds) -> str | None:
    """``seconds`` [s] of a record in words, or None when it is not a duration."""
    if isinstance(seconds, bool) or not isinstance(seconds, (int, float)) or \
            not seconds >= 0.0:
        return None
    return f"about {seconds:.0f} s" if seconds >= 1.0 else "under a second"


def _lookup(name: str) -> tuple[float, str] | None:
    """The last cold compile of kernel ``name`` [s] and where it comes from, in words to
    follow the wait (:func:`estimate`): this machine's record, else the package's table;
    for an instance of a template neither knows (a law's loop on a plant), the slowest
    instance recorded of the same template on the same plant (:func:`_kin`); None when
    nothing is known."""
    mine = _read(record_path()).get("kernels", {})
    if _wait(mine.get(name)) is not None:
        return float(mine[name]), ", as long as its last compile on this machine"
    table = _read(SHIPPED)
    theirs = table.get("kernels", {})
    where = table.get("machine", "the benchmark's machine")
    if _wait(theirs.get(name)) is not None:
        return float(theirs[name]), (f" on {where} (benchmarks/compile.py, "
                                     f"{table.get('date', '?')})")
    kin = _kin(name, {**theirs, **mine})
    if kin is not None:
        return kin, (", as long as another law's loop on this plant (none of this one is "
                     "recorded)")
    return None


def _kin(name: str, kernels: dict) -> float | None:
    """The slowest recorded compile [s] of another instance of ``name``'s template on the
    same plant (``"<template> [<plant> <parts>]"``: the first word of the instance), or
    None (not an instance, or none recorded)."""
    if not isinstance(kernels, dict) or not name.endswith("]") or " [" not in name:
        return None
    template, instance = name[:-1].split(" [", 1)
    prefix = f"{template} [{instance.split(' ', 1)[0]} "
    times = [float(v) for k, v in kernels.items() if isinstance(k, str)
             and k.startswith(prefix) and _wait(v) is not None]
    return max(times) if times else None


def seconds(name: str) -> float | None:
    """The last cold compile of kernel ``name`` [s] (:func:`_lookup`), or None."""
    found = _lookup(name)
    return None if found is None else found[0]


def kernel_name(f) -> str:
    """A kernel's name in the compile-time record: its module and qualified name, and
    the instance of a template (:data:`INSTANCE`)."""
    instance = f.__globals__.get(INSTANCE)
    name = getattr(f, "__template__", None) or f.__qualname__   # an instance: its template's
    return f"{f.__module__}.{name}" + (f" [{instance}]" if instance else "")


#: The name, in an instantiated template's namespace, of what tells its instance apart
#: (:func:`offshore_crane.simulation.loop.instantiate`: the plant and the law): one text,
#: many compiled loops, each with a compile time of its own.
INSTANCE = "__kernel_instance__"


def estimate(name: str, beside=None) -> str | None:
    """How long the cold compile of kernel ``name`` is expected to take, in words
    (``"about 26 s, as long as its last compile on this machine"``), or None when
    neither this machine's record nor the package's table knows it.

    Args:
        beside: ``(loads, cores)``: helper processes compile what the kernel calls beside
            it (:mod:`offshore_crane.compile_beside`), each ``loads[i]`` [s] of work, on
            ``cores`` cores: the wait is when the last of them ends, the cores shared
            fairly (:func:`finish`).
    """
    found = _lookup(name)
    if found is None:
        return None
    own, where = found
    if not (beside and beside[0]):
        return f"{_wait(own)}{where}"
    loads, cores = beside
    wait = finish([own, *loads], max(cores, 1))
    helpers = f"{len(loads)} helper process{'es' if len(loads) > 1 else ''}"
    return (f"{_wait(wait)} with {helpers} compiling what it calls beside it (the "
            "last compiles recorded: this machine's, else benchmarks/compile.py's)")


def finish(works, cores: int) -> float:
    """When the last of processes needing ``works`` [s] of one core each ends, started
    together on ``cores`` cores shared fairly (each runs at ``min(1, cores / running)``
    of a core) [s]."""
    left, t = sorted(w for w in works if w > 0), 0.0
    while left:
        rate = min(1.0, cores / len(left))
        t += left[0] / rate
        left = [w - left[0] for w in left[1:]]
    return t


def started(name: str) -> str | None:
    """A kernel missed the cache: if no compile is open in this thread, open one under
    ``name`` (the outermost kernel) and return its :func:`estimate`; else None."""
    key = threading.get_ident()
    planned, _BESIDE.value = getattr(_BESIDE, "value", None), None
    with _lock:
        if key in _OPEN:
            return None
        _OPEN[key] = (name, time.perf_counter())
    return estimate(name, planned)


#: Per thread: the helpers of the compile about to open (:func:`beside`).
_BESIDE = threading.local()


def beside(loads, cores: int) -> None:
    """Helper processes compile beside the compile about to open in this thread, each
    ``loads[i]`` [s] of work, on ``cores`` cores: its :func:`started` tells the wait
    with them (:func:`estimate`)."""
    _BESIDE.value = (tuple(loads), cores)


def saved(name: str) -> None:
    """Kernel ``name`` was compiled and saved: if it is the one that opened this thread's
    compile, record how long the compile took in this machine's record."""
    key = threading.get_ident()
    with _lock:
        opened = _OPEN.get(key)
        if opened is None or opened[0] != name:
            return
        del _OPEN[key]
    remember(name, time.perf_counter() - opened[1], record_path())


def remember(name: str, seconds: float, path: Path) -> None:
    """Write ``name``'s compile time [s] into the record at ``path`` (the output module's
    atomic write; a failure is ignored: the record only shortens a message)."""
    from offshore_crane.errors import OffshoreCraneError
    from offshore_crane.io import write_text

    data = _read(path)
    data.setdefault("kernels", {})[name] = round(float(seconds), 1)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_text(str(path), json.dumps(data, indent=1, sort_keys=True))
    except (OSError, OffshoreCraneError):
        pass
