"""Every link's pose in the base frame along a motion, from the URDF alone.

The URDF is the equivalent tree (``docs/conventions.md``): its movable joints are the six
virtual platform joints, the three joints of each leg, the arm's three joints and, with a
hanging load, the two cable joints. :func:`joint_values` sets each of them from the
independent coordinates ``q (N, 9)``:

- ``platform_x, _y, _z, _roll, _pitch, _yaw`` = q1..q6 (so that ``R_base_platform =
  Rz(q6) Ry(q5) Rx(q4)``);
- ``leg{i}_u1, leg{i}_u2`` = the U-joint angles θ1, θ2 [rad] and ``leg{i}_slide`` = the
  leg length l_i [m], from the closed-loop kinematics
  (:func:`offshore_crane.robot.kinematics.legs`), which closes each loop at S_i;
- ``arm_joint1, arm_joint2, arm_slide`` = q7, q8, q9;
- ``cable_joint1, cable_joint2`` = the sway angles φ1, φ2 [rad] (``sway (N, 2)``).

:func:`tree_poses` then composes the joints down the tree (fixed joints included),
vectorised over the N samples: the cost is one pass over the ~50 links, each a batched
3 x 3 product. A joint's ``origin`` places its frame in the parent link's frame; the
child link's frame is the joint frame moved by the joint: a rotation by the joint value
about its axis (revolute), a translation by it along the axis (prismatic).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import ARM_JOINTS, LEG_JOINTS, PLATFORM_JOINTS
from offshore_crane.errors import InputError, ModelError, NumericalError

#: The two cable joints of a hanging load (issue 14): revolute about x at ``arm_tip``,
#: then about y; the sway angles (φ1, φ2) [rad] are their positions.
CABLE_JOINTS = ("cable_joint1", "cable_joint2")


@dataclass(frozen=True)
class Poses:
    """Poses of every link of the URDF along a motion (base frame, z up).

    Attributes:
        links: Link names, parents before children (the root, ``base``, first).
        p: ``(N, L, 3)`` ``p_base_link``: each link frame's origin [m].
        R: ``(N, L, 3, 3)`` ``R_base_link``: maps link coordinates to base coordinates.
    """

    links: tuple
    p: np.ndarray
    R: np.ndarray

    def __len__(self) -> int:
        """Number of samples N."""
        return int(self.p.shape[0])

    def index(self, link: str) -> int:
        """Column of ``link`` in ``p`` and ``R`` (:class:`ModelError` if unknown)."""
        try:
            return self.links.index(link)
        except ValueError:
            raise ModelError(f"the URDF has no link '{link}'", element=link) from None

    def of(self, link: str) -> tuple[np.ndarray, np.ndarray]:
        """``(p_base_link (N, 3) [m], R_base_link (N, 3, 3))`` of one link."""
        k = self.index(link)
        return self.p[:, k], self.R[:, k]


def tree_order(description) -> tuple[tuple, tuple]:
    """The links of a parsed URDF, parents before children, with the joint above each.

    Returns:
        ``(links, joints)``: link names (root first) and, per link, the
        :class:`~offshore_crane.robot.urdf.Joint` whose child it is (None for the root).
    """
    root = description.root
    links, joints = [root], [None]
    k = 0
    while k < len(links):
        for name in description.child_joints.get(links[k], []):
            j = description.joints[name]
            links.append(j.child)
            joints.append(j)
        k += 1
    return tuple(links), tuple(joints)


def has_cable(description) -> bool:
    """Whether the URDF hangs the payload on the two cable joints."""
    return all(name in description.joints for name in CABLE_JOINTS)


def joint_values(robot, q, sway=None) -> dict[str, np.ndarray]:
    """The position of every movable joint of the equivalent tree along ``q``.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` coordinates [m, rad].
        sway: ``(N, 2)`` sway angles (φ1, φ2) [rad] of a hanging load; required exactly
            when the URDF has the cable joints.

    Returns:
        ``{joint name: (N,) [rad or m]}``.

    Raises:
        InputError: ``q`` or ``sway`` malformed or not finite; a sway given to a robot
            without cable, or none given to one with a cable.
        ModelError: the description asks for a hanging load (``payload.cable_length >
            0``) that this URDF does not hold (no cable joints), or the URDF has a movable
            joint this module cannot set.
    """
    from offshore_crane.robot.kinematics import legs
    from offshore_crane.validation import as_samples

    q, _ = as_samples("q", q)
    N = len(q)
    description = robot.description
    values: dict[str, np.ndarray] = {}
    for k, name in enumerate(PLATFORM_JOINTS):
        values[name] = q[:, k]
    leg_joints = [j for j in LEG_JOINTS if j[0] in description.joints]
    if leg_joints:
        state = legs(robot, q)
        for i, (u1, u2, slide) in enumerate(leg_joints):
            values[u1] = state.theta[:, i, 0]
            values[u2] = state.theta[:, i, 1]
            values[slide] = state.length[:, i]
    for k, name in enumerate(ARM_JOINTS):
        if name in description.joints:
            values[name] = q[:, 6 + k]
    cable = has_cable(description)
    length = getattr(robot.spec, "cable_length", 0.0) if robot.spec is not None else 0.0
    if length > 0.0 and not cable:
        raise ModelError(f"payload.cable_length = {length:g} m > 0, but this URDF welds "
                         "the payload to arm_tip (no cable joints): drawing the hanging "
                         "load needs the cable model (issue 14); set payload.cable_length "
                         "= 0 to draw it welded", element="payload.cable_length")
    if cable:
        if sway is None:
            raise InputError("the robot hangs its payload on a cable: give the sway angles "
                             "sway (N, 2) [rad] (phi1, phi2) of each sample", name="sway")
        sway, _ = as_samples("sway", sway, width=2)
        if len(sway) != N:
            raise InputError(f"sway has {len(sway)} samples and q {N}: give one (phi1, "
                             "phi2) per sample of q", name="sway")
        values[CABLE_JOINTS[0]] = sway[:, 0]
        values[CABLE_JOINTS[1]] = sway[:, 1]
    elif sway is not None:
        raise InputError("sway given, but the robot has no cable (its URDF has no "
                         f"{CABLE_JOINTS[0]}): leave it out", name="sway")
    unknown = [j.name for j in description.joints.values()
               if j.type not in ("fixed",) and j.name not in values]
    if unknown:
        raise ModelError(f"the URDF's movable joint(s) {', '.join(unknown)} are not set by "
                         "q or the sway: offshore_crane.outputs.visual draws the hybrid robot's "
                         "equivalent tree only", element=unknown[0])
    return values


def tree_poses(description, values: dict, N: int) -> Poses:
    """Forward kinematics of a URDF tree for given joint positions, batched.

    Args:
        description: A parsed URDF (:class:`~offshore_crane.robot.urdf.URDF`).
        values: ``{joint name: (N,)}`` position of every movable joint [rad or m].
        N: Number of samples.

    Returns:
        :class:`Poses`.
    """
    from offshore_crane.spatial import axis_angle_matrix

    links, joints = tree_order(description)
    L = len(links)
    p = np.empty((N, L, 3))
    R = np.empty((N, L, 3, 3))
    p[:, 0] = 0.0
    R[:, 0] = np.eye(3)
    slot = {name: k for k, name in enumerate(links)}
    for k in range(1, L):
        j = joints[k]
        a = slot[j.parent]
        Rp, pp = R[:, a], p[:, a]
        Rj = Rp @ j.R                                       # (N, 3, 3) joint frame
        pj = pp + Rp @ j.xyz                                # (N, 3)
        if j.type in ("revolute", "continuous"):
            R[:, k] = Rj @ axis_angle_matrix(j.axis, values[j.name])
            p[:, k] = pj
        elif j.type == "prismatic":
            R[:, k] = Rj
            p[:, k] = pj + (Rj @ j.axis) * values[j.name][:, None]
        elif j.type == "fixed":
            R[:, k] = Rj
            p[:, k] = pj
        else:
            raise ModelError(f"joint '{j.name}' is {j.type}: offshore_crane.outputs.visual moves "
                             "revolute, continuous, prismatic and fixed joints only",
                             element=j.name)
    return Poses(links, p, R)


def link_poses(robot, q, sway=None, load=None) -> Poses:
    """Every link's pose in the base frame along ``q`` (and the sway of a hanging load).

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` [m, rad].
        sway: ``(N, 2)`` [rad], with a cable only (see :func:`joint_values`).
        load: ``(N, 3)`` the payload from the tip [m], base axes, for a cable of varying
            length (a winch, an elastic cable): the cable joints take its direction
            (``R_base_tip Rx(φ1) Ry(φ2) (0, 0, −1)``) and the payload sits at the tip plus
            ``load``. Instead of ``sway``.

    Returns:
        :class:`Poses` with N samples (one for ``q (9,)``).

    Raises:
        The errors of :func:`joint_values`; NumericalError: a pose is not finite (the legs
        cannot reach ``q``: a leg through its U-joint centre), naming the sample.
    """
    if load is not None:
        sway = _sway_along(robot, q, np.atleast_2d(np.asarray(load, dtype=float)))
    values = joint_values(robot, q, sway)
    N = len(next(iter(values.values())))
    poses = tree_poses(robot.description, values, N)
    bad = ~np.isfinite(poses.p).all(axis=(1, 2))
    if bad.any():
        k = int(np.argmax(bad))
        raise NumericalError(f"sample {k}: the link poses are not finite (a leg passes "
                             "through its U-joint centre): check q there", index=k)
    if load is not None:
        poses.p[:, poses.index("payload")] = poses.p[:, poses.index("arm_tip")] + load
    return poses


def _sway_along(robot, q, load: np.ndarray) -> np.ndarray:
    """``(N, 2)`` the sway angles (φ1, φ2) [rad] that point the cable along ``load``
    ``(N, 3)`` (base axes): its direction in the tip's axes ``e = (−sin φ2, sin φ1 cos φ2,
    −cos φ1 cos φ2)`` inverted."""
    zero = np.zeros((len(load), 2))
    tip = tree_poses(robot.description, joint_values(robot, q, zero), len(load))
    R = tip.R[:, tip.index("arm_tip")]
    e = np.einsum("nji,nj->ni", R, load / np.linalg.norm(load, axis=1, keepdims=True))
    return np.column_stack([np.arctan2(e[:, 1], -e[:, 2]),
                            np.arcsin(np.clip(-e[:, 0], -1.0, 1.0))])
