"""The closed-loop robot's inertial-parameter regressor: Pinocchio's joint-torque regressor
of the equivalent tree projected on the independent speeds, as the RNEA reference
projects its torques.

``τ = Y_tree(q, v, a) π_tree`` (Pinocchio's ``computeJointTorqueRegressor``: 10 columns
per joint, the parameters ``[m, m c_x, m c_y, m c_z, I_xx, I_xy, I_yy, I_xz, I_yz, I_zz]``
of the body moved by the joint, inertia about the joint frame's origin, in that frame).
The actuator forces are linear in τ (:func:`.projection.project`: ``(T1, T2, Fs) =
τ_arm``, ``Jlᵀ Fl = (Gᵀ τ)[0:6]``), so each column of ``Y_tree`` projected the same way
gives X per unit of its parameter: ``X = Y π``. Only bodies with mass are kept (a
massless frame's parameters are not in the model).

Frames: Pinocchio's world is the base frame; units SI.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from offshore_crane.reference.rnea.closure import tree_state
from offshore_crane.reference.rnea.projection import project
from offshore_crane.reference.rnea.tree import read_tree

#: The ten standard parameters of a body, in Pinocchio's order, and their units.
PARAMETERS = ("m", "mcx", "mcy", "mcz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz")
UNITS = ("kg", "kg·m", "kg·m", "kg·m", "kg·m²", "kg·m²", "kg·m²", "kg·m²", "kg·m²",
         "kg·m²")


class Regressor(NamedTuple):
    """The regressor of ``N`` samples.

    Attributes:
        Y: ``(N, 9, P)`` [N or N·m per unit of each parameter]: ``X = Y @ pi``.
        pi: ``(P,)`` the model's standard parameters (from the URDF, via Pinocchio).
        names: ``(P,)`` ``"{body}.{parameter}"`` (body: the link the joint moves).
        units: ``(P,)`` each parameter's unit.
    """

    Y: np.ndarray
    pi: np.ndarray
    names: tuple
    units: tuple


def bodies(model) -> list[int]:
    """Joint indices (1..njoints−1) whose body has mass."""
    return [j for j in range(1, model.njoints) if model.inertias[j].mass > 0.0]


def regressor(robot: Any, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray,
              gravity: np.ndarray) -> Regressor:
    """The regressor of the closed-loop robot at ``N`` samples.

    Args:
        robot: Read by attribute only: ``robot.pinocchio_model`` (its URDF).
        q, qd, qdd: ``(N, 9)`` finite coordinates [m, rad], rates, accelerations.
        gravity: ``(3,)`` base frame [m/s²].

    Returns:
        :class:`Regressor`.

    Raises:
        NumericalError: a loop does not close (:func:`.closure.tree_state`).
    """
    import pinocchio as pin

    model = robot.pinocchio_model.copy()
    model.gravity.linear = np.asarray(gravity, dtype=float)
    data = model.createData()
    T = read_tree(robot)
    keep = bodies(model)
    cols = np.concatenate([np.arange(10 * (j - 1), 10 * j) for j in keep])
    Q, V, A, G, _ = tree_state(robot, q, qd, qdd)
    N, P = Q.shape[1], len(cols)
    Y = np.empty((N, 9, P))
    cond = np.empty(P)
    for k in range(N):                     # Pinocchio's regressor takes one state
        Yt = pin.computeJointTorqueRegressor(model, data, Q[:, k], V[:, k], A[:, k])
        tau = np.ascontiguousarray(Yt[:, cols].T)          # a column a row (project's)
        Gk = np.ascontiguousarray(np.broadcast_to(G[k], (P,) + G.shape[1:]))
        out = np.empty((P, 9))
        project(tau, Gk, T.plat_v, T.legs.v_index, T.arm_v, 1.0 / T.L, False, out, cond)
        Y[k] = out.T
    pi = np.concatenate([model.inertias[j].toDynamicParameters() for j in keep])
    names = tuple(f"{_body(model, j)}.{p}" for j in keep for p in PARAMETERS)
    return Regressor(Y, pi, names, UNITS * len(keep))


def _body(model, j: int) -> str:
    """The link moved by joint ``j`` (the first body frame whose parent joint is j)."""
    import pinocchio as pin

    for f in model.frames:
        if f.parentJoint == j and f.type == pin.FrameType.BODY:
            return f.name
    return model.names[j]
