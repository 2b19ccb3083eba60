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

It uses Pinocchio alone (the robot's ``robot.pinocchio_model`` and the names above), and
checks its own results against the URDF only (joint limits, loop residuals); it shares
nothing with the Kane paths:

1. :func:`tree_states` (:mod:`.closure`) closes the loops: Newton on the 18 residuals
   ``r = p_base_tip_i − p_base_anchor_i`` [m] over the passive joints, with the
   Jacobian ``∂r/∂q_tree = J_tip − J_anchor`` (linear rows of Pinocchio's frame
   Jacobians in LOCAL_WORLD_ALIGNED, i.e. derivatives of the frame origins in R1),
   independent joints held fixed, each sample warm-started from the previous one. The
   passive speeds follow from the same Jacobian: ``J_p v_p = −J_i v_i``.
2. :func:`constrained_dynamics` (:mod:`.dynamics`) solves the forward dynamics with six
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

:mod:`.model` holds Pinocchio's objects per robot. ``RigidConstraintModel`` does not
pickle, so the constraint models are built per process and cached per robot in a
module-level weak dictionary (never stored on the robot). Their ``RigidConstraintData``
serve ``constraintDynamics`` only: pin 4.1's ``lcaba`` leaves a nonzero
``contact_acceleration_desired`` in them that ``constraintDynamics`` would then take as
its target (see ``benchmarks/pinocchio_fd.py``).
"""

from offshore_crane.lazy import submodule_getattr

from offshore_crane.conventions import (ACTUATED_JOINTS, ARM_JOINTS, LEG_JOINTS, N_LEGS,
                                        PLATFORM_JOINTS)
from offshore_crane.reference.constrained.closure import (NEWTON_MAX_ITER, NEWTON_TOLERANCE,
                                                          VELOCITY_RESIDUAL_BOUND, TreeStates,
                                                          tree_states)
from offshore_crane.reference.constrained.dynamics import (ACCELERATION_RESIDUAL_BOUND,
                                                           ACCURACY, DYNAMICS_RESIDUAL_BOUND,
                                                           PROXIMAL_MAX_ITER, PROXIMAL_MU,
                                                           ConstrainedDynamics,
                                                           constrained_dynamics,
                                                           forward_dynamics)
from offshore_crane.reference.constrained.model import LoopTree, loop_tree

__all__ = ["ACCELERATION_RESIDUAL_BOUND", "ACCURACY", "ACTUATED_JOINTS", "ARM_JOINTS",
           "DYNAMICS_RESIDUAL_BOUND", "LEG_JOINTS", "N_LEGS", "NEWTON_MAX_ITER",
           "NEWTON_TOLERANCE", "PLATFORM_JOINTS", "PROXIMAL_MAX_ITER", "PROXIMAL_MU",
           "VELOCITY_RESIDUAL_BOUND", "ConstrainedDynamics", "LoopTree", "TreeStates",
           "constrained_dynamics", "forward_dynamics", "loop_tree", "tree_states"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
