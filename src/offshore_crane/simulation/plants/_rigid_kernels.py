"""Compiled kernels of the rigid plant (:mod:`.rigid`) for the RK4 driver
(:mod:`offshore_crane.simulation.loop`; imports Numba), over the compiled loop's
equations of motion and laws (:mod:`offshore_crane.simulation.rk4`). ``P``
(:func:`params`): the plant's and the model's packed arrays, gravity, the equations' and
the law's workspaces."""

from __future__ import annotations

import hashlib
import inspect

import numpy as np

from offshore_crane.dynamics import compiled as c
from offshore_crane.kernel_cache import njit
from offshore_crane.simulation.plants import shared_kernels as shared
from offshore_crane.simulation import rk4
from offshore_crane.simulation.laws import codes

jit = njit(**c.JIT)
accel, law = rk4.accel, rk4.law
unpack = c.unpack
CT, PDG = codes.COMPUTED_TORQUE, codes.PD_GRAVITY


def _make(stamp):

    @jit
    def rhs(P, i, y, X, dy, aux):
        """(q̇, q̈) into ``dy[:18]``; ``aux[0]`` ok (False: M singular)."""
        if len(stamp) == 0:
            return False
        C = unpack(P[0], P[1], P[2])[0]
        qdd = P[9]
        ok = accel(C, P[6], 6 + C.n_arm, y[:9], y[9:18], X, qdd, P[7])
        for j in range(9):
            dy[j] = y[9 + j]
            dy[9 + j] = qdd[j]
        aux[0] = 1.0 if ok else 0.0
        return ok

    @jit
    def keep(P, EXTRA, k, y, dy, aux):
        if len(stamp) == 0:
            return

    @jit
    def inverse(P, i, y, qdd, X):
        """The model's inverse dynamics at ``qdd``: the compiled law's computed torque
        with zero gains at the reference (q, q̇, q̈)."""
        if len(stamp) == 0:
            return
        Cc = unpack(P[3], P[4], P[5])[0]
        zero = P[10]
        law(Cc, P[6], CT, zero, zero, y[:9], y[9:18], y[:9], y[9:18], qdd, X, P[8])

    @jit
    def gravity(P, i, y, X):
        if len(stamp) == 0:
            return
        Cc = unpack(P[3], P[4], P[5])[0]
        zero = P[10]
        law(Cc, P[6], PDG, zero, zero, y[:9], zero, y[:9], zero, zero, X, P[8])

    return rhs, keep, inverse, gravity


#: What these kernels' disk cache is keyed by: the formulas' hash and the text of the
#: rigid loop's kernels they call (Numba's cache checks only a function's own file, so a
#: callee edited elsewhere would otherwise be linked stale).
STAMP = c.STAMP + hashlib.sha256((inspect.getsource(rk4) + inspect.getsource(shared)
                                  ).encode()).hexdigest()
rhs, keep, inverse, gravity = _make(STAMP)
check, coords, payload, arm_tip = shared.check, shared.coords, shared.payload, shared.arm_tip


def params(plant) -> tuple:
    """``P`` of a :class:`~offshore_crane.simulation.plants.RigidPlant`."""
    from offshore_crane.dynamics.constants import robot_arrays

    a, m = robot_arrays(plant.robot), robot_arrays(plant.model)
    ws, wl = rk4.workspaces(max(a.kane.n_arm, m.kane.n_arm))
    return (a.flat, a.layout, a.prismatic, m.flat, m.layout, m.prismatic,
            tuple(float(x) for x in plant.g), ws, wl, np.zeros(9), np.zeros(9))
