"""What a resolved description holds: bodies, arm joints, actuator capacities
(:class:`Description`, the input of the xacro).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, is_dataclass

import numpy as np

from offshore_crane.conventions import AIR_DENSITY
from offshore_crane.robot.description.geometry import floats, inertia6, visual
from offshore_crane.robot.description.schema import ARM_BODIES, FORMAT, N_LEGS


# ========================================================================== results
@dataclass(frozen=True)
class Capacities:
    """The actuators' capacities, in the order of X (T1, T2, Fs, Fl1..Fl6).

    Attributes:
        names: ``(9,)`` actuator names.
        push_max: ``(9,)`` largest force [N] (torque [N·m]) along + of the joint, ≥ 0;
            ``inf`` when not given.
        pull_max: ``(9,)`` largest magnitude along −, ≥ 0; ``inf`` when not given.
        speed_max: ``(9,)`` largest |rate| [m/s or rad/s]; ``inf`` when not given.
        power_max: ``(9,)`` largest |force × rate| [W]; ``inf`` when not given.
    """

    names: tuple
    push_max: np.ndarray
    pull_max: np.ndarray
    speed_max: np.ndarray
    power_max: np.ndarray

    def effort(self) -> np.ndarray:
        """``(9,)`` URDF effort limits: ``max(push_max, pull_max)``."""
        return np.maximum(self.push_max, self.pull_max)


@dataclass(frozen=True)
class WinchCapacities:
    """A winch's capacities (``actuators.winch``), each ``inf`` when not given.

    Attributes:
        pull_max: Largest line pull [N]. speed_max: largest |L̇| [m/s].
        acceleration_max: Largest |L̈| [m/s²]. power_max: largest |Fw L̇| [W].
        reflected_mass: The drum's and drive's inertia reflected to the line, ``J / r²``
            [kg] (not a capacity): > 0 makes the winch a commanded actuator of the
            elastic lift's simulation (its line pull a force, ``m_w L̈ = T − Fw``); 0
            (the default) an ideal winch whose length follows its profile.
    """

    pull_max: float = math.inf
    speed_max: float = math.inf
    acceleration_max: float = math.inf
    power_max: float = math.inf
    reflected_mass: float = 0.0

    def given(self) -> bool:
        """True when every capacity is given (a winch can be judged)."""
        return all(math.isfinite(v) for v in (self.pull_max, self.speed_max,
                                             self.acceleration_max, self.power_max))


@dataclass(frozen=True)
class LoadLimits:
    """Limits of a hanging load (``payload.limits``), judged by ``size`` like the
    actuators' capacities.

    Attributes:
        sway_max: Largest angle of the cable from the tip's vertical [rad] (inf: none).
        tension_ratio_min: Smallest cable tension over the static tension m·|g| [-]
            (the slack criterion of offshore lifting rules, commonly 0.1; NaN: not
            judged).
        tension_max: Largest cable tension [N] (inf: none).
    """

    sway_max: float = math.inf
    tension_ratio_min: float = math.nan
    tension_max: float = math.inf


@dataclass(frozen=True)
class Body:
    """Mass properties and drawing of one rigid body, in its frame.

    Attributes:
        mass: [kg]. com: ``(3,)`` [m]. inertia: ``(3, 3)`` about the CoM [kg·m²].
        visual: ``{"type", "radius", "length", "size", "xyz"}`` of its drawing.
    """

    mass: float
    com: np.ndarray
    inertia: np.ndarray
    visual: dict


@dataclass(frozen=True)
class ArmJoint:
    """An arm joint and the body it moves.

    Attributes:
        origin: ``(3,)`` joint origin in the parent body frame [m]. rpy: ``(3,)`` [rad].
        axis: ``(3,)`` unit axis in the joint frame. lower, upper: limits [rad or m].
        prismatic: True for ``arm_slide``. body: :class:`Body` in the joint frame.
    """

    origin: np.ndarray
    rpy: np.ndarray
    axis: np.ndarray
    lower: float
    upper: float
    prismatic: bool
    body: Body


@dataclass(frozen=True)
class Description:
    """A resolved robot description: every number explicit, checked.

    Attributes:
        name, source: Label and provenance text.
        path: The file it was read from.
        overrides: ``{dotted name: value}`` applied to the file.
        home_height: q3 of the home pose [m].
        p_base_P: ``(6, 3)`` U-joint centres, base frame [m].
        p_platform_S: ``(6, 3)`` sphere centres, platform frame [m].
        a1: ``(6, 3)`` first U-joint axes (unit), base frame.
        R_base_U: ``(6, 3, 3)`` the ``leg{i}_u1`` joint frames (y = a1, z = the leg
            direction at zero U-joint angles).
        rpy_U: ``(6, 3)`` the same as URDF rpy [rad].
        lower, upper: ``(6,)`` tuples of :class:`Body` (part frames).
        part_length: ``(6, 2)`` lower and upper part lengths [m].
        stroke: ``(6, 2)`` [m]. ujoint_limit: ``(6,)`` [rad].
        platform: :class:`Body` (platform frame, origin O2).
        base_visual: drawing of the base.
        arm: None without arm, else ``{"column": (origin, rpy, Body), "link1":
            ArmJoint, "link2": ..., "slider": ..., "tip": (origin, rpy)}``.
        payload: :class:`Body` in the arm_tip frame (mass 0: none).
        cable_length: [m].
        sway_damping: [N·m·s/rad].
        drag_area: the payload's C_d·A [m²] (0: no drag); air_density: [kg/m³].
        capacities: :class:`Capacities`.
        load_limits: :class:`LoadLimits` of a hanging load.
        winch: :class:`WinchCapacities` (``actuators.winch``).
        values: ``{dotted name: value}`` of every numeric field given (after overrides
            and expressions).
    """

    name: str
    source: str
    path: str
    overrides: dict
    home_height: float
    p_base_P: np.ndarray
    p_platform_S: np.ndarray
    a1: np.ndarray
    R_base_U: np.ndarray
    rpy_U: np.ndarray
    lower: tuple
    upper: tuple
    part_length: np.ndarray
    stroke: np.ndarray
    ujoint_limit: np.ndarray
    platform: Body
    base_visual: dict
    arm: dict | None
    payload: Body
    cable_length: float
    sway_damping: float
    capacities: Capacities
    values: dict = field(repr=False)
    load_limits: LoadLimits = field(default_factory=LoadLimits)
    winch: WinchCapacities = field(default_factory=WinchCapacities)
    drag_area: float = 0.0
    air_density: float = AIR_DENSITY

    @property
    def has_arm(self) -> bool:
        """True when the crane arm is present."""
        return self.arm is not None

    def xacro_data(self) -> dict:
        """The numbers the xacro reads (plain lists and floats; see the xacro)."""
        return _xacro_data(self)

    def digest(self) -> str:
        """SHA-256 (hex) of the robot this description makes: every resolved number and
        drawing, not how it was written (``name``, ``source``, ``path``, ``overrides``
        and the given ``values`` left out). Two descriptions with equal digests build the
        same robot: an override equal to the file's value changes nothing; without drag
        (``drag_area`` 0) the drag's fields, which then change nothing, are left out too
        (a description's digest is the one it had before they existed)."""
        import hashlib

        h = hashlib.sha256()
        skip = ("name", "source", "path", "overrides", "values") + (
            ("drag_area", "air_density") if self.drag_area == 0 else ())
        for f in fields(self):
            if f.name not in skip:
                h.update(f.name.encode() + b"=")
                _feed(h, getattr(self, f.name))
        return h.hexdigest()


def _feed(h, value) -> None:
    """Feed ``value`` to the hash ``h`` in a canonical, typed form (arrays by dtype, shape
    and bytes; floats by ``repr``; dicts by sorted key; dataclasses by field)."""
    if isinstance(value, np.ndarray):
        a = np.ascontiguousarray(value)
        h.update(f"a{a.dtype.str}{a.shape}".encode() + a.tobytes())
    elif is_dataclass(value):
        h.update(type(value).__name__.encode() + b"(")
        for f in fields(value):
            h.update(f.name.encode() + b"=")
            _feed(h, getattr(value, f.name))
        h.update(b")")
    elif isinstance(value, dict):
        h.update(b"{")
        for k in sorted(value, key=str):
            h.update(repr(k).encode() + b":")
            _feed(h, value[k])
        h.update(b"}")
    elif isinstance(value, (list, tuple)):
        h.update(b"[")
        for v in value:
            _feed(h, v)
        h.update(b"]")
    elif isinstance(value, (bool, int, float, str, type(None), np.generic)):
        h.update(f"{type(value).__name__}:{value!r};".encode())
    else:
        raise TypeError(f"no canonical form for {type(value).__name__}")


def _body_data(b: Body) -> dict:
    return {"mass": float(b.mass), "com": floats(b.com), "inertia": inertia6(b.inertia),
            "visual": visual(b.visual)}


def _xacro_data(d: Description) -> dict:
    caps = d.capacities
    # URDF effort and velocity fields: the capacities, 0 where the description gives none
    # (urdfdom, behind Pinocchio, refuses "inf"). They document only: the library reads
    # the capacities from the description (Robot.capacities), never from the URDF.
    effort, speed = (np.where(np.isfinite(x), x, 0.0) for x in (caps.effort(),
                                                                caps.speed_max))
    legs = []
    for i in range(N_LEGS):
        legs.append({
            "i": i + 1, "P": floats(d.p_base_P[i]), "rpy": floats(d.rpy_U[i]),
            "S": floats(d.p_platform_S[i]), "ulim": float(d.ujoint_limit[i]),
            "stroke": floats(d.stroke[i]), "effort": float(effort[3 + i]),
            "velocity": float(speed[3 + i]), "lower": _body_data(d.lower[i]),
            "upper": _body_data(d.upper[i])})
    data = {"format": FORMAT, "name": d.name, "base": {"visual": visual(d.base_visual)},
            "platform": _body_data(d.platform), "legs": legs, "arm": None,
            "payload": {"mass": float(d.payload.mass), "com": floats(d.payload.com),
                        "inertia": inertia6(d.payload.inertia),
                        "cable_length": float(d.cable_length),
                        "sway_damping": float(d.sway_damping),
                        "drag_area": float(d.drag_area),
                        "air_density": float(d.air_density)}}
    if d.arm is not None:
        origin, rpy, column = d.arm["column"]
        arm = {"column": {"origin": floats(origin), "rpy": floats(rpy),
                          **_body_data(column)}}
        for k, body in enumerate(ARM_BODIES):
            j = d.arm[body]
            arm[body] = {"origin": floats(j.origin), "rpy": floats(j.rpy),
                         "axis": floats(j.axis), "lower": float(j.lower),
                         "upper": float(j.upper), "effort": float(effort[k]),
                         "velocity": float(speed[k]), **_body_data(j.body)}
        tip_origin, tip_rpy = d.arm["tip"]
        arm["tip"] = {"origin": floats(tip_origin), "rpy": floats(tip_rpy)}
        data["arm"] = arm
    return data
