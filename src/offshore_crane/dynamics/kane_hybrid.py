"""Kane's inverse dynamics of the hybrid robot (paper Eqs. 18-40, corrected per errata).

Generalized speeds ``u_r = q̇_r`` (Eq. 18). For every body the partial velocity of its
centre of mass and its partial angular velocity are formed (platform: Eq. 20, 24; legs:
derived from the closed-form leg kinematics, errata 2-6; arm: Eq. 30 recursively). The
equations ``F_r + F*_r = 0`` (Eq. 36) are written ``A X = B`` (Eq. 37) with

    B_r = Σ_bodies  v_r · m (a − g) + ω_r · (I α + ω × I ω),
    A_rk = ∂(rate of actuated joint k)/∂u_r.

For the actuator order of Eq. 40, ``A = [[0, Jᵀ], [I3, 0]]`` by rows (u1..u6 | u7..u9):
an arm motor's joint rate is ``u7``, ``u8`` or ``u9`` (so its generalized force acts on one
row only: an action–reaction pair, errata 7), and a leg's rate is ``l̇_i = J_i · u[:6]``
where ``J`` is the leg-length (actuation) Jacobian, independent of the arm speeds. So

    (T1, T2, Fs) = B[6:9],     Jᵀ (Fl1..Fl6) = B[0:6].
"""

from __future__ import annotations

import numpy as np

from ..kane import body_load, inertia_to_world, inertia_wrench
from ..kinematics.chain import BaseMotion, chain_kinematics
from ..kinematics.legs import LegMotion, leg_kinematics
from ..kinematics.platform import platform_motion
from ..model.hybrid import HybridModel
from ..spatial import cross


def platform_load(model: HybridModel, plat: BaseMotion, gravity: np.ndarray) -> np.ndarray:
    """``B`` share of the platform and the links welded to it: ``(N, 6)``."""
    R = plat.R
    r = R @ model.platform_com
    a_com = plat.a + cross(plat.alpha, r) + cross(plat.omega, cross(plat.omega, r))
    force, torque = inertia_wrench(model.platform_mass, inertia_to_world(R, model.platform_inertia),
                                   a_com, plat.omega, plat.alpha, gravity)
    V = plat.V + cross(plat.W, r[:, None, :])
    return body_load(V, plat.W, force, torque)


def arm_load(model: HybridModel, q, qd, qdd, plat: BaseMotion, gravity) -> np.ndarray:
    """``B`` share of the moving arm bodies: ``(N, 9)`` (zeros for a robot without arm)."""
    arm = model.arm
    arm_q = slice(6, 6 + arm.n)
    B = np.zeros((q.shape[0], 9))
    for k, body in enumerate(chain_kinematics(arm, q[:, arm_q], qd[:, arm_q], qdd[:, arm_q],
                                              plat)):
        force, torque = inertia_wrench(arm.mass[k], inertia_to_world(body.R, arm.inertia[k]),
                                       body.a_com, body.omega, body.alpha, gravity)
        B[:, :6 + arm.n] += body_load(body.V, body.W, force, torque)
    return B


def legs_load(model: HybridModel, legs: LegMotion, gravity: np.ndarray) -> np.ndarray:
    """``B`` share of the 12 leg links: ``(N, 6)`` (legs do not move with u7..u9)."""
    R, w, al = legs.R, legs.omega, legs.alpha
    total = 0.0
    for mass, com, inertia, origin_a, origin_V in (
            (model.lower_mass, model.lower_com, model.lower_inertia, 0.0, 0.0),
            (model.upper_mass, model.upper_com, model.upper_inertia, legs.a_S, legs.V_S)):
        r = np.einsum("nlij,lj->nli", R, com)
        a_com = origin_a + cross(al, r) + cross(w, cross(w, r))
        I_world = R @ inertia @ np.swapaxes(R, -1, -2)
        force, torque = inertia_wrench(mass[:, None], I_world, a_com, w, al, gravity)
        V = origin_V + cross(legs.W, r[:, :, None, :])
        total = total + body_load(V, legs.W, force, torque).sum(axis=1)
    return total


def solve_actuators(B: np.ndarray, J: np.ndarray) -> np.ndarray:
    """Solve ``A X = B`` with its block structure (see module docstring).

    Args:
        B: ``(N, 9)`` [N or N·m per generalized speed].
        J: ``(N, 6, 6)`` leg-length Jacobian.

    Returns:
        ``(N, 9)`` actuator vector X in the order of :data:`ACTUATORS`.
    """
    X = np.empty_like(B)
    X[:, :3] = B[:, 6:9]
    X[:, 3:] = np.linalg.solve(np.swapaxes(J, -1, -2), B[:, :6, None])[..., 0]
    return X


def kane_B(model: HybridModel, q, qd, qdd, gravity):
    """Right-hand side ``B`` ``(N, 9)`` and the leg kinematics used to form it."""
    plat = platform_motion(q, qd, qdd)
    legs = leg_kinematics(model, plat)
    B = arm_load(model, q, qd, qdd, plat, gravity)
    B[:, :6] += platform_load(model, plat, gravity) + legs_load(model, legs, gravity)
    return B, legs
