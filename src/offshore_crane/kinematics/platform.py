"""Platform (body 1) kinematics from q1..q6 (CONVENTIONS.md coordinates).

``p_base_O2 = (q1, q2, q3)``, ``R_base_platform = Rz(q6) Ry(q5) Rx(q4)``; the partial
angular velocities (paper Eq. 24) are ``w4 = Rz(q6) Ry(q5) x``, ``w5 = Rz(q6) y``,
``w6 = z`` (erratum 1: the rotation is that of the coordinates, not ``exp(Ω̂ t)``).
"""

from __future__ import annotations

import numpy as np

from ..spatial import attitude_matrix, cross
from .chain import BaseMotion


def attitude_partials(q: np.ndarray) -> np.ndarray:
    """Partial angular velocities of the platform for u4, u5, u6.

    Args:
        q: ``(N, >=6)`` coordinates [m, rad].

    Returns:
        ``(N, 3, 3)``: ``[:, k]`` is the world vector ``w_{4+k}`` [rad/s per rad/s].
    """
    cp, sp = np.cos(q[:, 4]), np.sin(q[:, 4])
    cy, sy = np.cos(q[:, 5]), np.sin(q[:, 5])
    w = np.zeros((q.shape[0], 3, 3))
    w[:, 0, 0], w[:, 0, 1], w[:, 0, 2] = cy * cp, sy * cp, -sp
    w[:, 1, 0], w[:, 1, 1] = -sy, cy
    w[:, 2, 2] = 1.0
    return w


def platform_motion(q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> BaseMotion:
    """Pose, twist, acceleration and partials of the platform frame (origin O2 = CoM).

    Args:
        q, qd, qdd: ``(N, 9)`` (only columns 0..5 are read) [m, rad], rates, accelerations.

    Returns:
        :class:`BaseMotion` with ``V, W`` of shape ``(N, 6, 3)`` (speeds u1..u6).
    """
    N = q.shape[0]
    R = attitude_matrix(q[:, 3], q[:, 4], q[:, 5])
    w = attitude_partials(q)
    omega = np.einsum("nkj,nk->nj", w, qd[:, 3:6])
    # d/dt of w: w6 is constant, w5 turns with q6 about z, w4 turns with q6 and q5.
    z = np.broadcast_to(np.array([0.0, 0.0, 1.0]), (N, 3))
    w5_dot = cross(z, w[:, 1]) * qd[:, 5, None]
    w4_dot = cross(z * qd[:, 5, None] + w[:, 1] * qd[:, 4, None], w[:, 0])
    alpha = (np.einsum("nkj,nk->nj", w, qdd[:, 3:6])
             + w4_dot * qd[:, 3, None] + w5_dot * qd[:, 4, None])
    V = np.zeros((N, 6, 3))
    V[:, 0, 0] = V[:, 1, 1] = V[:, 2, 2] = 1.0
    W = np.zeros((N, 6, 3))
    W[:, 3:6] = w
    return BaseMotion(R=R, p=q[:, 0:3], omega=omega, alpha=alpha, v=qd[:, 0:3], a=qdd[:, 0:3],
                      V=V, W=W)
