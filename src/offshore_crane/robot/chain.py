"""Serial chains read from a URDF: the structure the arm recursion of the formulas needs.

A chain is a sequence of bodies, body ``k`` being moved by joint ``k`` (revolute,
continuous or prismatic) relative to body ``k-1``; body ``-1`` is the *base*, which may
itself move (the hybrid robot's platform) or be fixed (a robot arm on the ground). Links
welded by fixed joints are merged into one rigid body (exact: the mass properties add). A
continuous joint is a revolute joint without limits (one angle). The kinematics of a chain
(paper Eqs. 27-30, recursive form) is :func:`offshore_crane.robot.kinematics.formulas.arm_child`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from offshore_crane.errors import ModelError
from offshore_crane.robot.urdf import MOVABLE, URDF


@dataclass(frozen=True)
class SerialChain:
    """What Kane's method needs of a serial chain, read from a URDF.

    Attributes:
        base_link: Name of the base link.
        joint_names: ``(n,)`` movable joints in chain order.
        body_names: ``(n,)`` child link of each joint (welded links merged into it).
        prismatic: ``(n,)`` bool, True for a prismatic joint.
        p_parent_joint: ``(n, 3)`` joint origin in the parent body frame [m].
        R_parent_joint: ``(n, 3, 3)`` joint frame orientation in the parent body frame.
        axis: ``(n, 3)`` unit joint axis in the joint frame.
        mass: ``(n,)`` body masses [kg].
        com: ``(n, 3)`` centres of mass in the body frames [m].
        inertia: ``(n, 3, 3)`` central inertias in body axes [kg·m²].
        lower, upper: ``(n,)`` joint limits [rad or m].
        frames: ``{name: (body index, p_body_frame (3,), R_body_frame (3, 3))}`` for every
            welded link (``-1`` for links welded to the base).
        tip: The link the chain was cut at (``tip`` of :func:`chain_from_urdf`), or None.
        locked: Movable joints below the base but off the base→tip path, locked at zero
            position (their links welded to their parents as at q = 0); empty without tip.
    """

    base_link: str
    joint_names: tuple
    body_names: tuple
    prismatic: np.ndarray
    p_parent_joint: np.ndarray
    R_parent_joint: np.ndarray
    axis: np.ndarray
    mass: np.ndarray
    com: np.ndarray
    inertia: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    frames: dict
    tip: str | None = None
    locked: tuple = ()

    @property
    def n(self) -> int:
        """Number of movable joints."""
        return len(self.joint_names)


def merged_inertial(urdf: URDF, link: str):
    """Mass properties of ``link`` and every link welded to it, in ``link``'s frame.

    Returns:
        ``(mass [kg], com (3,) [m], central inertia (3, 3) [kg·m²], welded)`` where
        ``welded`` is :meth:`URDF.rigid_group`'s list.
    """
    welded = urdf.rigid_group(link)
    mass, first = 0.0, np.zeros(3)
    parts = []
    for name, p, R in welded:
        inertial = urdf.inertial(name)
        if inertial is None or inertial.mass == 0.0:
            continue
        c = p + R @ inertial.com
        parts.append((inertial.mass, c, R @ inertial.inertia @ R.T))
        mass += inertial.mass
        first += inertial.mass * c
    if mass == 0.0:
        return 0.0, np.zeros(3), np.zeros((3, 3)), welded
    com = first / mass
    inertia = np.zeros((3, 3))
    for m, c, I in parts:  # parallel-axis theorem
        d = c - com
        inertia += I + m * (d @ d * np.eye(3) - np.outer(d, d))
    return mass, com, inertia, welded


def path_joints(urdf: URDF, base_link: str, tip: str) -> list[str]:
    """Joints (fixed ones included) on the path from ``base_link`` down to link ``tip``.

    Raises:
        ModelError: ``tip`` is not a link of the URDF, or is not below ``base_link``.
    """
    if tip not in urdf.inertials:
        raise ModelError(f"the URDF has no link or frame '{tip}' (the tip asked for)",
                         element=tip)
    path, link = [], tip
    while link != base_link:
        jname = urdf.parent_joint.get(link)
        if jname is None:
            raise ModelError(f"the tip '{tip}' is not below the base link '{base_link}'",
                             element=tip)
        path.append(jname)
        link = urdf.joints[jname].parent
    return path[::-1]


def lock_off_path(urdf: URDF, base_link: str, tip: str) -> tuple[URDF, tuple]:
    """A copy of ``urdf`` whose movable joints below ``base_link`` and off the path to
    ``tip`` are made fixed at their zero position (mimic, floating and planar included).

    Returns:
        ``(urdf, locked)``: the modified URDF (the input is not changed) and the names of
        the locked joints in depth-first order.
    """
    on_path = set(path_joints(urdf, base_link, tip))
    joints, locked = dict(urdf.joints), []
    stack = list(reversed(urdf.child_joints.get(base_link, [])))
    while stack:  # depth-first, in file order
        jname = stack.pop()
        j = urdf.joints[jname]
        if j.type != "fixed" and jname not in on_path:
            # At q = 0 the child frame is the joint frame: a fixed joint with the same
            # origin welds it exactly there.
            joints[jname] = replace(j, type="fixed", axis=np.zeros(3), mimic=None)
            locked.append(jname)
        stack += reversed(urdf.child_joints.get(j.child, []))
    return URDF(urdf.name, urdf.inertials, joints, urdf.child_joints, urdf.parent_joint), \
        tuple(locked)


def chain_from_urdf(urdf: URDF, base_link: str, stop_at: tuple = (),
                    tip: str | None = None) -> SerialChain:
    """Follow the movable joints below ``base_link`` as one serial chain.

    Args:
        urdf: Parsed URDF.
        base_link: Link the chain is mounted on.
        stop_at: Joint names below which not to descend (they are not part of the chain).
        tip: Optional link (or welded frame) to end the chain at: only the movable joints
            on the path from ``base_link`` to ``tip`` are kept; every other movable joint
            below ``base_link`` is locked at zero position, its links welded (see
            :func:`lock_off_path`). Lets a chain be cut out of a branching tree.

    Raises:
        ModelError: a body has two movable children (branching, naming both joints), or a
            joint is floating, planar or mimics another, or ``tip`` is not below
            ``base_link``.
    """
    locked = ()
    if tip is not None:
        urdf, locked = lock_off_path(urdf, base_link, tip)
    names, bodies, prism, ps, Rs, axes, masses, coms, inertias, lo, up = ([] for _ in range(11))
    frames = {name: (-1, p, R) for name, p, R in urdf.rigid_group(base_link)}
    link = base_link
    while True:
        children = [j for j in urdf.movable_children(link) if j.name not in stop_at]
        if not children:
            break
        if len(children) > 1:
            raise ModelError(
                f"the chain branches below link '{link}' (joints "
                f"{', '.join(repr(j.name) for j in children)}): give a URDF whose movable "
                "joints form one serial chain, or a tip link to cut one out of the tree",
                element=children[1].name)
        j = children[0]
        if j.type not in MOVABLE:
            raise ModelError(f"joint '{j.name}' is {j.type}: a serial chain takes revolute, "
                             "continuous and prismatic joints only", element=j.name)
        if j.mimic is not None:
            raise ModelError(f"joint '{j.name}' mimics '{j.mimic}': mimic joints are not "
                             "supported, remove the <mimic> element", element=j.name)
        # The joint may hang from a link welded to the current body: compose placements.
        _, p_w, R_w = next((f for f in urdf.rigid_group(link) if f[0] == j.parent))
        mass, com, inertia, welded = merged_inertial(urdf, j.child)
        k = len(names)
        for name, p, R in welded:
            frames[name] = (k, p, R)
        names.append(j.name)
        bodies.append(j.child)
        prism.append(j.type == "prismatic")
        ps.append(p_w + R_w @ j.xyz)
        Rs.append(R_w @ j.R)
        axes.append(j.axis)
        masses.append(mass)
        coms.append(com)
        inertias.append(inertia)
        lo.append(j.lower)
        up.append(j.upper)
        link = j.child
    n = len(names)
    return SerialChain(
        base_link, tuple(names), tuple(bodies), np.array(prism, dtype=bool),
        np.array(ps).reshape(n, 3), np.array(Rs).reshape(n, 3, 3), np.array(axes).reshape(n, 3),
        np.array(masses), np.array(coms).reshape(n, 3), np.array(inertias).reshape(n, 3, 3),
        np.array(lo), np.array(up), frames, tip, locked)
