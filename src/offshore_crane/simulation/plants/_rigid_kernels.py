"""Compiled kernels of the rigid plant (:mod:`.rigid`) for the RK4 driver
(:mod:`offshore_crane.simulation.loop`; imports Numba), over the compiled loop's
equations of motion and laws (:mod:`offshore_crane.simulation.rk4`). ``P``
(:func:`params`): the plant's and the model's packed arrays, gravity, the one zeroed work
buffer (:func:`offshore_crane.simulation.rk4.carve`: the equations' and the law's work
arrays, views made in each kernel rather than handed in P, which the driver passes at
every stage)."""

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
equations, solve, carve, law = rk4.equations, rk4.solve, rk4.carve, rk4.call_law
energy = rk4.energy
inline = njit(inline="always", **c.JIT)


@inline
def _work(P):
    """The equations' and the law's work tuples (``ws``, ``wl``), carved from ``P[7]``
    for the longer arm of the plant's and the model's (their ``prismatic`` flags)."""
    return carve(P[7], max(P[2].shape[0], P[5].shape[0]))
unpack = c.unpack
CT, PDG = codes.COMPUTED_TORQUE, codes.PD_GRAVITY


def _make(stamp):

    @jit
    def rhs(P, i, y, X, dy, aux):
        """(q̇, q̈) into ``dy[:18]``; ``aux[0]`` ok (False: M singular)."""
        if len(stamp) == 0:
            return False
        C = unpack(P[0], P[1], P[2])[0]
        qdd = P[8]
        ws = _work(P)[0]
        equations(C, P[6], y[:9], y[9:18], ws)
        ok = solve(6 + C.n_arm, X, qdd, ws)
        for j in range(9):
            dy[j] = y[9 + j]
            dy[9 + j] = qdd[j]
        aux[0] = 1.0 if ok else 0.0
        return ok

    @jit
    def keep(P, EXTRA, k, y, dy, aux):
        """The energy [J] at ``y`` into ``EXTRA[k, 0]``: kinetic ``½ q̇ᵀ M q̇`` and
        gravitational ``−g · Σ m c``, from the explicit pass that :func:`rhs` at ``y``
        (the step's first stage) left in the work buffer, as the compiled loop records
        it (:func:`offshore_crane.simulation.rk4.run`)."""
        if len(stamp) == 0:
            return
        ws = _work(P)[0]
        EXTRA[k, 0] = energy(ws[2], ws[9], y[9:18], 6 + P[2].shape[0], P[6])

    @jit
    def inverse(P, i, y, qdd, X):
        """The model's inverse dynamics at ``qdd``: the compiled law's computed torque
        with zero gains at the reference (q, q̇, q̈)."""
        if len(stamp) == 0:
            return
        Cc = unpack(P[3], P[4], P[5])[0]
        zero = P[9]
        wl = _work(P)[1]
        law(Cc, P[6], CT, zero, zero, y[:9], y[9:18], y[:9], y[9:18], qdd, X, wl)

    @jit
    def gravity(P, i, y, X):
        if len(stamp) == 0:
            return
        Cc = unpack(P[3], P[4], P[5])[0]
        zero = P[9]
        wl = _work(P)[1]
        law(Cc, P[6], PDG, zero, zero, y[:9], zero, y[:9], zero, zero, X, wl)

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
    work = np.zeros(rk4.work_size(max(a.kane.n_arm, m.kane.n_arm)))
    return (a.flat, a.layout, a.prismatic, m.flat, m.layout, m.prismatic,
            tuple(float(x) for x in plant.g), work, np.zeros(9), np.zeros(9))
