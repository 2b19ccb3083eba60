"""Checks at the public boundary: shapes, dtypes and finiteness of user arrays, thread
counts."""

from __future__ import annotations

import math
import os

import numpy as np

from offshore_crane.errors import InputError, TrajectoryError

#: The machine's CPU count: :func:`thread_count` caps thread counts at it.
_CPUS = os.cpu_count() or 1


def as_samples(name: str, x, width: int = 9, finite: bool = True) -> tuple[np.ndarray, bool]:
    """Return ``x`` as a float ``(N, width)`` array and whether it was one sample.

    Args:
        name: Argument name used in messages (``"q"``, ``"qd"``...).
        x: ``(width,)`` or ``(N, width)`` array-like.
        finite: Check here that every value is finite (False: the caller's kernel checks
            it, sample by sample, and reports the same message).

    Raises:
        InputError: non-numeric data, wrong shape, NaN or inf (naming the sample index
            and column).
    """
    if (type(x) is np.ndarray and x.dtype == np.float64 and x.flags.c_contiguous
            and not finite and x.shape[-1:] == (width,)):
        if x.ndim == 2 and x.shape[0] > 0:
            return x, False               # fast path: already what the kernels read
        if x.ndim == 1:
            return x[None], True
    if isinstance(x, np.ma.MaskedArray):
        raise InputError(f"{name} is a masked array: fill or remove the masked samples "
                         "first (e.g. x.filled(...) or x.compressed()), the dynamics needs "
                         "every value", name=name)
    if np.iscomplexobj(x):
        raise InputError(f"{name} has complex values: give real numbers", name=name)
    try:
        arr = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an array of numbers", name=name) from None
    single = arr.ndim == 1
    if single:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != width:
        raise InputError(f"{name} has shape {np.shape(x)}; expected ({width},) or (N, {width})",
                         name=name)
    if arr.shape[0] == 0:
        raise InputError(f"{name} has no samples; give at least one row", name=name)
    if not finite:
        return np.ascontiguousarray(arr), single
    bad = ~np.isfinite(arr)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise InputError(f"{name}[{i}, {j}] is {arr[i, j]} (sample {i}, column {j + 1}); "
                         "every value must be finite", name=name, index=int(i))
    return arr, single


def same_length(**arrays: np.ndarray) -> int:
    """Check that all ``(N, ·)`` arrays share N; return N."""
    lengths = {name: a.shape[0] for name, a in arrays.items()}
    if len(set(lengths.values())) != 1:
        raise InputError("sample counts differ: " + ", ".join(f"{k} has {v}" for k, v in
                                                              lengths.items()),
                         name=next(iter(lengths)))
    return next(iter(lengths.values()))


#: Largest gravity component accepted [m/s²] (1e5 g): no test rig or planet comes near;
#: a larger value is a unit error, and with masses up to 1e12 kg and lengths up to 1e6 m
#: the forces and moments stay far inside float64 (< 1e24 N·m).
MAX_GRAVITY = 1e6
_DEFAULT_GRAVITY: dict = {}


def as_gravity(gravity) -> np.ndarray:
    """Gravity ``(3,)`` [m/s²], finite, each component at most :data:`MAX_GRAVITY`: a new
    read-only float64 array whatever was given (a list, a tuple, a writable or a
    read-only array), so that the compiled kernels see one type and compile once."""
    key = gravity if type(gravity) is tuple else None
    if key is not None and key in _DEFAULT_GRAVITY:
        return _DEFAULT_GRAVITY[key]
    if isinstance(gravity, (str, bytes)) or np.iscomplexobj(gravity):
        raise InputError(f"gravity must be 3 real numbers [m/s²], got {gravity!r}",
                         name="gravity")
    try:
        g = np.array(gravity, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"gravity must be 3 numbers [m/s²], got {gravity!r}",
                         name="gravity") from None
    if g.shape != (3,) or not np.all(np.isfinite(g)):
        raise InputError(f"gravity must be 3 finite numbers [m/s²], got {gravity!r}",
                         name="gravity")
    if np.abs(g).max() > MAX_GRAVITY:
        raise InputError(f"gravity {gravity!r} m/s² exceeds {MAX_GRAVITY:g} m/s² in size: "
                         "give it in m/s² (Earth: 9.81)", name="gravity")
    g.flags.writeable = False
    if key is not None and len(_DEFAULT_GRAVITY) < 16:
        _DEFAULT_GRAVITY[key] = g
    return g


def as_pair(value, name: str, unit: str) -> np.ndarray:
    """``value`` as two finite floats ``(2,)`` (e.g. the sway angles φ1, φ2 [rad]);
    ``name`` and ``unit`` are for the message."""
    try:
        v = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be two numbers [{unit}], got {value!r}",
                         name=name) from None
    if v.shape != (2,) or not np.isfinite(v).all():
        raise InputError(f"{name} must be two finite numbers [{unit}], got {value!r}",
                         name=name)
    return v


#: A time axis is uniform when every step is within this fraction of the mean step: times
#: written with 7 significant digits (a CSV from a spreadsheet) pass; a missing or doubled
#: sample (a step off by 100 %) or a drifting clock does not. A time error of 1e-6 of a
#: step is far below what finite differences or RK4 on that grid can resolve.
UNIFORM_STEP_RTOL = 1e-6


def uniform_step(t: np.ndarray, what: str = "the motion") -> float:
    """The mean step ``h`` [s] of an increasing, uniform time axis ``t`` ``(N,)`` (N ≥ 2,
    finite: the caller checks those); one rule for every path that steps along samples
    (finite differences, the swing's RK4).

    Raises:
        TrajectoryError: a step differs from ``h`` by more than :data:`UNIFORM_STEP_RTOL`
            relative (naming the step, its value and the mean), or ``h ≤ 0``.
    """
    n = len(t)
    d = np.diff(t)
    h = (t[-1] - t[0]) / (n - 1)
    uneven = ~(np.abs(d - h) <= UNIFORM_STEP_RTOL * h)
    if uneven.any():
        k = int(np.argmax(uneven))
        raise TrajectoryError(
            f"the time axis is not uniform: step {k} (t[{k + 1}] - t[{k}] = {float(d[k]):.6g} "
            f"s) differs from the mean step {float(h):.6g} s by more than "
            f"{UNIFORM_STEP_RTOL:g} relative: resample {what} on a uniform grid.",
            name="t", index=k)
    return float(h)


def as_real(name: str, x, error: type = InputError, unit: str = "") -> np.ndarray:
    """``x`` as a float64 array, refusing what a cast would silently change: complex values
    (NumPy drops the imaginary part with a mere warning), masked arrays and non-numbers.

    Args:
        name: The argument's name in messages. error: The exception class raised (a
            subclass of :class:`~offshore_crane.errors.InputError`). unit: e.g. ``"s"``.

    Raises:
        error: complex, masked or non-numeric ``x``.
    """
    units = f" [{unit}]" if unit else ""
    if isinstance(x, np.ma.MaskedArray):
        raise error(f"{name} is a masked array: fill or remove the masked values first",
                    name=name)
    if np.iscomplexobj(x) or isinstance(x, complex):
        raise error(f"{name} has complex values: give real numbers{units}", name=name)
    try:
        return np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise error(f"{name} must be numbers{units}, got {x!r}", name=name) from None


#: Share of the memory available when a record is planned that one record may take;
#: the environment variable ``OFFSHORE_CRANE_MEMORY_LIMIT`` (bytes) sets the limit instead.
MEMORY_SHARE = 0.5


def _human(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if n < 1000 or unit == "TB":
            return f"{n:.3g} {unit}"
        n /= 1000.0
    return f"{n:.3g} TB"


def memory_limit() -> tuple[float, str]:
    """``(bytes, how it was set)``: ``OFFSHORE_CRANE_MEMORY_LIMIT`` when set (not empty),
    else :data:`MEMORY_SHARE` of the memory available now (``MemAvailable``, Linux; the
    physical memory elsewhere).

    Raises:
        InputError: ``OFFSHORE_CRANE_MEMORY_LIMIT`` is not a finite number of bytes > 0
            (``nan`` turned the guard off, ``0`` or a negative limit refused everything).
    """
    import os

    given = os.environ.get("OFFSHORE_CRANE_MEMORY_LIMIT")
    if given:
        try:
            limit = float(given)
        except ValueError:
            limit = math.nan
        if not (math.isfinite(limit) and limit > 0):
            raise InputError(f"OFFSHORE_CRANE_MEMORY_LIMIT = {given!r}: give a number of "
                             "bytes, finite and > 0 (e.g. 8e9), or unset it (half the "
                             "memory available)", name="OFFSHORE_CRANE_MEMORY_LIMIT")
        return limit, "OFFSHORE_CRANE_MEMORY_LIMIT"
    available = None
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    available = float(line.split()[1]) * 1024.0
                    break
    except OSError:
        pass
    if available is None:
        try:
            available = float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
        except (OSError, ValueError, AttributeError):
            return float("inf"), "unknown memory"
    return MEMORY_SHARE * available, f"{MEMORY_SHARE:.0%} of {_human(available)} free"


def check_memory(n_bytes: float, what: str, fix: str, name: str | None = None) -> None:
    """Refuse, before allocating, a record of ``n_bytes`` beyond :func:`memory_limit`.

    Args:
        n_bytes: What the record will take [bytes] (samples × columns × 8).
        what: The record, for the message (``"60000 s at 100 Hz: 6000001 samples"``).
        fix: What to change (naming the flag or argument that made it big).
        name: The argument, for the exception.

    Raises:
        InputError: one line naming the size, the limit and ``fix``.
    """
    limit, how = memory_limit()
    if n_bytes > limit:
        raise InputError(f"{what} needs {_human(n_bytes)} of memory, over the limit "
                         f"{_human(limit)} ({how}): {fix}", name=name)


def not_a_number(value) -> str | None:
    """What keeps a value read from a file (TOML, JSON) from being a finite number, for a
    message (``"is a boolean, not a number"``), or None when it is one."""
    if isinstance(value, bool):
        return "is a boolean, not a number"
    if isinstance(value, str):
        return "is text, not a number"
    if not isinstance(value, (int, float)):
        return f"is a {type(value).__name__}, not a number"
    if not math.isfinite(value):
        return "is not finite"
    return None


def thread_count(threads) -> int:
    """``threads`` checked (a positive integer) and capped at the CPU count."""
    if threads == 1:
        return 1
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 1:
        raise InputError(f"threads must be a positive integer, got {threads!r}", name="threads")
    return int(min(threads, _CPUS))
