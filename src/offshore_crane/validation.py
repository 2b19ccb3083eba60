"""Checks at the public boundary: shapes, dtypes and finiteness of user arrays."""

from __future__ import annotations

import numpy as np

from .errors import InputError


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


def as_gravity(gravity) -> np.ndarray:
    """Gravity ``(3,)`` [m/s²], finite."""
    g = np.asarray(gravity, dtype=float)
    if g.shape != (3,) or not np.all(np.isfinite(g)):
        raise InputError(f"gravity must be 3 finite numbers [m/s²], got {gravity!r}",
                         name="gravity")
    return g
