"""The reference path: Pinocchio's RNEA on the equivalent tree, projected on u.

1. From the 9 independent coordinates, the tree's 27 joint positions, rates and
   accelerations that close the six loops (U-joint angles and leg lengths from
   :mod:`offshore_crane.kinematics.legs`).
2. ``τ = RNEA(q_tree, v_tree, a_tree)`` [N, N·m], by ``pin.rneaInParallel``.
3. With ``G = ∂v_tree/∂u`` (27 x 9; its leg rows hold the leg-length Jacobian and the
   U-joint rate partials), the virtual power of the tree equals that of the mechanism:
   ``Gᵀ S X = Gᵀ τ``, where ``S`` places X on the actuated joints. ``Gᵀ S`` is the same
   ``A`` as Kane's, so the same block solve applies.
"""

from __future__ import annotations

import numpy as np

from ..kinematics.legs import leg_kinematics
from ..kinematics.platform import platform_motion
from ..model.hybrid import ARM_JOINTS, N_LEGS, PLATFORM_JOINTS
from ..spatial import dot
from .kane_hybrid import solve_actuators


def _index(model, name: str) -> int:
    return model.idx_vs[model.getJointId(name)]


def tree_indices(pmodel) -> dict:
    """Velocity indices of the tree joints: ``platform (6,)``, ``arm (na,)``, ``legs (6, 3)``.

    ``na`` is 3, or 0 for a Stewart platform without arm (xacro ``with_arm = 0``).
    """
    return {
        "platform": np.array([_index(pmodel, n) for n in PLATFORM_JOINTS]),
        "arm": np.array([_index(pmodel, n) for n in ARM_JOINTS if pmodel.existJointName(n)],
                        dtype=int),
        "legs": np.array([[_index(pmodel, f"leg{i}_{s}") for s in ("u1", "u2", "slide")]
                          for i in range(1, N_LEGS + 1)]),
    }


def tree_state(robot, q, qd, qdd):
    """Tree positions, rates, accelerations ``(N, 27)`` that close the loops.

    Returns:
        ``(q_tree, v_tree, a_tree, legs, plat)``; all revolute and prismatic joints have
        one coordinate each, so the three arrays share the velocity index layout.
    """
    pmodel = robot.pinocchio_model
    idx = tree_indices(pmodel)
    plat = platform_motion(q, qd, qdd)
    legs = leg_kinematics(robot.hybrid, plat)
    N = q.shape[0]
    out = []
    for base, leg in ((q, (legs.theta, legs.length)), (qd, (legs.theta_d, legs.rate)),
                      (qdd, (legs.theta_dd, legs.accel))):
        x = np.empty((N, pmodel.nv))
        x[:, idx["platform"]] = base[:, :6]
        x[:, idx["arm"]] = base[:, 6:6 + len(idx["arm"])]
        x[:, idx["legs"][:, :2]] = leg[0]
        x[:, idx["legs"][:, 2]] = leg[1]
        out.append(x)
    return (*out, legs, plat)


def tree_torques(robot, q_tree, v_tree, a_tree, gravity, threads: int = 1) -> np.ndarray:
    """``τ = RNEA(q, v, a)`` ``(N, 27)`` with ``pin.rneaInParallel``."""
    import pinocchio as pin

    model = robot.pinocchio_model.copy()
    model.gravity.linear = np.asarray(gravity, dtype=float)
    pool = pin.ModelPool(model, threads)
    Q, V, A = (np.asfortranarray(x.T) for x in (q_tree, v_tree, a_tree))
    tau = np.empty_like(Q, order="F")
    pin.rneaInParallel(threads, pool, Q, V, A, tau)
    return tau.T


def project(robot, tau: np.ndarray, legs) -> np.ndarray:
    """``Gᵀ τ``: the tree forces as generalized forces ``(N, 9)`` on u1..u9."""
    idx = tree_indices(robot.pinocchio_model)
    B = np.zeros((tau.shape[0], 9))             # arm rows stay zero without arm
    B[:, :6] = tau[:, idx["platform"]]
    B[:, 6:6 + len(idx["arm"])] = tau[:, idx["arm"]]
    tl = tau[:, idx["legs"]]                                    # (N, 6, 3)
    # rows of G for leg joints: θ̇1 = a1·ω, θ̇2 = a2·ω, l̇ = J u (for r = 1..6)
    B[:, :6] += np.einsum("nl,nlr->nr", tl[..., 0], dot(legs.a1[:, :, None, :], legs.W))
    B[:, :6] += np.einsum("nl,nlr->nr", tl[..., 1], dot(legs.a2[:, :, None, :], legs.W))
    B[:, :6] += np.einsum("nl,nlr->nr", tl[..., 2], legs.J)
    return B


def rnea_B(robot, q, qd, qdd, gravity, threads: int = 1):
    """``Gᵀ τ`` ``(N, 9)`` and the leg kinematics used to form it."""
    qt, vt, at, legs, _ = tree_state(robot, q, qd, qdd)
    tau = tree_torques(robot, qt, vt, at, gravity, threads)
    return project(robot, tau, legs), legs
