"""The constrained reference's forward dynamics: Pinocchio's ``constraintDynamics``.

Six ``RigidConstraintModel(CONTACT_3D)`` loop constraints on the equivalent tree
(:mod:`.model`), at the tree states of :mod:`.closure`; every solved sample is then checked
by measurements that do not trust the solver (:func:`_measure`).

Frames: the base frame R1 is Pinocchio's world (the URDF root ``base``); units SI.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from offshore_crane.conventions import N_LEGS
from offshore_crane.errors import ConstraintResidualError
from offshore_crane.reference.constrained.closure import (NEWTON_MAX_ITER, NEWTON_TOLERANCE,
                                                          TreeStates, positive, solve_tree,
                                                          validated_inputs)
from offshore_crane.reference.constrained.model import LoopTree, loop_tree
from offshore_crane.validation import as_gravity

#: Default absolute and relative accuracy of Pinocchio's proximal solver (issue 13 asks
#: for <= 1e-12).
ACCURACY = 1e-12
#: Proximal regularisation mu of ``constraintDynamics``. With mu = 0 Pinocchio factorises
#: the exact KKT system (possible because the 18 loop rows are independent away from
#: leg singularities) and the proximal loop stops at its second pass, when the
#: multipliers no longer change. Measured on 200 random states, mu from 0 to 1e-4 gives
#: the same round trip against the Kane inverse dynamics (worst 1e-12, median 6e-15
#: relative); mu > 0 only adds passes (3 to 5).
PROXIMAL_MU = 0.0
#: Cap on Pinocchio's proximal iterations (with mu = 0 it stops after 2).
PROXIMAL_MAX_ITER = 50
#: Bound on the acceleration residual max |a_tip − a_anchor| (classical accelerations,
#: R1) relative to the larger of |g| and the largest anchor acceleration [m/s²].
#: Measured: <= 4.3e-13 m/s² (< 5e-14 relative) on 1000 random states and Table 1; 1e-9
#: is the issue's 1e-8 agreement target with a factor 10 of margin, so a sample passing
#: this check cannot spoil that comparison.
ACCELERATION_RESIDUAL_BOUND = 1e-9
#: Bound on the tree's equation-of-motion residual max |RNEA(q, v, a) − τ − Jcᵀ f|
#: relative to the largest generalized force in it [N, N·m] (measured <= 8e-13 N on
#: forces of hundreds of N); same reasoning as above.
DYNAMICS_RESIDUAL_BOUND = 1e-9


@dataclass(frozen=True)
class ConstrainedDynamics:
    """Forward dynamics on the closed-loop tree, with what was measured along the way.

    Attributes:
        qdd: ``(N, 9)`` independent accelerations [m/s², rad/s²] (NaN in the arm columns
            for a robot without its arm).
        a: ``(N, nv)`` tree accelerations [m/s², rad/s²].
        tree: The :class:`TreeStates` the dynamics was solved at.
        loop_forces: ``(N, 6, 3)`` force exerted by the platform on ``leg{i}_upper`` at
            the sphere centre S_i, in R1 [N] (the platform receives the opposite).
        acceleration_residual: ``(N,)`` max over loops and axes of |a_tip − a_anchor|
            (classical accelerations in R1) [m/s²].
        dynamics_residual: ``(N,)`` max |RNEA(q, v, a) − τ − Jcᵀ f| over the tree joints
            [N, N·m].
        proximal_iterations: ``(N,)`` passes of Pinocchio's proximal solver.
    """

    qdd: np.ndarray
    a: np.ndarray
    tree: TreeStates
    loop_forces: np.ndarray
    acceleration_residual: np.ndarray
    dynamics_residual: np.ndarray
    proximal_iterations: np.ndarray



def constrained_dynamics(robot: Any, q: np.ndarray, qd: np.ndarray, X: np.ndarray,
                         gravity: Any = (0.0, 0.0, -9.81), accuracy: float = ACCURACY,
                         limits: bool = True) -> ConstrainedDynamics:
    """Forward dynamics of the closed-loop robot with Pinocchio's constraint dynamics.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` coordinates [m, rad] (docs/conventions.md).
        qd: Same shape, rates [m/s, rad/s].
        X: Same shape, actuator forces ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]``, signed along
            the joint axes (Fl > 0 extends the leg). Without the arm, the first three
            columns are ignored (they may be NaN, as ``inverse_dynamics`` returns them).
        gravity: ``(3,)`` gravity in R1 [m/s²].
        accuracy: Absolute and relative accuracy of Pinocchio's proximal solver.
        limits: Check the tree joints against their URDF limits.

    Returns:
        :class:`ConstrainedDynamics` with ``(N, ·)`` arrays.

    Raises:
        InputError, WorkspaceError, ModelError: as :func:`tree_states`.
        ConstraintResidualError: a loop-closure, acceleration or equation-of-motion
            residual above its bound, or Pinocchio's solver short of ``accuracy`` after
            :data:`PROXIMAL_MAX_ITER` passes (the message names the sample).
    """
    tree = loop_tree(robot)
    q, qd, X = validated_inputs(tree, q=q, qd=qd, X=X)
    g = as_gravity(gravity)
    accuracy = positive("accuracy", accuracy)
    states = solve_tree(tree, q, qd, NEWTON_TOLERANCE, NEWTON_MAX_ITER, bool(limits))
    pin, model, data, check = tree.pin, tree.model, tree.data, tree.check
    model.gravity = pin.Motion(g, np.zeros(3))
    prox = pin.ProximalSettings(accuracy, accuracy, PROXIMAL_MU, PROXIMAL_MAX_ITER)
    frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    n = len(q)
    A = np.empty((n, model.nv))
    forces = np.empty((n, N_LEGS, 3))
    acc_res = np.empty(n)
    dyn_res = np.empty(n)
    passes = np.empty(n, dtype=int)
    tau = np.zeros(model.nv)
    for k in range(n):
        x, v = states.q[k], states.v[k]
        tau[tree.act] = X[k, tree.act_columns]
        A[k] = pin.constraintDynamics(model, data, x, v, tau, tree.cmodels, tree.cdatas, prox)
        passes[k] = prox.iter
        # Pinocchio stops on either criterion; with mu = 0 the relative one (change of
        # the multipliers between passes) is met at the second pass. Its "absolute
        # residual" omits the M⁻¹(τ − h) part of the right-hand side, so it is not a
        # constraint residual: the measured one is in _measure.
        if not (prox.absolute_residual <= accuracy or prox.relative_residual <= accuracy):
            raise ConstraintResidualError(
                f"Pinocchio's constraintDynamics stopped at sample {k} after {prox.iter} passes "
                f"with relative residual {prox.relative_residual:.3g} > accuracy {accuracy:.3g}",
                index=k, kind="proximal", residual=float(prox.relative_residual),
                bound=accuracy)
        # lambda_c holds, per loop, the force on the leg tip in the tip frame (LOCAL).
        lam = data.lambda_c.reshape(N_LEGS, 3)
        for i, cd in enumerate(tree.cdatas):
            forces[k, i] = cd.oMc1.rotation @ lam[i]
        acc_res[k], dyn_res[k] = _measure(tree, x, v, A[k], tau, forces[k], g, k, frame)
    qdd = np.full((n, 9), np.nan)
    qdd[:, tree.columns] = A[:, tree.indep]
    return ConstrainedDynamics(qdd=qdd, a=A, tree=states, loop_forces=forces,
                               acceleration_residual=acc_res, dynamics_residual=dyn_res,
                               proximal_iterations=passes)


def _measure(tree: LoopTree, x, v, a, tau, forces, g, k: int, frame) -> tuple[float, float]:
    """Acceleration and equation-of-motion residuals of one solved sample (then checked)."""
    pin, model, data = tree.pin, tree.model, tree.check
    pin.forwardKinematics(model, data, x, v, a)
    acc_scale = np.linalg.norm(g)
    acc_res = 0.0
    for tip, anchor in zip(tree.tips, tree.anchors):
        a_tip = pin.getFrameClassicalAcceleration(model, data, tip, frame).linear
        a_anchor = pin.getFrameClassicalAcceleration(model, data, anchor, frame).linear
        acc_res = max(acc_res, np.abs(a_tip - a_anchor).max())
        acc_scale = max(acc_scale, np.abs(a_anchor).max())
    rnea = pin.rnea(model, data, x, v, a).copy()
    _, J = tree.loop_residual(x)
    generalized = J.T @ forces.reshape(-1)
    dyn_res = np.abs(rnea - tau - generalized).max()
    dyn_scale = max(np.abs(rnea).max(), np.abs(tau).max(), np.abs(generalized).max())
    for kind, res, bound, unit in (
            ("acceleration", acc_res, ACCELERATION_RESIDUAL_BOUND * acc_scale, "m/s²"),
            ("dynamics", dyn_res, DYNAMICS_RESIDUAL_BOUND * dyn_scale, "N or N·m")):
        if not res <= bound:
            raise ConstraintResidualError(
                f"{kind} residual {res:.3g} {unit} at sample {k} exceeds its bound "
                f"{bound:.3g} {unit}: the constrained solve is unreliable there (leg "
                "singularity?)", index=k, kind=kind, residual=float(res), bound=float(bound))
    return float(acc_res), float(dyn_res)


def forward_dynamics(robot: Any, q: np.ndarray, qd: np.ndarray, X: np.ndarray,
                     gravity: Any = (0.0, 0.0, -9.81), accuracy: float = ACCURACY) -> np.ndarray:
    """Accelerations q̈ produced by the actuator forces X, by Pinocchio's constraint dynamics.

    The independent reference for ``offshore_crane.forward_dynamics``: see
    :func:`constrained_dynamics` for the arguments, the checks and the errors.

    Returns:
        qdd ``(N, 9)`` (or ``(9,)`` for one ``(9,)`` sample) [m/s², rad/s²].
    """
    single = np.ndim(q) == 1
    qdd = constrained_dynamics(robot, q, qd, X, gravity=gravity, accuracy=accuracy).qdd
    return qdd[0] if single else qdd
