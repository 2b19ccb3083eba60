"""Compiled kernels two plants share (:mod:`._rigid_kernels`, :mod:`._elastic_kernels`:
both keep the legs' packed arrays at ``P[3:6]``, neither has a hanging payload, both stop
on a singular mass matrix only), the no-op ``winch`` and ``winch_to`` of the plants
without a commanded winch (the hanging load's too) and the rigid plant's power by
address. Closed over the formulas' hash."""

from __future__ import annotations

import numpy as np

from offshore_crane import kernel_calls
from offshore_crane.dynamics import compiled as c
from offshore_crane.kernel_cache import njit
from offshore_crane.stops import CODES

OK, _, SINGULAR, _, _, _ = CODES
jit = njit(**c.LEAN)
inline = njit(inline="always", **c.JIT)
actuator_coordinates, unpack = c.KE.actuator_coordinates, c.unpack


@jit
def _power(flat, lay, prism, q, qd, X, w):
    """The actuators' power [W] ``Σ X_k ṡ_k`` under the applied forces ``X`` at ``q, q̇``
    (9,) each, on the robot of packed arrays ``flat, lay, prism`` (``w`` (18,): scratch
    for the actuated joints' positions and rates): the arm joints' sum, then the legs',
    added as :func:`~offshore_crane.simulation.record.actuator_power` adds them on NumPy
    (the same numbers, bit for bit). Called by address (:data:`POWER`)."""
    s, sd = w[:9], w[9:]
    actuator_coordinates(unpack(flat, lay, prism)[0], q, qd, s, sd)
    arm = 0.0
    for j in range(3):
        arm += X[j] * sd[j]
    legs = 0.0
    for j in range(3, 9):
        legs += X[j] * sd[j]
    return arm + legs


#: :func:`_power` called by address: the loop that records the power (the rigid plant's
#: ``keep``) does not compile the legs' kinematics itself; a helper process compiles them
#: once beside the first loop (a first cold ``simulate`` waited 0.8 s longer with them
#: inlined, measured). The hanging load and the elastic cable form their power on NumPy
#: after the run: recorded in their loops, the hanging load ran no faster and the
#: elastic lift 2 % faster, and their first cold ``simulate`` waited 1-1.3 s longer
#: (measured; the elastic lift's is the nearest to issue 37's 15 s).
POWER = kernel_calls.Entry.typed("actuator_power", lambda: _power,
                                 "float64(*PACKED, V, V, V, V)", c.STAMP)
power = POWER.call


def _make(stamp):

    @jit
    def check(P, y, aux, ok):
        """SINGULAR for a singular mass matrix, else OK."""
        if len(stamp) == 0:
            return OK
        return OK if ok else SINGULAR

    @jit
    def coords(P, q, qd, s, sd):
        """The actuated joints' positions and rates (the legs' arrays at ``P[3:6]``)."""
        if len(stamp) == 0:
            return
        actuator_coordinates(unpack(P[3], P[4], P[5])[0], q, qd, s, sd)

    @jit
    def payload(P, i, y, pay):
        """No hanging payload: NaN (an anti-sway law is refused on these plants)."""
        if len(stamp) == 0:
            return
        for j in range(6):
            pay[j] = np.nan

    @jit
    def arm_tip(P, q, qd, qdd, out):
        """No hanging payload: NaN (a compensation law is refused on the rigid plant)."""
        if len(stamp) == 0:
            return
        for j in range(9):
            out[j] = np.nan

    @inline
    def winch(P, i, y, X):
        """No commanded winch: nothing (the forces stay the law's 9; inlined: no call)."""
        if len(stamp) == 0:
            return

    @jit
    def winch_to(P, i, y, Lr, Ldr, Lddr, X):
        """No commanded winch: nothing."""
        if len(stamp) == 0:
            return

    return check, coords, payload, arm_tip, winch, winch_to


check, coords, payload, arm_tip, winch, winch_to = _make(c.STAMP)
