"""Rates and accelerations of sampled motions by central finite differences (orders 2, 4, 6) on
uniform time axes.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from offshore_crane.errors import TrajectoryError
from offshore_crane.validation import uniform_step


FD_ORDERS = (2, 4, 6)


@lru_cache(maxsize=64)
def _stencil_weights(offsets: tuple, deriv: int) -> tuple:
    """Finite-difference weights of the ``deriv``-th derivative on integer ``offsets``.

    Solves the Vandermonde system ``sum_j w_j s_j**k = deriv! * (k == deriv)`` for
    ``k = 0 .. M-1`` exactly in rational arithmetic (Gauss-Jordan elimination), so the
    weights are correctly rounded and annihilate constants to round-off. Divide by
    ``h**deriv`` to use them on a grid of step ``h``.

    Args:
        offsets: ``M`` distinct integer offsets, in units of the grid step.
        deriv: Order of the derivative, ``0 <= deriv < M``.

    Returns:
        ``M`` float weights, in the order of ``offsets``.
    """
    from fractions import Fraction  # imported here: only needed when differentiating

    m = len(offsets)
    rhs = [Fraction(math.factorial(deriv) if k == deriv else 0) for k in range(m)]
    a = [[Fraction(s) ** k for s in offsets] + [rhs[k]] for k in range(m)]  # augmented
    for col in range(m):
        pivot = next(r for r in range(col, m) if a[r][col] != 0)
        a[col], a[pivot] = a[pivot], a[col]
        inv = 1 / a[col][col]
        a[col] = [x * inv for x in a[col]]
        for r in range(m):
            if r != col and a[r][col] != 0:
                f = a[r][col]
                a[r] = [x - f * y for x, y in zip(a[r], a[col])]
    return tuple(float(a[r][m]) for r in range(m))


def _check_time_axis(t: np.ndarray, what: str) -> None:
    """Raise TrajectoryError unless ``t`` is finite and strictly increasing."""
    finite = np.isfinite(t)
    if not finite.all():
        k = int(np.argmin(finite))
        raise TrajectoryError(
            f"{what}: t[{k}] = {float(t[k])!r} is not finite: give finite times [s].",
            name="t", index=k)
    dt = np.diff(t)
    bad = dt <= 0.0
    if bad.any():
        k = int(np.argmax(bad)) + 1
        raise TrajectoryError(
            f"{what}: time is not strictly increasing at sample {k} "
            f"(t[{k - 1}] = {float(t[k - 1])!r} s, t[{k}] = {float(t[k])!r} s): sort the "
            "samples and remove duplicates.", name="t", index=k)


def finite_difference(t, q, order: int = 4):
    """First and second time derivatives of sampled data by finite differences.

    Interior samples use the central stencil of ``order + 1`` points (offsets
    ``-order/2 .. order/2``). The ``order/2`` samples at each end, where that stencil does
    not fit, use one-sided stencils on the first (last) ``order + 1`` samples for ``qd`` and
    ``order + 2`` samples for ``qdd``, so every sample has a truncation error of
    ``O(h**order)``. Weights come from a Vandermonde solve (as in Fornberg's method),
    computed once per stencil shape.

    Args:
        t: ``(N,)`` time [s]; strictly increasing and uniform (every step within
            ``1e-6`` of the mean step, relative).
        q: ``(N,)`` or ``(N, m)`` samples [any unit u].
        order: Order of accuracy, 2, 4 or 6.

    Returns:
        ``(qd, qdd)``, both of the shape of ``q``, in [u/s] and [u/s²].

    Raises:
        TrajectoryError: bad ``order``; ``t`` not 1-D, not finite, not strictly increasing
            or not uniform (``index`` names the first offending sample or step); ``q`` of
            the wrong shape or not finite; fewer than ``order + 2`` samples.
    """
    if isinstance(order, bool) or order not in FD_ORDERS:
        raise TrajectoryError(
            f"finite-difference order must be one of {FD_ORDERS}, got {order!r}.", name="order")
    t = np.asarray(t, dtype=float)
    q = np.asarray(q, dtype=float)
    if t.ndim != 1:
        raise TrajectoryError(f"t must be 1-D (N,), got shape {t.shape}.", name="t")
    n = t.shape[0]
    if q.ndim not in (1, 2) or q.shape[0] != n:
        raise TrajectoryError(
            f"q must have shape ({n},) or ({n}, m) to match t, got {q.shape}.", name="q")
    need = order + 2
    if n < need:
        raise TrajectoryError(
            f"finite differences of order {order} need at least {need} samples, got {n}: "
            "give a longer trajectory or a lower order.", name="t")
    _check_time_axis(t, "finite_difference")
    finite = np.isfinite(q)
    if not finite.all():
        k = int(np.argmin(finite.reshape(n, -1).all(axis=1)))
        raise TrajectoryError(
            f"q is not finite at sample {k}: give finite samples.", name="q", index=k)

    h = uniform_step(t, "the trajectory")  # mean step [s]

    half = order // 2
    derivatives = []
    for deriv, width in ((1, order + 1), (2, order + 2)):
        out = np.empty_like(q)
        # Interior: central stencil, one shifted slice per tap.
        central = tuple(range(-half, half + 1))
        acc = np.zeros_like(q[half:n - half])
        for s, w in zip(central, _stencil_weights(central, deriv)):
            acc += w * q[half + s:n - half + s]
        out[half:n - half] = acc
        # Ends: one-sided stencils on the first / last `width` samples, as small matrices.
        left = np.array([_stencil_weights(tuple(range(-i, width - i)), deriv)
                         for i in range(half)])  # (half, width)
        right = np.array([_stencil_weights(tuple(range(-(width - 1 - i), i + 1)), deriv)
                          for i in range(half - 1, -1, -1)])  # rows: samples n-half .. n-1
        out[:half] = np.tensordot(left, q[:width], axes=1)
        out[n - half:] = np.tensordot(right, q[n - width:], axes=1)
        derivatives.append(out / h**deriv)
    return derivatives[0], derivatives[1]
