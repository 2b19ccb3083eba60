"""Compiled kernels of the hanging plant (:mod:`.hanging`) for the RK4 driver
(:mod:`offshore_crane.simulation.loop`; imports Numba). ``P`` (:func:`params`): the
plant's and the model's packed arrays with the cable (their sway damping and drag), the
legs' arrays, gravity and scratch. Closed over the formulas' hash (a formula edited
rebuilds them)."""

from __future__ import annotations

import hashlib
import inspect

import numpy as np

from offshore_crane import kernel_calls
from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics.cable import kernels as ck
from offshore_crane.dynamics.cable.work import carve_tension
from offshore_crane.kernel_cache import njit
from offshore_crane.simulation.plants import shared_kernels as shared
from offshore_crane.stops import CODES

OK, _, SINGULAR, DIVERGED, _, _ = CODES
jit = njit(**c.LEAN)
#: The plant's Kane passes, called by address: each loop (one per law) compiles its own
#: code only (:mod:`offshore_crane.kernel_calls`).
accelerations, computed_torque = ck.ACCELERATIONS.call, ck.COMPUTED_TORQUE.call
pay_kernel = ck.PAYLOAD.call
set_length, tip_kinematics = ck.set_length, ck.tip_kinematics
kane_call, cable_force = c.call_kane, c.K.cable_force
actuator_coordinates, unpack = c.KE.actuator_coordinates, c.unpack
#: A coordinate beyond this has diverged (record.DIVERGED_STATE).
LIMIT = 1e6


def _make(stamp):

    @jit
    def prepare(P, i, y, aux):
        """Nothing made ahead of the law (no pass of the plant's that its laws share)."""
        if len(stamp) == 0:
            return

    @jit
    def hoist_at(P, flat, lay, prism, i):
        """``(L̇, L̈)`` of the winch at stage point ``i``, its length written into the
        arrays ``flat, lay, prism`` (the plant's or the model's own copy); ``(0, 0)``
        and nothing written for a fixed length (``P[17]`` of one row)."""
        if len(stamp) == 0:
            return 0.0, 0.0
        Lh = P[17]
        if Lh.shape[0] == 1:
            return 0.0, 0.0
        set_length(flat, lay, prism, Lh[i, 0])
        return Lh[i, 1], Lh[i, 2]

    @jit
    def rhs(P, i, y, X, dy, aux):
        """The 11 coordinates' rates and accelerations into ``dy[:22]``; ``aux[0]`` ok,
        ``aux[1]`` the energy T + V [J]."""
        if len(stamp) == 0:
            return False
        a, en = P[6], P[7]
        Ld, Ldd = hoist_at(P, P[0], P[1], P[2], i)
        ok = accelerations(P[0], P[1], P[2], P[3], P[4], y[:11], y[11:22], X, P[5], Ld, Ldd,
                           a, en, P[18])
        for j in range(11):
            dy[j] = y[11 + j]
            dy[11 + j] = a[j]
        aux[0] = 1.0 if ok else 0.0
        aux[1] = en[0] + en[1]
        return ok

    @jit
    def check(P, y, aux, ok):
        """A runaway coordinate (DIVERGED), a singular mass matrix (SINGULAR), or OK."""
        if len(stamp) == 0:
            return OK
        for j in range(11):
            if abs(y[j]) > LIMIT:
                return DIVERGED
        return OK if ok else SINGULAR

    @jit
    def tension(flat, lay, prism, g, y, dy, work):
        """The cable's tension [N] at the state ``y`` (22,) moving at ``dy``'s
        accelerations: the fused Kane pass of the chain with the sway joints (the arrays
        ``flat, lay, prism`` of the fixed length; ``g`` (3,) [m/s²]), and the force its
        store carries across the sway joints (as the cable's inverse dynamics,
        :func:`~offshore_crane.dynamics.cable.kernels.kane`). ``work``: the plant's
        scratch (:mod:`offshore_crane.dynamics.cable.work`)."""
        if len(stamp) == 0:
            return 0.0
        C = unpack(flat, lay, prism)[0]
        rows, A, rhs6, diag, store = carve_tension(work, C.n_arm)
        rows[:] = 0.0
        diag[:] = 0.0
        kane_call(C, y[:11], y[11:22], dy[11:22], (g[0], g[1], g[2]), False, 0, True, rows,
                  A, rhs6, diag, store)
        return cable_force(C, store)[1]

    @jit
    def keep(P, EXTRA, k, y, dy, X, aux):
        """The sway, its rate and acceleration (2 each), the energy and, on a cable of a
        fixed length, its tension (before the drag's share, which the plant's ``finish``
        adds; NaN with a winch: ``finish`` forms the hoisted pull) into ``EXTRA[k]``."""
        if len(stamp) == 0:
            return
        for j in range(2):
            EXTRA[k, j] = y[9 + j]
            EXTRA[k, 2 + j] = y[20 + j]
            EXTRA[k, 4 + j] = dy[20 + j]
        EXTRA[k, 6] = aux[1]
        EXTRA[k, 7] = (call_tension(P[0], P[1], P[2], P[5], y, dy, P[18])
                       if P[17].shape[0] == 1 else np.nan)

    @jit
    def inverse(P, i, y, qdd, X):
        """X for ``qdd`` (9,) at the measured ``y`` on the model (the sway read)."""
        if len(stamp) == 0:
            return
        Ld, Ldd = hoist_at(P, P[8], P[9], P[10], i)
        computed_torque(P[8], P[9], P[10], P[11], P[12], y[:11], y[11:22], qdd, P[5], Ld,
                        Ldd, X, P[18])

    @jit
    def gravity(P, i, y, X):
        """X holding the model still at the measured positions (on the winch's length
        at stage point ``i``, held still too)."""
        if len(stamp) == 0:
            return
        zero = P[16]
        hoist_at(P, P[8], P[9], P[10], i)
        computed_torque(P[8], P[9], P[10], P[11], P[12], y[:11], zero[:11], zero[:9], P[5],
                        0.0, 0.0, X, P[18])

    @jit
    def coords(P, q, qd, s, sd):
        """The actuated joints' positions and rates (legs' arrays)."""
        if len(stamp) == 0:
            return
        actuator_coordinates(unpack(P[13], P[14], P[15])[0], q, qd, s, sd)

    @jit
    def payload(P, i, y, pay):
        """The payload relative to the tip, velocity and position (6,), on the model (the
        winch's length and rate at stage point ``i``)."""
        if len(stamp) == 0:
            return
        Ld = hoist_at(P, P[8], P[9], P[10], i)[0]
        pay_kernel(P[8], P[9], P[10], y[:11], y[11:22], Ld, pay)

    @jit
    def arm_tip(P, q, qd, qdd, out):
        """The tip's position, velocity, acceleration (9,) under ``q, q̇, q̈`` (9,), on
        the model."""
        if len(stamp) == 0:
            return
        tip_kinematics(P[8], P[9], P[10], q, qd, qdd, out)

    return prepare, rhs, check, keep, inverse, gravity, coords, payload, arm_tip, tension


#: What these kernels' disk cache is keyed by: the formulas' hash and the text of the
#: cable's kernels and the shared ones they call (Numba's cache checks only a function's
#: own file, so a callee edited elsewhere would otherwise be linked stale).
STAMP = ck.STAMP + hashlib.sha256((inspect.getsource(ck) + inspect.getsource(shared)
                                   ).encode()).hexdigest()
(prepare, rhs, check, keep, inverse, gravity, coords, payload, arm_tip,
 tension) = _make(STAMP)
#: The tension called by address (:mod:`offshore_crane.kernel_calls`): compiled once,
#: beside a first loop on a cold cache, not in each loop.
TENSION = kernel_calls.Entry.typed("hanging_tension", lambda: tension,
                                   "float64(*PACKED, V, V, V, V)", STAMP)
call_tension = TENSION.call
#: A winch on a rigid cable follows its length profile: it takes no command.
winch, winch_to = shared.winch, shared.winch_to


def params(plant) -> tuple:
    """``P`` of a :class:`~offshore_crane.simulation.plants.HangingPlant`."""
    from offshore_crane.dynamics.constants import robot_arrays

    a, m = plant.plant_arrays, plant.model_arrays
    legs = robot_arrays(plant.model.without_hanging_payload())
    Lh = plant.lengths
    # a winch writes its length into the arrays: the plant's and the model's own copies
    own = (lambda x: x.copy()) if len(Lh) > 1 else (lambda x: x)
    return (own(a.flat), a.layout, a.prismatic, np.asarray(plant.damp_p, float),
            plant.drag_p, np.array(plant.g, dtype=float), np.zeros(11), np.zeros(2),
            own(m.flat), m.layout, m.prismatic, np.asarray(plant.damp_c, float),
            plant.drag_c, legs.flat, legs.layout, legs.prismatic, np.zeros(11),
            np.ascontiguousarray(Lh, dtype=float), np.zeros(ck.WORK))
