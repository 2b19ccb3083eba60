"""Building blocks of Kane's method shared by the hybrid robot and general serial chains.

For a rigid body with mass ``m`` [kg], central inertia ``I`` [kg·m²] (world axes),
centre-of-mass acceleration ``a`` [m/s²], angular velocity ``omega`` [rad/s] and angular
acceleration ``alpha`` [rad/s²], Kane's generalized inertia force is (paper Eq. 5)

    F*_r = -(m a . v_r + (I alpha + omega x I omega) . w_r),

and the generalized active force of gravity ``g`` [m/s²] is ``F_r = m g . v_r``, where
``v_r`` [m/s per unit u_r] and ``w_r`` [rad/s per unit u_r] are the partial velocity of
the centre of mass and the partial angular velocity of the body. The inverse dynamics
right-hand side of ``A X = B`` (paper Eq. 37) is ``B_r = -(F*_r + F_r^gravity)`` summed
over bodies, which :func:`body_load` returns for one body.
"""

from __future__ import annotations

import numpy as np

from .spatial import cross, matvec


def inertia_to_world(R_world_body: np.ndarray, inertia_body: np.ndarray) -> np.ndarray:
    """Rotate a central inertia tensor to world axes: ``R I Rᵀ``.

    Args:
        R_world_body: ``(N, 3, 3)`` body orientation.
        inertia_body: ``(3, 3)`` central inertia in body axes [kg·m²].

    Returns:
        ``(N, 3, 3)`` [kg·m²].
    """
    return R_world_body @ inertia_body @ np.swapaxes(R_world_body, -1, -2)


def inertia_wrench(mass: float, inertia_world: np.ndarray, a_com: np.ndarray,
                   omega: np.ndarray, alpha: np.ndarray, gravity: np.ndarray):
    """Minus the resultant of inertia and gravity forces of one body.

    Args:
        mass: ``m`` [kg].
        inertia_world: ``(N, 3, 3)`` central inertia in world axes [kg·m²].
        a_com: ``(N, 3)`` centre-of-mass acceleration [m/s²].
        omega: ``(N, 3)`` angular velocity [rad/s].
        alpha: ``(N, 3)`` angular acceleration [rad/s²].
        gravity: ``(3,)`` gravity acceleration [m/s²].

    Returns:
        ``(force, torque)``: ``m (a - g)`` [N] and ``I alpha + omega x I omega`` [N·m],
        both ``(N, 3)``, both in world axes, the torque about the centre of mass.
    """
    force = mass * (a_com - gravity)
    torque = matvec(inertia_world, alpha) + cross(omega, matvec(inertia_world, omega))
    return force, torque


def body_load(v_partial: np.ndarray, w_partial: np.ndarray, force: np.ndarray,
              torque: np.ndarray) -> np.ndarray:
    """Project a body's ``(force, torque)`` on its partial velocities: ``B_r`` share.

    Args:
        v_partial: ``(N, n, 3)`` partial velocities of the centre of mass [m/s per u_r].
        w_partial: ``(N, n, 3)`` partial angular velocities [rad/s per u_r].
        force: ``(N, 3)`` from :func:`inertia_wrench` [N].
        torque: ``(N, 3)`` from :func:`inertia_wrench` [N·m].

    Returns:
        ``(N, n)``: ``v_r . force + w_r . torque`` [N or N·m per generalized speed].
    """
    return np.einsum("...rk,...k->...r", v_partial, force) + np.einsum("...rk,...k->...r", w_partial, torque)
