"""X of the robot with its hanging load by the compiled Kane pass
(:func:`offshore_crane.dynamics.cable.kernels.kane`)."""

from __future__ import annotations

import numpy as np

from offshore_crane.robot.kinematics import workspace as ws


def kane_forces(robot, t, q, qd, qdd, Y, g, limits, checks, thresholds, L=None, P=None):
    """X ``(n, 9)``, the cable's ``F`` ``(n, 6)`` and the condition numbers, by the
    compiled ``kernels.kane``: the payload on the chain (``L`` and ``P`` None), hoisted
    (``L`` ``(n, 3)``) or replaced by a given pull on the tip (``P`` ``(n, 3)`` [N])."""
    from offshore_crane.dynamics.runtime import compiled_kernels, run_threaded
    from offshore_crane.dynamics.cable import kernels as ck
    from offshore_crane.dynamics.constants import cable_arrays

    compiled_kernels()
    arrays = cable_arrays(robot)
    n = len(t)
    q11 = np.ascontiguousarray(np.concatenate([q, Y[:, 0:2]], axis=1))
    qd11 = np.ascontiguousarray(np.concatenate([qd, Y[:, 2:4]], axis=1))
    qdd11 = np.ascontiguousarray(np.concatenate([qdd, Y[:, 4:6]], axis=1))
    X = np.empty((n, 9))
    F = np.empty((n, 6))
    kappa = np.empty((3, n)) if checks else np.empty((3, 1))
    if n == 0:
        return X, F, kappa if checks else None

    hoist = np.empty((0, 3)) if L is None else L
    pull = np.empty((0, 3)) if P is None else np.ascontiguousarray(P)

    def run(start, stop, health):
        ck.kane(arrays.flat, arrays.layout, arrays.prismatic, robot.hybrid.sway_damping, q11,
                qd11, qdd11, hoist, pull, g, checks, limits, thresholds.warn,
                thresholds.error, start, stop, X, kappa, health, F)

    health = run_threaded(run, n, 1)
    ws.enforce(health, (q, qd, qdd), arrays.limits if limits else None,
               kappa if checks else None, thresholds, (ws.LEG_JACOBIAN, ws.GIMBAL), t)
    return X, F, kappa if checks else None
