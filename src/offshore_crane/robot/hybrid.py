"""The hybrid robot's structure, read from its expanded URDF (docs/conventions.md names).

Nothing here is a number of the robot: every mass, length and axis comes from the URDF.
The reader checks that the URDF has the structure the closed-form leg kinematics relies
on, and says what is wrong otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from offshore_crane.conventions import (ACTUATED_JOINTS, ACTUATORS, ACTUATOR_UNITS, AIR_DENSITY,
                                        ARM_JOINTS, CABLE_JOINTS, N_LEGS, PLATFORM_JOINTS)
from offshore_crane.errors import ModelError
from offshore_crane.robot.chain import SerialChain, chain_from_urdf, merged_inertial
from offshore_crane.robot.urdf import URDF

__all__ = ["HybridModel", "hybrid_from_urdf", "ACTUATED_JOINTS", "ACTUATORS",
           "ACTUATOR_UNITS", "ARM_JOINTS", "N_LEGS", "PLATFORM_JOINTS"]
_PLATFORM_CHAIN = ("platform_x", "platform_y", "platform_z",
                   "platform_yaw", "platform_pitch", "platform_roll")
_PLATFORM_AXES = {"platform_x": (1, 0, 0), "platform_y": (0, 1, 0), "platform_z": (0, 0, 1),
                  "platform_yaw": (0, 0, 1), "platform_pitch": (0, 1, 0),
                  "platform_roll": (1, 0, 0)}
_TOL = 1e-12


@dataclass(frozen=True)
class HybridModel:
    """Arrays of the hybrid robot, in the frames named by each attribute.

    Attributes:
        platform_mass: [kg], platform and every link welded to it (arm column).
        platform_com: ``(3,)`` its centre of mass in the platform frame [m].
        platform_inertia: ``(3, 3)`` its central inertia, platform axes [kg·m²].
        p_platform_S: ``(6, 3)`` sphere centres S_i in the platform frame [m].
        p_base_P: ``(6, 3)`` U-joint centres P_i in the base frame [m].
        R_base_U: ``(6, 3, 3)`` orientation of each ``leg{i}_u1`` joint frame; its y axis
            is the first U-joint axis a1 and its z axis the leg direction at zero angles.
        lower_mass, upper_mass: ``(6,)`` [kg].
        lower_com, upper_com: ``(6, 3)`` centres of mass in the lower link frame (origin
            P_i) and upper link frame (origin S_i), both with the leg along z [m].
        lower_inertia, upper_inertia: ``(6, 3, 3)`` central inertias [kg·m²].
        stroke: ``(6, 2)`` shortest and longest leg length [m].
        ujoint_limits: ``(6, 2, 2)`` [leg, axis, (lower, upper)] [rad].
        arm: The arm as a :class:`SerialChain` mounted on the platform; it has no
            joints for a Stewart platform without arm (xacro argument ``with_arm = 0``).
            A payload on a cable is not part of it.
        cable: With a hanging payload (``payload.cable_length > 0``), the arm chain
            continued by the two sway joints ``cable_joint1``, ``cable_joint2`` and the
            payload below them (5 joints: q7, q8, q9, phi1, phi2); None otherwise.
        sway_damping: ``(2,)`` viscous damping of the sway joints [N·m·s/rad] (their URDF
            ``<dynamics damping>``); zeros without a cable.
        drag_area: The hanging payload's drag area C_d·A [m²] (the URDF's ``<drag>`` of
            the link ``payload``; 0 without drag or cable). air_density: [kg/m³].
    """

    platform_mass: float
    platform_com: np.ndarray
    platform_inertia: np.ndarray
    p_platform_S: np.ndarray
    p_base_P: np.ndarray
    R_base_U: np.ndarray
    lower_mass: np.ndarray
    lower_com: np.ndarray
    lower_inertia: np.ndarray
    upper_mass: np.ndarray
    upper_com: np.ndarray
    upper_inertia: np.ndarray
    stroke: np.ndarray
    ujoint_limits: np.ndarray
    arm: SerialChain
    cable: SerialChain | None = None
    sway_damping: np.ndarray = field(default_factory=lambda: np.zeros(2))
    drag_area: float = 0.0
    air_density: float = AIR_DENSITY

    @property
    def drag(self) -> float:
        """``½ ρ C_d A`` [kg/m]: the payload's drag force is ``−drag |v| v`` [N] at the
        velocity v [m/s] relative to still air (0 without drag)."""
        return 0.5 * self.air_density * self.drag_area

    @property
    def has_arm(self) -> bool:
        """True when the crane arm is present (``with_arm = 1``)."""
        return self.arm.n > 0

    @cached_property
    def actuators(self) -> tuple:
        """Names of the actuators that exist (of :data:`ACTUATORS`)."""
        return ACTUATORS[:self.arm.n] + ACTUATORS[3:]

    @cached_property
    def massless_legs(self) -> bool:
        """True when no leg link has mass or inertia (their inertia terms are exact zeros)."""
        return not (self.lower_mass.any() or self.upper_mass.any()
                    or self.lower_inertia.any() or self.upper_inertia.any())

    @property
    def total_mass(self) -> float:
        """Mass of all bodies [kg] (the contract's 17, fewer without arm, plus a payload,
        welded or hanging)."""
        hanging = 0.0 if self.cable is None else float(self.cable.mass[self.arm.n:].sum())
        return float(self.platform_mass + self.lower_mass.sum() + self.upper_mass.sum()
                     + self.arm.mass.sum() + hanging)

    @property
    def cable_length(self) -> float:
        """Length of the payload's cable [m] (0 for a welded payload): the distance from
        ``cable_joint2`` to the payload's centre of mass, read from the URDF."""
        return 0.0 if self.cable is None else float(np.linalg.norm(self.cable.com[-1]))


def _check(cond: bool, message: str, element: str):
    if not cond:
        raise ModelError(message, element=element)


def _drag(urdf, cable: bool) -> dict:
    """``drag_area`` [m²] and ``air_density`` [kg/m³] of the hanging payload from the
    URDF's ``<drag>`` of the link ``payload`` (none: no drag).

    Raises:
        ModelError: a drag on a payload that does not hang on a cable.
    """
    area, rho = urdf.drag.get("payload", (0.0, AIR_DENSITY))
    _check(cable or area == 0.0, "the URDF gives the link 'payload' a <drag>, but the "
           "payload does not hang on a cable (joints cable_joint1, cable_joint2)", "payload")
    return {"drag_area": float(area), "air_density": float(rho)}


def _near(a, b) -> bool:
    return bool(np.allclose(a, b, rtol=0.0, atol=_TOL))


def hybrid_from_urdf(urdf: URDF) -> HybridModel:
    """Extract :class:`HybridModel` from the equivalent-tree URDF.

    Raises:
        ModelError: naming the link or joint that breaks the expected structure.
    """
    _check(urdf.root == "base", f"the root link is '{urdf.root}', expected 'base'", urdf.root)
    parent = "base"
    for name in _PLATFORM_CHAIN:
        j = urdf.joint(name)
        _check(j.parent == parent, f"joint '{name}' should hang from '{parent}'", name)
        expected = "prismatic" if name in PLATFORM_JOINTS[:3] else "revolute"
        _check(j.type == expected and _near(j.axis, _PLATFORM_AXES[name])
               and _near(j.xyz, 0.0) and _near(j.R, np.eye(3)),
               f"virtual joint '{name}' must be {expected} about {_PLATFORM_AXES[name]} "
               "with a zero origin", name)
        inertial = urdf.inertial(j.child)
        _check(j.child == "platform" or inertial is None or inertial.mass == 0.0,
               f"virtual link '{j.child}' must be massless", j.child)
        parent = j.child
    _check(parent == "platform", "the virtual joints must end at link 'platform'", parent)

    pm, pc, pI, welded = merged_inertial(urdf, "platform")
    frames = {name: p for name, p, _ in welded}
    S, P, RU, stroke, ulim = [], [], [], [], []
    lower, upper = [], []
    for i in range(1, N_LEGS + 1):
        anchor = f"platform_anchor{i}"
        _check(anchor in frames, f"frame '{anchor}' must be welded to 'platform'", anchor)
        S.append(frames[anchor])
        u1, u2, sl = (urdf.joint(f"leg{i}_{s}") for s in ("u1", "u2", "slide"))
        _check(u1.parent == "base" and u1.type == "revolute" and _near(u1.axis, (0, 1, 0)),
               f"'{u1.name}' must be a revolute joint on 'base' about y of its frame", u1.name)
        _check(u2.parent == u1.child and u2.type == "revolute" and _near(u2.axis, (1, 0, 0))
               and _near(u2.xyz, 0.0) and _near(u2.R, np.eye(3)),
               f"'{u2.name}' must follow '{u1.name}' with a zero origin, about x", u2.name)
        _check(urdf.inertial(u1.child) is None or urdf.inertial(u1.child).mass == 0.0,
               f"the U-joint cross '{u1.child}' must be massless", u1.child)
        _check(sl.parent == u2.child and sl.type == "prismatic" and _near(sl.axis, (0, 0, 1))
               and _near(sl.xyz, 0.0) and _near(sl.R, np.eye(3)),
               f"'{sl.name}' must follow '{u2.name}' with a zero origin, along z, so that "
               "its position is the leg length", sl.name)
        _check(sl.lower > 0.0 and sl.upper > sl.lower,
               f"'{sl.name}' needs limits 0 < lower < upper (the leg stroke) [m]", sl.name)
        tip = {name: p for name, p, _ in urdf.rigid_group(sl.child)}
        _check(f"leg{i}_tip" in tip and _near(tip[f"leg{i}_tip"], 0.0),
               f"frame 'leg{i}_tip' must be welded to '{sl.child}' at its origin", f"leg{i}_tip")
        P.append(u1.xyz)
        RU.append(u1.R)
        stroke.append((sl.lower, sl.upper))
        ulim.append(((u1.lower, u1.upper), (u2.lower, u2.upper)))
        lower.append(merged_inertial(urdf, u2.child)[:3])
        upper.append(merged_inertial(urdf, sl.child)[:3])
    arm = chain_from_urdf(urdf, "platform", stop_at=CABLE_JOINTS[:1])
    _check(arm.joint_names in (ARM_JOINTS, ()),
           f"the arm's joints are {arm.joint_names}, expected {ARM_JOINTS} (or none: a "
           "Stewart platform without arm)", "arm")
    cable = None
    if CABLE_JOINTS[0] in urdf.joints:
        cable = chain_from_urdf(urdf, "platform")
        _check(cable.joint_names == ARM_JOINTS + CABLE_JOINTS
               and all(urdf.joint(j).type == "revolute" for j in CABLE_JOINTS),
               f"the hanging load's chain is {cable.joint_names}, expected "
               f"{ARM_JOINTS + CABLE_JOINTS} (revolute sway joints)", CABLE_JOINTS[0])
        _check(_near(cable.axis[3], (1, 0, 0)) and _near(cable.axis[4], (0, 1, 0))
               and _near(cable.p_parent_joint[4], 0.0) and _near(cable.R_parent_joint[4],
                                                                  np.eye(3))
               and cable.mass[3] == 0.0 and _near(cable.com[4][:2], 0.0)
               and cable.com[4][2] < 0.0 and _near(cable.inertia[4], 0.0)
               and cable.mass[4] > 0.0,
               "the sway joints must be about x then y at one point, the cable link "
               "massless and the payload a point mass below them on the cable", CABLE_JOINTS[0])
    return HybridModel(
        platform_mass=pm, platform_com=pc, platform_inertia=pI,
        p_platform_S=np.array(S), p_base_P=np.array(P), R_base_U=np.array(RU),
        lower_mass=np.array([x[0] for x in lower]), lower_com=np.array([x[1] for x in lower]),
        lower_inertia=np.array([x[2] for x in lower]),
        upper_mass=np.array([x[0] for x in upper]), upper_com=np.array([x[1] for x in upper]),
        upper_inertia=np.array([x[2] for x in upper]),
        stroke=np.array(stroke), ujoint_limits=np.array(ulim), arm=arm, cable=cable,
        sway_damping=np.array([urdf.joint(j).damping if cable is not None else 0.0
                               for j in CABLE_JOINTS]),
        **_drag(urdf, cable is not None))
