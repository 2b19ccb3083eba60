"""The workspace check of a few samples, compiled (imports Numba): for a caller that asks
after every control period whether the motion left the workspace (a stepper), where
:func:`~offshore_crane.robot.kinematics.check_workspace` (NumPy over the samples, made for
long records) spends about 0.25 ms a call on a period's ten samples.

:func:`first_outside` makes :func:`~offshore_crane.robot.kinematics.check_workspace`'s
tests on the same formulas (:mod:`offshore_crane.robot.kinematics.formulas`, compiled as
:data:`offshore_crane.dynamics.compiled.K`), sample by sample: an arm joint outside its
limits, a sphere centre not above its U-joint, a leg length outside its stroke, a U-joint
angle outside its limits (a NaN compares as inside in both). It gives the first sample
outside, not the message: :func:`~offshore_crane.robot.kinematics.check_workspace` on
the record says which limit and by how much.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.dynamics import compiled as c
from offshore_crane.kernel_cache import njit

attitude, leg_geometry, ujoint_angles = c.K.attitude, c.K.leg_geometry, c.K.ujoint_angles


def _make(stamp):
    @njit(**c.LEAN)
    def first_outside(q, start, stop, pS, pP, RU, arm, stroke, ujoint):
        """The first sample ``k`` of ``q`` ``(N, 9)`` [m, rad] in ``[start, stop)``
        outside the workspace, else −1. ``pS``, ``pP`` ``(6, 3)`` [m]: the sphere
        centres in the platform frame and the U-joint centres in the base frame;
        ``RU`` ``(6, 3, 3)``: the U-joints' frames; ``arm`` ``(n_arm, 2)``, ``stroke``
        ``(6, 2)`` [m], ``ujoint`` ``(6, 2, 2)`` [rad]: the limits (low, high)."""
        if len(stamp) == 0:
            return -1
        na = arm.shape[0]
        for k in range(start, stop):
            for j in range(na):
                x = q[k, 6 + j]
                if x < arm[j, 0] or x > arm[j, 1]:
                    return k
            R = attitude(q[k])[0]
            p = (q[k, 0], q[k, 1], q[k, 2])
            for i in range(6):
                g = leg_geometry(p, R, (pS[i, 0], pS[i, 1], pS[i, 2]),
                                 (pP[i, 0], pP[i, 1], pP[i, 2]),
                                 (RU[i, 0, 0], RU[i, 1, 0], RU[i, 2, 0]),
                                 (RU[i, 0, 1], RU[i, 1, 1], RU[i, 2, 1]),
                                 (RU[i, 0, 2], RU[i, 1, 2], RU[i, 2, 2]))
                d, length = g[1], g[2]
                if d[2] <= 0.0 or length < stroke[i, 0] or length > stroke[i, 1]:
                    return k
                t1, t2 = ujoint_angles(g[5], g[6], g[7], g[8])
                if (t1 < ujoint[i, 0, 0] or t1 > ujoint[i, 0, 1] or t2 < ujoint[i, 1, 0]
                        or t2 > ujoint[i, 1, 1]):
                    return k
        return -1

    return first_outside


first_outside = _make(c.STAMP)


def geometry(robot) -> tuple:
    """:func:`first_outside`'s arguments after ``stop`` for ``robot`` (its description's
    legs and limits, :func:`~offshore_crane.robot.kinematics.workspace.limits_of`)."""
    from offshore_crane.robot.kinematics import workspace as ws

    m, lim = robot.hybrid, ws.limits_of(robot.hybrid)
    return tuple(np.ascontiguousarray(a, dtype=float) for a in (
        m.p_platform_S, m.p_base_P, m.R_base_U, lim.arm, lim.stroke, lim.ujoint))
