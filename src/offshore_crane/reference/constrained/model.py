"""Pinocchio's objects for the constrained reference: the tree, its loop cuts, its indices.

Read from ``robot.pinocchio_model`` (the URDF's equivalent tree) with the joint and frame
names of ``docs/conventions.md`` (:mod:`offshore_crane.conventions`), once per robot and
process (:func:`loop_tree`). ``RigidConstraintModel`` does not pickle, so the constraint
models are cached in a module-level weak dictionary (never stored on the robot).

Frames: the base frame R1 is Pinocchio's world (the URDF root ``base``); units SI.
"""

from __future__ import annotations

import weakref
from typing import Any

import numpy as np

from offshore_crane.conventions import (ACTUATED_JOINTS, ARM_JOINTS, LEG_JOINTS, LEG_TIPS, N_LEGS,
                                        PLATFORM_ANCHORS, PLATFORM_JOINTS)
from offshore_crane.errors import ModelError, require
from offshore_crane.spatial import attitude_matrix

#: Platform test pose (q1..q6) [m, rad] used once per robot to confirm that the virtual
#: joints realise q1..q6 as docs/conventions.md says (generic values: no angle is special).
_PROBE_POSE = np.array([0.011, -0.023, 0.517, 0.13, -0.21, 0.37])
#: Tolerance of that confirmation [m, —]: a few ulp of the probe's magnitudes.
_PROBE_TOLERANCE = 1e-12

_TREES: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


class LoopTree:
    """Pinocchio objects and index arrays for one robot (built once per process)."""

    def __init__(self, robot: Any):
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
        self.tips = [self._frame(name) for name in LEG_TIPS]
        self.anchors = [self._frame(name) for name in PLATFORM_ANCHORS]
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
        expected = attitude_matrix(*_PROBE_POSE[3:])
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


def loop_tree(robot: Any) -> LoopTree:
    """The cached :class:`LoopTree` of ``robot`` (built on first use in this process).

    Raises:
        ModelError: the URDF lacks a joint or frame named in docs/conventions.md, or its
            virtual joints do not realise q1..q6.
    """
    try:
        return _TREES[robot]
    except KeyError:
        tree = _TREES[robot] = LoopTree(robot)
        return tree
    except TypeError:             # not weak-referenceable: build without caching
        return LoopTree(robot)
