"""Classical fourth-order Runge–Kutta, written once: the stage and the combination of the
Butcher tableau (0, ½, ½, 1; ⅙, ⅓, ⅓, ⅙), compiled with Numba and inlined into the compiled
loops (the rigid robot's simulation, the swing under a prescribed motion), and driven
from Python by :func:`rk4_step` (a Python control law, the hanging-load simulation).

Every loop keeps its own state layout and stage evaluations; none spells out the
arithmetic below, so all of them round alike. The reference (``reference/cable.py``)
keeps its own, deliberately independent, RK4.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
from offshore_crane.kernel_cache import njit

from offshore_crane.dynamics.jit import JIT


@njit(inline="always", **JIT)
def rk4_stage(y, k, a, out):
    """A stage's state ``out = y + a k`` (``a`` = h/2 or h [s]); ``(n,)`` arrays."""
    for j in range(y.shape[0]):
        out[j] = y[j] + a * k[j]


@njit(inline="always", **JIT)
def rk4_combine(y, h, k1, k2, k3, k4):
    """The step in place: ``y += h/6 (k1 + 2 k2 + 2 k3 + k4)`` (``h`` [s]); ``(n,)``."""
    for j in range(y.shape[0]):
        y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])


def rk4_step(f: Callable[[int, np.ndarray], np.ndarray], i: int, y: np.ndarray,
             k1: np.ndarray, h: float) -> np.ndarray:
    """One RK4 step of ``dy/dt = f(i, y)`` from ``y`` ``(n,)`` at stage-grid index ``i``
    (the step's start; ``i + 1`` its middle, ``i + 2`` its end, on a grid of half steps)
    with ``k1 = f(i, y)`` already evaluated (a driver records it); ``h`` [s]. Returns the
    new state (``y`` is not changed)."""
    stage = np.empty_like(y)
    rk4_stage(y, k1, 0.5 * h, stage)
    k2 = f(i + 1, stage)
    stage = np.empty_like(y)
    rk4_stage(y, k2, 0.5 * h, stage)
    k3 = f(i + 1, stage)
    stage = np.empty_like(y)
    rk4_stage(y, k3, h, stage)
    k4 = f(i + 2, stage)
    out = y.copy()
    rk4_combine(out, h, k1, k2, k3, k4)
    return out
