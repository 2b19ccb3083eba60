"""Closed-form kinematics of the six U-P-S legs, batched over N samples and 6 legs.

For leg i, ``d = S_i - P_i = l u`` (paper Eqs. 7, 10). The leg's angular velocity has the
part perpendicular to the leg given by the paper's Eq. 12, ``ω⊥ = u × v_S / l``, and a
spin about the leg fixed by the U-joint (erratum 3): ``ω`` lies in span{a1, a2}, the two
U-joint axes, i.e. ``ω · n = 0`` with ``n = a1 × a2``. Hence

    ω = ω⊥ − (ω⊥ · n)/(u · n) u.

Accelerations are derived, not copied (erratum 4): from ``a_S = l̈ u + 2 l̇ ω×u + l α×u +
l ω×(ω×u)``, ``l̈ = a_S·u + l |ω×u|²``, ``α⊥ = u × (α×u)``, and the U-joint gives
``α · n = θ̇1 θ̇2`` (``α = θ̈1 a1 + θ̈2 a2 + θ̇1 θ̇2 a1×a2``). ``u · n = −cos θ2`` vanishes
when the leg lies along the first U-joint axis: the U-joint gimbal singularity.

Joint angles of the U-joint (frame of ``leg{i}_u1``: a1 = y, leg at zero angles = z,
a2 = x of the cross): the leg direction in that frame is
``(cos θ2 sin θ1, −sin θ2, cos θ2 cos θ1)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.hybrid import HybridModel
from ..spatial import cross, dot
from .chain import BaseMotion


@dataclass
class LegMotion:
    """Kinematics of the six legs; every array has leading axes ``(N, 6)``.

    Attributes:
        p_S, v_S, a_S: ``(N, 6, 3)`` sphere centre S_i: position [m], velocity [m/s],
            acceleration [m/s²] (base frame).
        length, rate, accel: ``(N, 6)`` leg length l_i [m], l̇_i [m/s], l̈_i [m/s²].
        u: ``(N, 6, 3)`` unit vector from P_i to S_i.
        theta, theta_d, theta_dd: ``(N, 6, 2)`` U-joint angles [rad], rates, accelerations.
        a1, a2: ``(N, 6, 3)`` U-joint axes (a1 fixed in the base, a2 on the cross).
        u_dot_n: ``(N, 6)`` ``u · (a1 × a2) = −cos θ2``; zero at the gimbal singularity.
        R: ``(N, 6, 3, 3)`` ``R_base_leg`` (both leg links share it).
        omega, alpha: ``(N, 6, 3)`` angular velocity [rad/s], acceleration [rad/s²].
        V_S: ``(N, 6, 6, 3)`` partial velocities of S_i for u1..u6 [m/s per u_r].
        W: ``(N, 6, 6, 3)`` partial angular velocities of the leg for u1..u6.
        J: ``(N, 6, 6)`` leg-length (actuation) Jacobian, ``l̇ = J · u[:6]``.
    """

    p_S: np.ndarray
    v_S: np.ndarray
    a_S: np.ndarray
    length: np.ndarray
    rate: np.ndarray
    accel: np.ndarray
    u: np.ndarray
    theta: np.ndarray
    theta_d: np.ndarray
    theta_dd: np.ndarray
    a1: np.ndarray
    a2: np.ndarray
    u_dot_n: np.ndarray
    R: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    V_S: np.ndarray
    W: np.ndarray
    J: np.ndarray


def leg_kinematics(model: HybridModel, platform: BaseMotion) -> LegMotion:
    """Leg kinematics from the platform's motion (:func:`platform_motion`).

    Args:
        model: The robot's arrays.
        platform: Platform motion with partials for u1..u6.

    Returns:
        :class:`LegMotion`.
    """
    R, w, al = platform.R, platform.omega[:, None, :], platform.alpha[:, None, :]
    r = np.einsum("nij,lj->nli", R, model.p_platform_S)        # O2 -> S_i, base axes
    p_S = platform.p[:, None, :] + r
    v_S = platform.v[:, None, :] + cross(w, r)
    a_S = platform.a[:, None, :] + cross(al, r) + cross(w, cross(w, r))

    d = p_S - model.p_base_P
    length = np.sqrt(dot(d, d))
    u = d / length[..., None]
    rate = dot(u, v_S)

    # U-joint angles in each leg{i}_u1 frame.
    d_loc = np.einsum("lji,nlj->nli", model.R_base_U, d)       # R_base_Uᵀ d
    th1 = np.arctan2(d_loc[..., 0], d_loc[..., 2])
    th2 = np.arctan2(-d_loc[..., 1], np.hypot(d_loc[..., 0], d_loc[..., 2]))
    c1, s1, c2, s2 = np.cos(th1), np.sin(th1), np.cos(th2), np.sin(th2)
    RU = model.R_base_U
    a1 = np.broadcast_to(RU[:, :, 1], d.shape)
    x_cross = np.stack([c1, np.zeros_like(c1), -s1], axis=-1)   # cross's x axis in U frame
    a2 = np.einsum("lij,nlj->nli", RU, x_cross)
    n = cross(a1, a2)
    u_dot_n = dot(u, n)

    # angular velocity (Eq. 12 + U-joint spin, erratum 3)
    w_perp = cross(u, v_S) / length[..., None]
    omega = w_perp - (dot(w_perp, n) / u_dot_n)[..., None] * u
    th1_d, th2_d = dot(omega, a1), dot(omega, a2)

    # accelerations (derived, erratum 4)
    wxu = cross(omega, u)
    accel = dot(a_S, u) + length * dot(wxu, wxu)
    alpha_x_u = ((a_S - accel[..., None] * u - 2.0 * rate[..., None] * wxu) / length[..., None]
                 - cross(omega, wxu))
    alpha_perp = cross(u, alpha_x_u)
    alpha = alpha_perp + ((th1_d * th2_d - dot(alpha_perp, n)) / u_dot_n)[..., None] * u

    # partial velocities for u1..u6: v_S,r = V_r + W_r × r (platform partials at O2)
    V_S = platform.V[:, None, :, :] + cross(platform.W[:, None, :, :], r[:, :, None, :])
    J = dot(u[:, :, None, :], V_S)
    Wp = cross(u[:, :, None, :], V_S) / length[..., None, None]
    Wl = Wp - (dot(Wp, n[:, :, None, :]) / u_dot_n[..., None])[..., None] * u[:, :, None, :]

    # R_base_leg = R_base_U Ry(θ1) Rx(θ2)
    Rloc = np.empty(th1.shape + (3, 3))
    Rloc[..., 0, 0], Rloc[..., 0, 1], Rloc[..., 0, 2] = c1, s1 * s2, s1 * c2
    Rloc[..., 1, 0], Rloc[..., 1, 1], Rloc[..., 1, 2] = 0.0, c2, -s2
    Rloc[..., 2, 0], Rloc[..., 2, 1], Rloc[..., 2, 2] = -s1, c1 * s2, c1 * c2
    R_leg = RU @ Rloc

    return LegMotion(
        p_S=p_S, v_S=v_S, a_S=a_S, length=length, rate=rate, accel=accel, u=u,
        theta=np.stack([th1, th2], -1), theta_d=np.stack([th1_d, th2_d], -1),
        theta_dd=np.stack([dot(alpha, a1), dot(alpha, a2)], -1),
        a1=a1, a2=a2, u_dot_n=u_dot_n, R=R_leg, omega=omega, alpha=alpha,
        V_S=V_S, W=Wl, J=J)
