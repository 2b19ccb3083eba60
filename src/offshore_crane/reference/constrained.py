"""Closed-loop forward dynamics by Pinocchio's constraint dynamics: an independent reference.

The URDF describes the *equivalent tree* of the robot (docs/conventions.md): the six loops
are cut at the spherical joints, and each cut leaves two massless frames that must
coincide, ``leg{i}_tip`` (on ``leg{i}_upper``) and ``platform_anchor{i}`` (on
``platform``). The platform hangs from ``base`` by six virtual joints ``platform_x``,
``platform_y``, ``platform_z``, ``platform_yaw``, ``platform_pitch``, ``platform_roll``
whose values are exactly the independent coordinates q1..q6 (position of O2 in the base
frame R1 [m]; R_base_platform = Rz(q6) Ry(q5) Rx(q4) [rad]), and the arm joints
``arm_joint1``, ``arm_joint2``, ``arm_slide`` are q7, q8 [rad], q9 [m]. The remaining 18
tree joints (per leg ``leg{i}_u1``, ``leg{i}_u2``, ``leg{i}_slide``) are *passive*: they
follow from q through the 18 scalar loop equations ``p_base_tip_i = p_base_anchor_i``.

This module uses Pinocchio alone (and the joint and frame names above):

1. :func:`tree_states` closes the loops: Newton on the 18 residuals
   ``r = p_base_tip_i − p_base_anchor_i`` [m] over the passive joints, with the
   Jacobian ``∂r/∂q_tree = J_tip − J_anchor`` (linear rows of Pinocchio's frame
   Jacobians in LOCAL_WORLD_ALIGNED, i.e. derivatives of the frame origins in R1),
   independent joints held fixed, each sample warm-started from the previous one. The
   passive speeds follow from the same Jacobian: ``J_p v_p = −J_i v_i``.
2. :func:`constrained_dynamics` solves the forward dynamics with six
   ``RigidConstraintModel(CONTACT_3D)`` loop constraints (Pinocchio's
   ``constraintDynamics``: the KKT system ``M a + h = τ + Jcᵀ λ``, ``Jc a + γ = 0``,
   factorised by Pinocchio's sparse constrained Cholesky [Carpentier, Budhiraja, Mansard,
   "Proximal and sparse resolution of constrained dynamic equations", RSS 2021]), with
   the actuator forces X = [T1, T2, Fs, Fl1..Fl6] as the generalized forces of the joints
   ``arm_joint1``, ``arm_joint2``, ``arm_slide``, ``leg1_slide`` .. ``leg6_slide``
   (signed along the joint axes; Fl > 0 extends the leg) and zero on every passive and
   virtual joint. Since the virtual platform joints and the arm joints *are* q1..q9, their
   tree accelerations are q̈1..q̈9.
3. Every solved sample is checked by measurements that do not trust the solver: the
   relative classical acceleration of each pair of frames (Pinocchio forward kinematics
   with the solved accelerations), and the tree's equation of motion
   ``RNEA(q, v, a) − τ − Jcᵀ f`` with the returned loop forces ``f``.

``RigidConstraintModel`` does not pickle, so the constraint models are built per process
and cached per robot in a module-level weak dictionary (never stored on the robot). Their
``RigidConstraintData`` serve ``constraintDynamics`` only: pin 4.1's ``lcaba`` leaves a
nonzero ``contact_acceleration_desired`` in them that ``constraintDynamics`` would then
take as its target (see ``benchmarks/pinocchio_fd.py``).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import ConstraintResidualError, InputError, ModelError, WorkspaceError, require
from offshore_crane.validation import as_gravity, as_samples, same_length

#: Tree joints realising q1..q6, in the order of q (docs/conventions.md).
PLATFORM_JOINTS = ("platform_x", "platform_y", "platform_z",
                   "platform_roll", "platform_pitch", "platform_yaw")
#: Tree joints realising q7..q9 (absent when the robot is built without its arm).
ARM_JOINTS = ("arm_joint1", "arm_joint2", "arm_slide")
#: Number of U-P-S legs, hence of loops.
N_LEGS = 6
#: Passive joints of each leg, in tree order.
LEG_JOINTS = tuple((f"leg{i}_u1", f"leg{i}_u2", f"leg{i}_slide") for i in range(1, N_LEGS + 1))
#: Joints carrying X = [T1, T2, Fs, Fl1..Fl6], in the order of X.
ACTUATED_JOINTS = ARM_JOINTS + tuple(f"leg{i}_slide" for i in range(1, N_LEGS + 1))

#: Newton tolerance on the loop closure, max |p_tip − p_anchor| [m]. The robot spans
#: about 1 m, where one ulp is 2.2e-16 m; a chain of ~10 rigid transforms accumulates a
#: few ulp, so 1e-13 m (~500 ulp) is reachable and is far below any physical tolerance.
NEWTON_TOLERANCE = 1e-13
#: Newton iteration cap per sample. Measured: 2 steps per sample along Table 1 at 1 kHz
#: (3 at 100 Hz), 4–6 from an unrelated previous sample (random states) or from the
#: neutral legs; 30 steps leave a wide margin while a diverging solve still fails fast.
NEWTON_MAX_ITER = 30
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
#: Bound on the velocity residual max |v_tip − v_anchor| relative to the largest anchor
#: speed [m/s]: the passive speeds come from one 18x18 solve whose condition number is
#: <= 2.8 on 1000 random states (legs far from singular), so the round-off is ~1e-15
#: relative (measured <= 7e-16 m/s); 1e-10 flags a broken solve while tolerating
#: condition numbers up to ~1e5.
VELOCITY_RESIDUAL_BOUND = 1e-10
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
#: Platform test pose (q1..q6) [m, rad] used once per robot to confirm that the virtual
#: joints realise q1..q6 as docs/conventions.md says (generic values: no angle is special).
_PROBE_POSE = np.array([0.011, -0.023, 0.517, 0.13, -0.21, 0.37])
#: Tolerance of that confirmation [m, —]: a few ulp of the probe's magnitudes.
_PROBE_TOLERANCE = 1e-12

_TREES: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


@dataclass(frozen=True)
class TreeStates:
    """Equivalent-tree states that close the six loops.

    Attributes:
        q: ``(N, nq)`` tree configuration in Pinocchio's order (nq = 27 with the arm,
            24 without) [m, rad].
        v: ``(N, nv)`` tree velocity [m/s, rad/s].
        position_residual: ``(N,)`` max over loops and axes of |p_tip − p_anchor| in R1 [m].
        velocity_residual: ``(N,)`` max over loops and axes of |v_tip − v_anchor| [m/s].
        iterations: ``(N,)`` Newton steps taken for each sample.
    """

    q: np.ndarray
    v: np.ndarray
    position_residual: np.ndarray
    velocity_residual: np.ndarray
    iterations: np.ndarray


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


class _Tree:
    """Pinocchio objects and index arrays for one robot (built once per process)."""

    def __init__(self, robot):
        pin = require("pinocchio", "pin", "The constrained-dynamics reference")
        self.pin = pin
        model = robot.pinocchio_model.copy()       # gravity is set on this copy per call
        self.model = model
        self.data = model.createData()             # for constraintDynamics only
        self.check = model.createData()            # for kinematics and the checks
        self.has_arm = model.existJointName(ARM_JOINTS[0])
        independent = PLATFORM_JOINTS + (ARM_JOINTS if self.has_arm else ())
        #: Columns of q (0-based) that exist in this tree.
        self.columns = np.arange(len(independent))
        self.indep = self._indices(independent)
        self.passive = self._indices(sum(LEG_JOINTS, ()))
        actuated = ACTUATED_JOINTS if self.has_arm else ACTUATED_JOINTS[len(ARM_JOINTS):]
        self.act_columns = np.array([ACTUATED_JOINTS.index(n) for n in actuated])
        self.act = self._indices(actuated)
        self.tips = [self._frame(f"leg{i}_tip") for i in range(1, N_LEGS + 1)]
        self.anchors = [self._frame(f"platform_anchor{i}") for i in range(1, N_LEGS + 1)]
        self.lower = model.lowerPositionLimit.copy()
        self.upper = model.upperPositionLimit.copy()
        # Cold start: U-joints at zero, legs at mid-stroke (a leg of zero length would
        # make its U-joint columns of the Jacobian vanish).
        self.start = pin.neutral(model)
        slides = self._indices(tuple(j[2] for j in LEG_JOINTS))
        self.start[slides] = 0.5 * (self.lower[slides] + self.upper[slides])
        self.cmodels = pin.StdVec_RigidConstraintModel()
        self.cdatas = pin.StdVec_RigidConstraintData()
        for tip, anchor in zip(self.tips, self.anchors):
            ft, fa = model.frames[tip], model.frames[anchor]
            cm = pin.RigidConstraintModel(pin.ContactType.CONTACT_3D, model,
                                          ft.parentJoint, ft.placement,
                                          fa.parentJoint, fa.placement,
                                          pin.ReferenceFrame.LOCAL)
            self.cmodels.append(cm)
            self.cdatas.append(cm.createData())
        pin.initConstraintDynamics(model, self.data, self.cmodels, self.cdatas)
        self._confirm_platform_joints()

    def _indices(self, names) -> np.ndarray:
        """Configuration (= velocity) indices of 1-DOF joints ``names``."""
        out = []
        for name in names:
            if not self.model.existJointName(name):
                raise ModelError(f"the URDF has no joint '{name}', which the constrained "
                                 "reference needs (docs/conventions.md names)", element=name)
            joint = self.model.joints[self.model.getJointId(name)]
            if joint.nq != 1 or joint.nv != 1 or joint.idx_q != joint.idx_v:
                raise ModelError(f"joint '{name}' has nq = {joint.nq}, nv = {joint.nv}; the "
                                 "constrained reference needs one-DOF joints (revolute or "
                                 "prismatic with a fixed axis)", element=name)
            out.append(joint.idx_q)
        return np.array(out)

    def _frame(self, name: str) -> int:
        if not self.model.existFrame(name):
            raise ModelError(f"the URDF has no frame '{name}', which marks a loop cut "
                             "(docs/conventions.md)", element=name)
        return self.model.getFrameId(name)

    def _confirm_platform_joints(self) -> None:
        """The virtual joints must put frame ``platform`` at (q1..q3, Rz Ry Rx(q4..q6))."""
        pin = self.pin
        x = self.start.copy()
        x[self.indep[:6]] = _PROBE_POSE
        pin.framesForwardKinematics(self.model, self.check, x)
        placement = self.check.oMf[self._frame("platform")]
        roll, pitch, yaw = _PROBE_POSE[3:]
        expected = _rot_z(yaw) @ _rot_y(pitch) @ _rot_x(roll)
        error = max(np.abs(placement.translation - _PROBE_POSE[:3]).max(),
                    np.abs(placement.rotation - expected).max())
        if not error <= _PROBE_TOLERANCE:
            raise ModelError(f"the virtual joints {', '.join(PLATFORM_JOINTS)} do not realise "
                             "q1..q6 (position, then R = Rz(q6) Ry(q5) Rx(q4)): frame "
                             f"'platform' is off by {error:.3g} at a probe pose; fix the URDF",
                             element="platform")

    # --- one sample -------------------------------------------------------------------

    def loop_residual(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Loop residual ``r (18,)`` [m] and its Jacobian ``(18, nv)`` at configuration x."""
        pin, model, data = self.pin, self.model, self.check
        pin.computeJointJacobians(model, data, x)
        pin.updateFramePlacements(model, data)
        frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
        r = np.empty(3 * N_LEGS)
        J = np.empty((3 * N_LEGS, model.nv))
        for i, (tip, anchor) in enumerate(zip(self.tips, self.anchors)):
            rows = slice(3 * i, 3 * i + 3)
            r[rows] = data.oMf[tip].translation - data.oMf[anchor].translation
            J[rows] = (pin.getFrameJacobian(model, data, tip, frame)[:3]
                       - pin.getFrameJacobian(model, data, anchor, frame)[:3])
        return r, J


def _rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rot_y(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _tree(robot) -> _Tree:
    """The cached :class:`_Tree` of ``robot`` (built on first use in this process)."""
    try:
        return _TREES[robot]
    except KeyError:
        tree = _TREES[robot] = _Tree(robot)
        return tree
    except TypeError:             # not weak-referenceable: build without caching
        return _Tree(robot)


def _samples(name: str, x, ignored: np.ndarray) -> tuple[np.ndarray, bool]:
    """``x`` as ``(N, 9)`` floats; columns ``ignored`` may hold anything (they are unused)."""
    try:
        arr = np.array(x, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an array of numbers", name=name) from None
    if ignored.size and arr.ndim in (1, 2) and arr.shape[-1] == 9:
        arr[..., ignored] = 0.0
    return as_samples(name, arr)


def _positive(name: str, value, integer: bool = False):
    """``value`` as a positive finite float (or integer), else :class:`InputError`."""
    try:
        ok = (not isinstance(value, bool) and np.ndim(value) == 0 and bool(np.isfinite(value))
              and value > 0 and (not integer or float(value) == int(value)))
    except (TypeError, ValueError):
        ok = False
    if not ok:
        kind = "a positive integer" if integer else "a positive finite number"
        raise InputError(f"{name} must be {kind}, got {value!r}", name=name)
    return int(value) if integer else float(value)


def _solve_tree(tree: _Tree, q: np.ndarray, qd: np.ndarray, tolerance: float,
                max_iter: int, limits: bool) -> TreeStates:
    """Newton loop closure and passive speeds for every sample (see :func:`tree_states`)."""
    n, cols = len(q), tree.columns
    Q = np.empty((n, tree.model.nq))
    V = np.zeros((n, tree.model.nv))
    pos = np.empty(n)
    vel = np.empty(n)
    steps = np.empty(n, dtype=int)
    x = tree.start.copy()
    for k in range(n):
        x[tree.indep] = q[k, cols]
        for it in range(max_iter + 1):
            r, J = tree.loop_residual(x)
            err = np.abs(r).max()
            if err <= tolerance:
                break
            if it == max_iter or not np.isfinite(err):
                raise ConstraintResidualError(
                    f"loop closure did not converge at sample {k}: max |p_tip - p_anchor| = "
                    f"{err:.3g} m after {it} Newton steps (tolerance {tolerance:.3g} m); the "
                    "pose may be outside the legs' reach or at a leg singularity",
                    index=k, kind="position", residual=float(err), bound=tolerance)
            x[tree.passive] -= np.linalg.solve(J[:, tree.passive], r)
        Q[k], pos[k], steps[k] = x, err, it
        v_indep = qd[k, cols]
        V[k, tree.indep] = v_indep
        drive = J[:, tree.indep] @ v_indep             # anchor-relative speeds [m/s]
        V[k, tree.passive] = np.linalg.solve(J[:, tree.passive], -drive)
        vel[k] = np.abs(J @ V[k]).max()
        scale = np.abs(drive).max()
        if not vel[k] <= VELOCITY_RESIDUAL_BOUND * scale:
            raise ConstraintResidualError(
                f"velocity loop residual {vel[k]:.3g} m/s at sample {k} exceeds "
                f"{VELOCITY_RESIDUAL_BOUND:.0e} x {scale:.3g} m/s: the leg Jacobian is "
                "(nearly) singular there", index=k, kind="velocity", residual=float(vel[k]),
                bound=float(VELOCITY_RESIDUAL_BOUND * scale))
    if limits:
        _check_limits(tree, Q)
    return TreeStates(q=Q, v=V, position_residual=pos, velocity_residual=vel, iterations=steps)


def _check_limits(tree: _Tree, Q: np.ndarray) -> None:
    """Every tree joint inside its URDF limits (leg strokes, U-joint and arm ranges)."""
    bad = (Q < tree.lower) | (Q > tree.upper)
    if bad.any():
        k, j = np.argwhere(bad)[0]
        joint = next(name for name, jm in zip(tree.model.names, tree.model.joints)
                     if jm.idx_q == j and jm.nq > 0)
        raise WorkspaceError(
            f"{joint} = {Q[k, j]:.6g} at sample {k} is outside its URDF limits "
            f"[{tree.lower[j]:.6g}, {tree.upper[j]:.6g}]; change the state, or pass "
            "limits=False to study it anyway", joint=joint, index=int(k), value=float(Q[k, j]))


def tree_states(robot, q, qd, tolerance: float = NEWTON_TOLERANCE,
                max_iter: int = NEWTON_MAX_ITER, limits: bool = True) -> TreeStates:
    """Tree configurations and velocities that close the six loops, by Pinocchio alone.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` independent coordinates (docs/conventions.md) [m, rad].
        qd: Same shape, their rates [m/s, rad/s].
        tolerance: Newton stops when max |p_tip − p_anchor| <= tolerance [m].
        max_iter: Newton steps allowed per sample.
        limits: Check every tree joint (leg lengths, U-joint angles, arm joints) against
            its URDF limits.

    Returns:
        :class:`TreeStates` with ``(N, ·)`` arrays (also for one sample).

    Raises:
        InputError: bad shapes, NaN/inf, non-positive tolerance or max_iter.
        ConstraintResidualError: Newton did not converge within ``max_iter`` steps, or the
            velocity residual exceeds its bound (the message names the sample).
        WorkspaceError: a tree joint outside its URDF limits (``limits=True``).
        ModelError: the URDF lacks a joint or frame named in docs/conventions.md.
    """
    tree = _tree(robot)
    q, qd = _inputs(tree, q=q, qd=qd)
    return _solve_tree(tree, q, qd, _positive("tolerance", tolerance),
                       _positive("max_iter", max_iter, integer=True), bool(limits))


def _inputs(tree: _Tree, **arrays) -> list[np.ndarray]:
    """Validated ``(N, 9)`` arrays; the columns a robot without its arm does not use (q7..q9
    of q and qd, T1, T2, Fs of X) are not looked at."""
    used = {"X": tree.act_columns}
    out = {name: _samples(name, x, np.setdiff1d(np.arange(9), used.get(name, tree.columns)))[0]
           for name, x in arrays.items()}
    same_length(**out)
    return list(out.values())


def constrained_dynamics(robot, q, qd, X, gravity=(0.0, 0.0, -9.81),
                         accuracy: float = ACCURACY, limits: bool = True) -> ConstrainedDynamics:
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
    tree = _tree(robot)
    q, qd, X = _inputs(tree, q=q, qd=qd, X=X)
    g = as_gravity(gravity)
    accuracy = _positive("accuracy", accuracy)
    states = _solve_tree(tree, q, qd, NEWTON_TOLERANCE, NEWTON_MAX_ITER, bool(limits))
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


def _measure(tree: _Tree, x, v, a, tau, forces, g, k: int, frame) -> tuple[float, float]:
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


def forward_dynamics(robot, q, qd, X, gravity=(0.0, 0.0, -9.81),
                     accuracy: float = ACCURACY) -> np.ndarray:
    """Accelerations q̈ produced by the actuator forces X, by Pinocchio's constraint dynamics.

    The independent reference for ``offshore_crane.forward_dynamics``: see
    :func:`constrained_dynamics` for the arguments, the checks and the errors.

    Returns:
        qdd ``(N, 9)`` (or ``(9,)`` for one ``(9,)`` sample) [m/s², rad/s²].
    """
    single = np.ndim(q) == 1
    qdd = constrained_dynamics(robot, q, qd, X, gravity=gravity, accuracy=accuracy).qdd
    return qdd[0] if single else qdd
