"""What the RNEA reference reads of the robot: its serial chains, from Pinocchio's model.

The robot is read by attribute only: ``robot.pinocchio_model`` (Pinocchio's model of the
URDF's equivalent tree) and the joint and frame names of ``docs/conventions.md``
(:mod:`offshore_crane.conventions`). Each chain is a list of 1-DOF joints with their
placements in the parent joint frame, their axes and types, as Pinocchio parsed them.

Frames: the base frame is Pinocchio's world (the URDF root ``base``); units SI.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from offshore_crane.conventions import ARM_JOINTS, LEG_TIPS, PLATFORM_ANCHORS, PLATFORM_JOINTS
from offshore_crane.errors import ModelError, NumericalError, require

_MODELS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()

class Chain(NamedTuple):
    """Serial chains of 1-DOF joints read from Pinocchio's model, stacked.

    Attributes:
        R, p: ``(m, n, 3, 3)``, ``(m, n, 3)`` joint placements in the parent joint frame.
        axis: ``(m, n, 3)`` unit axis in the joint frame; ``prismatic``: ``(m, n)``.
        R_end, p_end: ``(m, 3, 3)``, ``(m, 3)`` the end frame in the last joint's frame.
        coordinate: ``(m, n)`` index of each joint's coordinate (in q1..q9, or -1).
        v_index: ``(m, n)`` velocity index of each joint in the tree.
    """

    R: np.ndarray
    p: np.ndarray
    axis: np.ndarray
    prismatic: np.ndarray
    R_end: np.ndarray
    p_end: np.ndarray
    coordinate: np.ndarray
    v_index: np.ndarray


@dataclass(frozen=True)
class Tree:
    """What the reference reads of Pinocchio's model of the URDF."""

    platform: Chain       # one chain per anchor (6), the platform's virtual joints
    legs: Chain           # one chain per leg tip (6): u1, u2, slide
    arm_v: np.ndarray     # velocity indices of the arm joints (0 or 3)
    plat_v: np.ndarray    # velocity indices of q1..q6's joints
    nv: int
    L: float              # mean |S_i − O2| [m]: scales the rotation rows of Jlᵀ


def _joint_axis(jmodel) -> tuple[np.ndarray, bool]:
    """Unit axis (in the joint frame) and type of a 1-DOF joint from its motion subspace."""
    data = jmodel.createData()
    jmodel.calc(data, np.zeros(jmodel.nq))
    S = np.asarray(data.S).reshape(6)
    lin, ang = S[:3], S[3:]
    if np.linalg.norm(ang) > 0.5:
        return ang / np.linalg.norm(ang), False
    return lin / np.linalg.norm(lin), True


def _chain(model, frame: str, coordinates: dict) -> tuple:
    fid = model.getFrameId(frame)
    if fid >= len(model.frames):
        raise NumericalError(f"the tree has no frame '{frame}'", name=frame)
    f = model.frames[fid]
    joints = []
    j = f.parentJoint
    while j > 0:
        joints.append(j)
        j = model.parents[j]
    joints.reverse()
    R, p, axis, prism, coord, vidx = [], [], [], [], [], []
    for j in joints:
        M = model.jointPlacements[j]
        a, is_p = _joint_axis(model.joints[j])
        R.append(M.rotation)
        p.append(M.translation)
        axis.append(a)
        prism.append(is_p)
        coord.append(coordinates.get(model.names[j], -1))
        vidx.append(model.idx_vs[j])
    return (np.array(R), np.array(p), np.array(axis), np.array(prism), f.placement.rotation,
            f.placement.translation, np.array(coord), np.array(vidx))


def _stack(chains) -> Chain:
    return Chain(*(np.ascontiguousarray(np.array([c[k] for c in chains])) for k in range(8)))


def read_tree(robot: Any) -> Tree:
    """The reference's view of ``robot.pinocchio_model`` (cached per robot).

    Raises:
        ModelError: the six platform anchors do not hang from the platform's six virtual
            joints, or a leg is not revolute, revolute, prismatic.
    """
    out = _MODELS.get(robot)
    if out is None:
        require("pinocchio", "pin", "The RNEA reference")
        model = robot.pinocchio_model
        coords = {name: k for k, name in enumerate(PLATFORM_JOINTS)}
        plat = _stack([_chain(model, a, coords) for a in PLATFORM_ANCHORS])
        legs = _stack([_chain(model, t, {}) for t in LEG_TIPS])
        if (not (plat.v_index == plat.v_index[0]).all()
                or sorted(plat.coordinate[0]) != list(range(6)) or legs.v_index.shape[1] != 3
                or not (legs.prismatic == [False, False, True]).all()):
            raise ModelError("the RNEA reference needs the six platform anchors on the "
                             "platform's six virtual joints and three joints per leg "
                             "(revolute, revolute, prismatic)",
                             element="platform")
        arm_v = np.array([model.idx_vs[model.getJointId(n)] for n in ARM_JOINTS
                          if model.existJointName(n)], dtype=np.int64)
        plat_v = np.array([model.idx_vs[model.getJointId(n)] for n in PLATFORM_JOINTS],
                          dtype=np.int64)
        L = float(np.mean([np.linalg.norm(p) for p in plat.p_end]))
        out = _MODELS[robot] = Tree(plat, legs, arm_v, plat_v, model.nv, L)
    return out
