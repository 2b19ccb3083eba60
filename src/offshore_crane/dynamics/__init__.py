"""Inverse dynamics of the hybrid robot: Kane (default) or the Pinocchio RNEA path."""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..validation import as_gravity, as_samples, same_length

METHODS = ("kane", "rnea")
GRAVITY = (0.0, 0.0, -9.81)


def inverse_dynamics(robot, q, qd, qdd, method: str = "kane", gravity=GRAVITY) -> np.ndarray:
    """Actuator forces that produce the motion ``(q, qd, qdd)``.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` coordinates (CONVENTIONS.md): q1..q3 [m] position of
            the platform CoM in the base frame, q4..q6 [rad] roll, pitch, yaw, q7, q8 [rad]
            arm joint angles, q9 [m] slider displacement.
        qd: Same shape, rates [m/s, rad/s].
        qdd: Same shape, accelerations [m/s², rad/s²].
        method: ``"kane"`` (hand-written Kane, NumPy) or ``"rnea"`` (Pinocchio RNEA on
            the equivalent tree, projected on u).
        gravity: ``(3,)`` gravity in the base frame [m/s²].

    Returns:
        X ``(N, 9)`` (or ``(9,)``): ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]``, signed along
        the joint directions (positive Fl extends the leg).

    Raises:
        InputError: bad shapes, non-finite values, unknown method.
    """
    if method not in METHODS:
        raise InputError(f"unknown method '{method}': use one of {', '.join(METHODS)}",
                         name="method")
    q, single = as_samples("q", q)
    qd, _ = as_samples("qd", qd)
    qdd, _ = as_samples("qdd", qdd)
    same_length(q=q, qd=qd, qdd=qdd)
    g = as_gravity(gravity)
    if method == "kane":
        from .kane_hybrid import kane_inverse_dynamics

        X = kane_inverse_dynamics(robot.hybrid, q, qd, qdd, g)
    else:
        from .rnea import rnea_inverse_dynamics

        X = rnea_inverse_dynamics(robot, q, qd, qdd, g)
    return X[0] if single else X
