"""Scenes: what a simulation contains, read from a small TOML file.

A scene says which sub-systems exist, how the legs are modelled, what hangs at the arm
tip, the gravity, the trajectory, which actuator forces are wanted and by which
method(s). The solver then computes nothing the scene does not need (see
:func:`offshore_crane.dynamics.solve`: arm-only outputs skip the legs, a static platform
skips its velocity and acceleration terms, massless legs skip their inertia terms; all
exact). ``offshore-crane id --scene FILE.toml`` runs one; ``scenes/`` holds examples.

Schema (every key optional; SI units; unknown keys or sections are errors)::

    name = "crane with payload"        # label (default: the file's stem)
    description = "..."                # free text
    gravity = [0.0, 0.0, -9.81]        # base frame [m/s²]
    outputs = ["T1", "T2", "Fs"]       # any of T1 T2 Fs Fl1..Fl6 (default: all that exist)
    methods = ["kane"]                 # kane | kane-explicit | rnea; two or more are
                                       # compared (max |ΔX| ≤ 1e-9 max |X|)

    [robot]                            # the robot (docs/robot-description.md)
    description = "my_platform.toml"   # its description file (relative to this file;
                                       # default: the shipped lab design)
    "legs.lower.mass" = 3.1            # any field, by its dotted name or its alias
    platform_mass = 55.0               # (platform_mass = platform.mass)

    [subsystems]
    platform = true                    # false: the arm on a fixed deck (no legs; only
                                       # T1, T2, Fs exist)
    arm = true                         # false: the Stewart platform alone (only Fl1..Fl6)
    leg_model = "full"                 # "full" (exact), "thin-rod", "massless"
                                       # (approximations, method kane only)
    deck_pose = [0, 0, 0.5, 0, 0, 0]   # q1..q6 of the fixed deck [m, rad]; only with
                                       # platform = false; default (0, 0, home_height, 0, 0, 0)

    [payload]                          # a rigid body welded to the frame arm_tip
    mass = 2.0                         # [kg], ≥ 0 (default 0: no payload)
    offset = [0.0, 0.0, -0.05]         # its centre of mass in the arm_tip frame [m]
    inertia = { ixx = 1e-3, iyy = 1e-3, izz = 1e-3, ixy = 0, ixz = 0, iyz = 0 }
                                       # about its centre of mass, arm_tip axes [kg·m²];
                                       # positive definite; default 0 (a point mass)
    cable_length = 0.0                 # [m]: > 0 hangs the payload (a point mass: offset
                                       # and inertia zero) on a cable from arm_tip
    sway_damping = 0.0                 # [N·m·s/rad] of each sway angle (with a cable)
    [cable]                            # the swing, with cable_length > 0 (docs/cable.md)
    initial = [0.05, 0.0]              # sway phi1, phi2 at the start [rad] (default 0)
    initial_rate = [0.0, 0.0]          # [rad/s]
    substeps = 1                       # RK4 steps per sample interval
    slack = "error"                    # or "warn": mark slack-cable samples and go on

    [actuators]                        # capacities: overrides of the description's
    Fl.push_max = 3000.0               # actuators.* fields (Fl = all legs, Fl1..Fl6, T1,
    T1 = { push_max = 40, pull_max = 40 }   # T2, Fs; push_max, pull_max, speed_max,
                                       # power_max) [N, N·m, m/s, rad/s, W]

    [trajectory]
    source = "table1"                  # "table1", "sea" ([sea] below) or a CSV file
                                       # t_s,q1..q9 (relative to this file)
    duration = 31.4159                 # table1, sea: model-scale span from t = 0 [s]
                                       # (default 10π for table1, 60 for sea)
    rate = 100.0                       # table1, sea: sampling rate [Hz] (default 100)
    fd_order = 4                       # CSV only: finite-difference order 2, 4 or 6

    [sea]                              # source = "sea": a ship in a sea state, Froude-
    hs = 2.5                           # scaled onto q1..q6 (offshore_crane.motion.sea,
    tp = 8.0                           # docs/sea.md); full-scale Hs [m], Tp [s],
    heading = 90.0                     # heading [deg] (180 head seas, 90 from starboard)
    scale = 20.0                       # Froude scale λ (full-scale length / model length)
    vessel = "supply"                  # shipped vessel or an RAO CSV (relative to this file)
    kind = "jonswap"                   # or "pierson-moskowitz"; gamma = 3.3 (JONSWAP only)
    spreading = 4.0                    # cos-2s exponent (short-crested); directions = 36
    seed = 0                           # random phases
    point = [0.0, 0.0, 0.0]            # the crane's base on the vessel [m], full scale
    highpass = 0.3                     # drop components below this [rad/s], full scale

    [operation]                        # q7..q9 with source = "sea" (else held at zero)
    waypoints = [[0, 0, 0, 0.1], [5, 0.8, -0.5, 0.2]]  # [t s, q7 rad, q8 rad, q9 m], quintic

How a scene maps onto the robot and the solver:

- ``[robot]``, ``[payload]`` and ``[subsystems] arm`` are overrides of the robot
  description, all checked by one path (:func:`offshore_crane.robot.overrides.normalise`
  and the description's own checks, as if written in the description file): ``arm =
  false`` is ``arm.enabled = false`` (no column, links, slider; q7..q9 of the trajectory
  are then ignored); ``[payload]`` ``mass``, ``offset``, ``inertia`` are ``payload.mass``,
  ``payload.com``, ``payload.inertia`` (a link ``payload`` welded to ``arm_tip``, which
  the Kane and the Pinocchio paths both read). A field given two different values (in
  ``[robot]`` and ``[payload]``, or by the scene and ``--set``) is an error.
- ``platform = false``: the legs are not evaluated and q1..q6 of the trajectory are
  replaced by ``deck_pose`` with zero rates, so the static-platform pruning applies.

Errors are :class:`~offshore_crane.errors.SceneError` with a one-line message naming the
file and the key, e.g. ``scenes/x.toml: [payload] mass = -1: must be ≥ 0 kg``.
"""

from __future__ import annotations

import math
import os
import statistics
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from offshore_crane.conventions import ARM_ACTUATORS, ACTUATOR_UNITS, ACTUATORS, GRAVITY, INERTIA_RTOL, LEG_ACTUATORS
from offshore_crane.dynamics import LEG_MODELS, METHODS
from offshore_crane.errors import SceneError
from offshore_crane.io import toml_value

SECTIONS = ("robot", "subsystems", "payload", "cable", "actuators", "trajectory", "sea",
            "operation", "control")
TOP_KEYS = ("name", "description", "gravity", "outputs", "methods")
SUBSYSTEM_KEYS = ("platform", "arm", "leg_model", "deck_pose")
PAYLOAD_KEYS = ("mass", "offset", "inertia", "cable_length", "sway_damping")
CABLE_KEYS = ("initial", "initial_rate", "substeps", "slack")
INERTIA_KEYS = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
TRAJECTORY_KEYS = ("source", "duration", "rate", "fd_order")
SEA_KEYS = ("hs", "tp", "heading", "scale", "vessel", "kind", "gamma", "spreading",
            "directions", "seed", "point", "highpass")
#: [sea] keys without which no sea motion exists.
SEA_REQUIRED = ("hs", "tp", "heading", "scale")
OPERATION_KEYS = ("waypoints",)
#: Model-scale record of ``source = "sea"`` when [trajectory] does not say [s], [Hz].
SEA_DURATION, SEA_RATE = 60.0, 100.0
CONTROL_KEYS = ("law", "kp", "kd", "rate", "step", "integrator", "initial_error", "noise_q",
                "noise_qd", "seed", "model", "lower", "upper", "saturation", "anti_sway")
#: [control] keys that are Controller arguments (the others: simulate's).
CONTROLLER_KEYS = ("law", "kp", "kd", "rate", "lower", "upper", "saturation", "noise_q",
                   "noise_qd", "seed", "anti_sway")
#: Where a scene file sets the robot fields it owns besides [robot] (for messages).
SCENE_FIELDS = {"arm.enabled": "[subsystems] arm", "payload.mass": "[payload] mass",
                "payload.com": "[payload] offset", "payload.inertia": "[payload] inertia",
                "payload.cable_length": "[payload] cable_length",
                "payload.sway_damping": "[payload] sway_damping"}


def _scene_field(name: str) -> str:
    """Where a scene file sets the robot field ``name`` besides [robot]."""
    if name.startswith("actuators."):
        return f"[actuators] {name[len('actuators.'):]}"
    return SCENE_FIELDS[name]
#: Run time of the fidelity report: median of this many runs per leg model.
FIDELITY_REPEAT = 5


def _finite(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def _finite_vector(v, n: int) -> bool:
    return isinstance(v, (tuple, list)) and len(v) == n and all(_finite(x) for x in v)


@dataclass(frozen=True)
class Payload:
    """A rigid body welded to the frame ``arm_tip`` (the slider's outer end): the robot
    description's ``payload`` fields. Checked with the rest of the robot when a
    :class:`Scene` holds it (mass ≥ 0, a physical inertia, ...).

    Attributes:
        mass: [kg]; 0 means no payload.
        offset: ``(3,)`` centre of mass in the ``arm_tip`` frame [m] (``payload.com``).
        inertia: ``(ixx, iyy, izz, ixy, ixz, iyz)`` about the centre of mass, ``arm_tip``
            axes [kg·m²] (URDF convention); all zero for a point mass.
        cable_length: [m]; 0: welded to ``arm_tip``; > 0: a point mass hanging on a
            cable of this length (:mod:`offshore_crane.dynamics.cable`).
        sway_damping: viscous damping of each sway angle [N·m·s/rad] (with a cable).
    """

    mass: float = 0.0
    offset: tuple = (0.0, 0.0, 0.0)
    inertia: tuple = (0.0,) * 6
    cable_length: float = 0.0
    sway_damping: float = 0.0

    def overrides(self) -> dict:
        """The dotted robot fields this payload sets."""
        return {"payload.mass": self.mass, "payload.com": list(self.offset),
                "payload.inertia": dict(zip(INERTIA_KEYS, self.inertia)),
                "payload.cable_length": self.cable_length,
                "payload.sway_damping": self.sway_damping}


@dataclass(frozen=True)
class Scene:
    """What a simulation contains (see the module docstring for the TOML schema).

    Attributes:
        name: Label.
        description: Free text.
        path: The file it was read from, or None.
        robot: ``{dotted name or alias: value}`` overrides of the robot description;
            after creation: checked, dotted, and holding ``arm.enabled`` and ``payload.*``
            when ``arm`` or ``payload`` were given.
        robot_description: The robot description file (TOML), or None for the default.
        platform: False: the arm on a fixed deck at ``deck_pose`` (legs not evaluated).
        arm: False: the Stewart platform alone (``arm.enabled = false``); None (the
            default): as ``robot`` says, else true. A bool after creation.
        leg_model: ``"full"``, ``"thin-rod"`` or ``"massless"``.
        deck_pose: ``(6,)`` q1..q6 of the fixed deck [m, rad], or None for the home
            pose ``(0, 0, home_height, 0, 0, 0)``.
        payload: :class:`Payload` at the arm tip, or None (the default): as ``robot`` and
            the description say. After creation: the payload of the resolved robot.
        gravity: ``(3,)`` base frame [m/s²].
        trajectory: ``"table1"`` or the path of a CSV file.
        duration, rate: Table 1 span [s] and sampling rate [Hz] (None: defaults).
        fd_order: Finite-difference order for a CSV trajectory.
        sea: ``[sea]`` for ``trajectory = "sea"``: :func:`offshore_crane.motion.sea.sea_motion`'s
            arguments (``heading`` for ``heading_deg``), full scale.
        operation: Crane waypoints ``((t, q7, q8, q9), ...)`` [s, rad, rad, m] for
            ``trajectory = "sea"``, or None (arm held at zero).
        outputs: Actuators wanted, or None for all that exist.
        methods: Methods to run; the first one's result is reported, the others are
            compared with it.
    """

    name: str = "default"
    description: str = ""
    path: str | None = None
    robot: dict = field(default_factory=dict)
    robot_description: str | None = None
    platform: bool = True
    arm: bool | None = None
    leg_model: str = "full"
    deck_pose: tuple | None = None
    payload: Payload | None = None
    gravity: tuple = GRAVITY
    trajectory: str = "table1"
    duration: float | None = None
    rate: float | None = None
    fd_order: int = 4
    sea: dict = field(default_factory=dict)
    operation: tuple | None = None
    outputs: tuple | None = None
    methods: tuple = ("kane",)
    control: dict = field(default_factory=dict)
    cable: dict = field(default_factory=dict)
    #: Where the scene comes from, for messages (the file, or the file with the
    #: command-line options applied).
    origin: str | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        _check_robot(self)
        _check_values(self)
        check_scene(self)
        _check_sea(self)

    def where(self) -> str:
        """Where the scene comes from, for messages."""
        return self.origin or self.path or f"scene '{self.name}'"

    def actuators(self) -> tuple:
        """Actuators that exist in this scene, in the order of X."""
        return (ARM_ACTUATORS if self.arm else ()) + (LEG_ACTUATORS if self.platform else ())

    def wanted(self) -> tuple:
        """Actuators to compute: ``outputs``, or all that exist."""
        return self.actuators() if self.outputs is None else self.outputs

    def robot_overrides(self) -> dict:
        """``{dotted name: value}``: every robot field the scene sets (checked)."""
        return dict(self.robot)

    def describe(self) -> str:
        """One line: sub-systems, leg model, payload."""
        parts = ["Stewart platform" if self.platform else "fixed deck (no platform motion, "
                 "no legs)", "arm" if self.arm else "no arm"]
        if self.platform:
            parts.append(f"{self.leg_model} legs")
        if self.payload.cable_length > 0:
            parts.append(f"payload {self.payload.mass:g} kg hanging on a "
                         f"{self.payload.cable_length:g} m cable from arm_tip")
        elif self.payload.mass > 0:
            parts.append(f"payload {self.payload.mass:g} kg at "
                         f"({', '.join(f'{x:g}' for x in self.payload.offset)}) m from arm_tip")
        return ", ".join(parts)


# --------------------------------------------------------------------------- reading
class _Reader:
    """Checks the values of one scene table; errors name ``where`` and the key."""

    def __init__(self, where: str, section: str | None, table: dict, known: tuple):
        self.where, self.section, self.table = where, section, table
        prefix = f"[{section}] " if section else ""
        for key in table:
            if key not in known:
                self.fail_key(key, f"{prefix}unknown key '{key}': known keys are "
                              f"{', '.join(known)}")

    def key_name(self, key: str) -> str:
        return f"{self.section}.{key}" if self.section else key

    def fail_key(self, key: str, message: str):
        raise SceneError(f"{self.where}: {message}", path=self.where, name=self.key_name(key))

    def fail(self, key: str, problem: str):
        prefix = f"[{self.section}] " if self.section else ""
        self.fail_key(key, f"{prefix}{key} = {toml_value(self.table[key])}: {problem}")

    def get(self, key: str, default=None):
        return self.table.get(key, default)

    def number(self, key: str, default=None, unit: str = "", minimum: float | None = None,
               positive: bool = False):
        if key not in self.table:
            return default
        v = self.table[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            self.fail(key, f"must be a finite number{f' [{unit}]' if unit else ''}")
        if positive and v <= 0:
            self.fail(key, f"must be > 0{f' {unit}' if unit else ''}")
        if minimum is not None and v < minimum:
            self.fail(key, f"must be ≥ {minimum:g}{f' {unit}' if unit else ''}")
        return float(v)

    def vector(self, key: str, n: int, default=None, unit: str = ""):
        if key not in self.table:
            return default
        v = self.table[key]
        if (not isinstance(v, list) or len(v) != n
                or any(isinstance(x, bool) or not isinstance(x, (int, float))
                       or not math.isfinite(x) for x in v)):
            self.fail(key, f"must be a list of {n} finite numbers [{unit}]")
        return tuple(float(x) for x in v)

    def boolean(self, key: str, default: bool) -> bool:
        if key not in self.table:
            return default
        if not isinstance(self.table[key], bool):
            self.fail(key, "must be true or false")
        return self.table[key]

    def string(self, key: str, default=None, choices: tuple | None = None):
        if key not in self.table:
            return default
        v = self.table[key]
        if not isinstance(v, str):
            self.fail(key, "must be a string" + (f": one of {', '.join(choices)}"
                                                  if choices else ""))
        if choices and v not in choices:
            self.fail(key, f"must be one of {', '.join(choices)}")
        return v

    def names(self, key: str, choices: tuple):
        """A non-empty list of distinct names out of ``choices`` (in file order)."""
        if key not in self.table:
            return None
        v = self.table[key]
        if not isinstance(v, list) or not v or not all(isinstance(x, str) for x in v):
            self.fail(key, f"must be a non-empty list of names out of {', '.join(choices)}")
        unknown = [x for x in v if x not in choices]
        if unknown:
            self.fail(key, f"unknown {', '.join(map(repr, unknown))}: choose among "
                      f"{', '.join(choices)}")
        if len(set(v)) != len(v):
            self.fail(key, "names a value twice")
        return tuple(v)


def _section(where: str, data: dict, name: str, known: tuple) -> _Reader:
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise SceneError(f"{where}: {name} = {toml_value(table)}: must be a table [{name}]",
                         path=where, name=name)
    return _Reader(where, name, table, known)


def _robot(where: str, data: dict, base: Path | None) -> dict:
    """``[robot]``, ``[payload]`` and ``[subsystems] arm`` as the Scene's ``robot``,
    ``robot_description`` (checked by :func:`_check_robot` when the Scene is made)."""
    robot = data.get("robot", {})
    if not isinstance(robot, dict):
        raise SceneError(f"{where}: robot = {toml_value(robot)}: must be a table [robot]",
                         path=where, name="robot")
    robot = dict(robot)
    description = robot.pop("description", None)
    if description is not None:
        if not isinstance(description, str) or not description:
            raise SceneError(f"{where}: [robot] description = {toml_value(description)}: must be "
                             "the path of a robot description file (TOML)", path=where,
                             name="robot.description")
        p = Path(description)
        if not p.is_absolute() and base is not None:
            p = base / p
        if not p.is_file():
            raise SceneError(f"{where}: [robot] description = {toml_value(description)}: no such "
                             f"file {p} (relative paths start at the scene file's folder)",
                             path=where, name="robot.description")
        description = str(p)
    overrides = _normalised(where, robot, "[robot]", flatten=True)
    r = _section(where, data, "payload", PAYLOAD_KEYS)
    payload = {}
    if "inertia" in r.table and not isinstance(r.get("inertia"), dict):
        r.fail("inertia", f"must be a table of {', '.join(INERTIA_KEYS)} [kg·m²]")
    if "inertia" in r.table:
        _Reader(where, "payload.inertia", r.get("inertia"), INERTIA_KEYS)  # known keys
    for key, name in (("mass", "payload.mass"), ("offset", "payload.com"),
                      ("inertia", "payload.inertia"), ("cable_length", "payload.cable_length"),
                      ("sway_damping", "payload.sway_damping")):
        if key in r.table:
            payload[name] = r.get(key)
    sub = data.get("subsystems", {})
    if isinstance(sub, dict) and "arm" in sub:
        payload["arm.enabled"] = sub["arm"]
    actuators = data.get("actuators", {})
    if not isinstance(actuators, dict):
        raise SceneError(f"{where}: actuators = {toml_value(actuators)}: must be a table "
                         "[actuators]", path=where, name="actuators")
    payload.update(_normalised(where, {"actuators": actuators}, "[actuators]", flatten=True))
    for name, value in _normalised(where, payload, None).items():
        if name in overrides and not _same_value(overrides[name], value):
            raise SceneError(f"{where}: {_scene_field(name)} = {_plain(value)} contradicts "
                             f"[robot] {name} = {_plain(overrides[name])}: give it once",
                             path=where, name=name)
        overrides[name] = value
    return dict(robot=overrides, robot_description=description)


def _plain(value) -> str:
    """``value`` as TOML, floats in their shortest form (2, not 2.0)."""
    if isinstance(value, float) and math.isfinite(value):
        return f"{value:g}" if float(f"{value:g}") == value else repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_plain(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {_plain(v)}" for k, v in value.items()) + " }"
    return toml_value(value)


def _same_value(a, b) -> bool:
    from offshore_crane.robot.overrides import conflicts

    return not conflicts({"x": a}, {"x": b})


def _normalised(where: str, raw: dict, section: str | None, flatten: bool = False) -> dict:
    """:func:`offshore_crane.robot.overrides.normalise` (of the flattened nested tables
    with ``flatten``), its errors as SceneErrors naming the scene (and the section)."""
    from offshore_crane.errors import DescriptionError
    from offshore_crane.robot.overrides import flatten_table, normalise

    try:
        return normalise(flatten_table(raw, where) if flatten else raw, where)
    except DescriptionError as exc:
        text = str(exc)
        if section and text.startswith(f"{where}: "):
            text = f"{where}: {section} {text[len(where) + 2:]}"
        raise SceneError(text, path=where, name=exc.field) from None


def _check_robot(scene: "Scene") -> None:
    """Fold ``arm`` and ``payload`` into ``scene.robot``, check every override as the
    description's own fields (one path: :mod:`offshore_crane.robot.overrides`, then
    :func:`offshore_crane.robot.description.resolve`), and set ``arm`` and ``payload``
    from the resolved robot.

    Raises:
        SceneError: a bad or contradictory override, naming the scene and the field.
    """
    where = scene.where()
    if not isinstance(scene.robot, dict):
        raise SceneError(f"{where}: robot = {scene.robot!r}: must be a dict {{name: value}}",
                         path=scene.path, name="robot")
    robot = _normalised(where, scene.robot, None)
    spec = _resolve(scene, robot)
    own = {}                            # arm and payload where they differ from the robot
    if scene.arm is not None and bool(scene.arm) != spec.has_arm:
        own["arm.enabled"] = scene.arm
    if scene.payload is not None:
        if not isinstance(scene.payload, Payload):
            raise SceneError(f"{where}: payload = {scene.payload!r}: must be a Payload",
                             path=scene.path, name="payload")
        if scene.payload != _payload_of(spec):
            own.update(scene.payload.overrides())
    if own:
        for name, value in _normalised(where, own, None).items():
            if name in robot and not _same_value(robot[name], value):
                raise SceneError(f"{where}: {name} = {_plain(value)} contradicts robot "
                                 f"{name} = {_plain(robot[name])}: give it once",
                                 path=scene.path, name=name)
            robot[name] = value
        spec = _resolve(scene, robot)
    object.__setattr__(scene, "robot", robot)
    object.__setattr__(scene, "arm", bool(spec.has_arm))
    object.__setattr__(scene, "payload", _payload_of(spec))


def _resolve(scene: "Scene", robot: dict):
    from offshore_crane.errors import DescriptionError
    from offshore_crane.robot.description import resolve

    try:
        return resolve(scene.robot_description, robot)
    except DescriptionError as exc:
        raise SceneError(f"{scene.where()}: {exc}", path=scene.path, name=exc.field) from None


def _payload_of(spec) -> Payload:
    """The :class:`Payload` of a resolved description."""
    p = spec.payload
    return Payload(float(p.mass), tuple(float(x) for x in p.com),
                   tuple(float(p.inertia[i, j]) for i, j in
                         ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))),
                   float(spec.cable_length), float(spec.sway_damping))


def _trajectory(where: str, data: dict, base: Path | None) -> dict:
    r = _section(where, data, "trajectory", TRAJECTORY_KEYS)
    source = r.string("source", "table1")
    out = dict(trajectory=source)
    if source == "sea":
        out["duration"] = r.number("duration", None, "s", positive=True)
        out["rate"] = r.number("rate", None, "Hz", positive=True)
        if "fd_order" in r.table:
            r.fail("fd_order", "applies to a CSV trajectory only (a sea state has analytic "
                   "derivatives)")
    elif source != "table1":
        path = Path(source)
        if not path.is_absolute() and base is not None:
            path = base / path
        if not path.is_file():
            r.fail("source", f"no such file {path} (give 'table1' or a CSV t_s,q1..q9; "
                   "relative paths start at the scene file's folder)")
        out["trajectory"] = str(path)
        for key in ("duration", "rate"):
            if key in r.table:
                r.fail(key, "applies to table1 only (a CSV file's samples set the time axis)")
        if "fd_order" in r.table:
            v = r.get("fd_order")
            if isinstance(v, bool) or v not in (2, 4, 6):
                r.fail("fd_order", "must be 2, 4 or 6")
            out["fd_order"] = int(v)
    else:
        if "fd_order" in r.table:
            r.fail("fd_order", "applies to a CSV trajectory only (table1 has analytic "
                   "derivatives)")
        out["duration"] = r.number("duration", None, "s", positive=True)
        out["rate"] = r.number("rate", None, "Hz", positive=True)
    return out


def _sea(where: str, data: dict, base: Path | None) -> dict:
    """``[sea]`` and ``[operation]``: types here; values by the sea module's own checks
    (:func:`_check_sea`, when the Scene is made)."""
    r = _section(where, data, "sea", SEA_KEYS)
    sea = {}
    for key in ("hs", "tp", "heading", "scale", "gamma", "spreading", "highpass"):
        if key in r.table:
            sea[key] = r.number(key)
    if "point" in r.table:
        sea["point"] = r.vector("point", 3, unit="m")
    for key in ("seed", "directions"):
        if key in r.table:
            v = r.get(key)
            if isinstance(v, bool) or not isinstance(v, int):
                r.fail(key, "must be an integer")
            sea[key] = v
    if "kind" in r.table:
        sea["kind"] = r.string("kind")
    if "vessel" in r.table:
        vessel = r.string("vessel")
        from offshore_crane.motion.sea import vessel_names

        if vessel not in vessel_names():
            p = Path(vessel)
            if not p.is_absolute() and base is not None:
                p = base / p
            if not p.is_file():
                r.fail("vessel", f"neither a shipped vessel ({', '.join(vessel_names())}) "
                       f"nor a file {p} (relative paths start at the scene file's folder)")
            vessel = str(p)
        sea["vessel"] = vessel
    o = _section(where, data, "operation", OPERATION_KEYS)
    operation = None
    if "waypoints" in o.table:
        w = o.get("waypoints")
        if (not isinstance(w, list) or not w or any(
                not isinstance(row, list) or len(row) != 4 or any(
                    isinstance(x, bool) or not isinstance(x, (int, float))
                    or not math.isfinite(x) for x in row) for row in w)):
            o.fail("waypoints", "must be a list of [t, q7, q8, q9] rows of finite numbers "
                   "[s, rad, rad, m]")
        operation = tuple(tuple(float(x) for x in row) for row in w)
    return dict(sea=sea, operation=operation)


def _check_sea(scene: "Scene") -> None:
    """The ``[sea]`` / ``[operation]`` sections against the trajectory source and the
    sea module's argument checks (what :func:`offshore_crane.motion.sea.sea_state` would say)."""
    where = scene.where()

    def fail(key, message):
        raise SceneError(f"{where}: {message}", path=scene.path, name=key)

    if scene.trajectory != "sea":
        if scene.sea:
            fail("sea", f"[sea] applies to [trajectory] source = \"sea\", not "
                 f"{toml_value(scene.trajectory)}")
        if scene.operation is not None:
            fail("operation", "[operation] applies to [trajectory] source = \"sea\"")
        return
    missing = [k for k in SEA_REQUIRED if k not in scene.sea]
    if missing:
        fail("sea", f"[trajectory] source = \"sea\" needs [sea] {', '.join(missing)} "
             "(full-scale Hs [m], Tp [s], heading [deg], Froude scale)")
    unknown = [k for k in scene.sea if k not in SEA_KEYS]
    if unknown:
        fail(f"sea.{unknown[0]}", f"[sea] unknown key '{unknown[0]}'")
    if not scene.platform:
        fail("sea", "[sea] moves the platform, but [subsystems] platform = false")
    if scene.operation is not None and not scene.arm:
        fail("operation", "[operation] moves the arm, but the robot has no arm")
    from offshore_crane.errors import SeaStateError
    from offshore_crane.motion.sea import check_arguments

    try:
        check_arguments(**sea_arguments(scene))
    except SeaStateError as exc:
        if exc.name == "waypoints":
            fail("operation.waypoints", f"[operation] {exc}")
        fail(f"sea.{exc.name}", f"[sea] {exc}")


def sea_arguments(scene: "Scene") -> dict:
    """``scene.sea`` as keyword arguments of :func:`offshore_crane.motion.sea.sea_motion` (but
    duration, rate and robot)."""
    args = dict(scene.sea)
    args["heading_deg"] = args.pop("heading", None)
    if scene.operation is not None:
        args["operation"] = [list(row) for row in scene.operation]
    return args


def _control(where: str, data: dict) -> dict:
    """The ``[control]`` section of ``offshore-crane simulate``: checked values, as a dict
    of :func:`controller`'s and :func:`offshore_crane.simulation.rigid.simulate`'s arguments."""
    from offshore_crane.simulation.control import LAWS, Controller
    from offshore_crane.errors import InputError
    from offshore_crane.simulation.rigid import INTEGRATORS

    r = _section(where, data, "control", CONTROL_KEYS)
    out: dict = {}
    if "law" in r.table:
        out["law"] = r.string("law", choices=LAWS)
    for key, unit in (("kp", "1/s² or N/m"), ("kd", "1/s or N·s/m"), ("noise_q", "m, rad"),
                      ("noise_qd", "m/s, rad/s")):
        if key in r.table:
            v = r.get(key)
            out[key] = r.vector(key, 9, unit=unit) if isinstance(v, list) else r.number(
                key, unit=unit, minimum=0.0)
    for key in ("lower", "upper", "initial_error"):
        if key in r.table:
            v = r.get(key)
            if key != "initial_error" and isinstance(v, list) and len(v) == 9 and all(
                    isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
                out[key] = tuple(float(x) for x in v)   # may hold ±inf
            else:
                out[key] = r.vector(key, 9, unit="N·m, N" if key != "initial_error" else
                                    "m, rad")
    if "rate" in r.table:
        out["rate"] = r.number("rate", unit="Hz", positive=True)
    if "anti_sway" in r.table:
        out["anti_sway"] = r.number("anti_sway", unit="damping ratio", minimum=0.0)
    if "step" in r.table:
        out["step"] = r.number("step", unit="s", positive=True)
    if "integrator" in r.table:
        out["integrator"] = r.string("integrator", choices=INTEGRATORS)
    if "saturation" in r.table:
        out["saturation"] = r.boolean("saturation", True)
    if "seed" in r.table:
        seed = r.get("seed")
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            r.fail("seed", "must be an integer ≥ 0")
        out["seed"] = seed
    if "model" in r.table:
        model = r.get("model")
        if not isinstance(model, dict):
            r.fail("model", "must be a table of robot parameters (the controller's model)")
        out["model"] = _normalised(where, model, "[control] model", flatten=True)
    try:                                # the law's own checks (gains, limits), named here
        Controller(**{k: v for k, v in out.items() if k in CONTROLLER_KEYS})
    except InputError as exc:
        raise SceneError(f"{where}: [control] {exc}", path=where, name="control") from None
    return out


def _cable(where: str, data: dict) -> dict:
    """The ``[cable]`` section: :func:`offshore_crane.dynamics.cable.inverse_dynamics`'s
    ``initial``, ``initial_rate``, ``substeps`` and ``slack``, checked."""
    from offshore_crane.dynamics.cable import SLACK

    r = _section(where, data, "cable", CABLE_KEYS)
    out: dict = {}
    if "initial" in r.table:
        out["initial"] = r.vector("initial", 2, unit="rad")
    if "initial_rate" in r.table:
        out["initial_rate"] = r.vector("initial_rate", 2, unit="rad/s")
    if "substeps" in r.table:
        n = r.get("substeps")
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            r.fail("substeps", "must be an integer ≥ 1 (RK4 steps per sample interval)")
        out["substeps"] = n
    if "slack" in r.table:
        out["slack"] = r.string("slack", choices=SLACK)
    return out


def controller(scene: Scene, robot=None):
    """The :class:`~offshore_crane.simulation.control.Controller` of the scene's ``[control]``
    section (its ``model`` table overrides the scene's robot for the controller)."""
    from offshore_crane.simulation.control import Controller

    c = scene.control
    model = None
    if "model" in c:
        model = load_robot(scene, c["model"])
    return Controller(**{k: v for k, v in c.items() if k in CONTROLLER_KEYS}, model=model)


def scene_from_dict(data: dict, where: str = "scene", base: Path | None = None) -> Scene:
    """Build and check a :class:`Scene` from parsed TOML.

    Args:
        data: The TOML document as a dict.
        where: Name of the source used in messages (the file path).
        base: Folder that relative CSV paths start from.

    Raises:
        SceneError: naming ``where`` and the key.
    """
    for key, value in data.items():
        if isinstance(value, dict) and key not in SECTIONS:
            raise SceneError(f"{where}: unknown section [{key}]: known sections are "
                             f"{', '.join(f'[{s}]' for s in SECTIONS)}", path=where, name=key)
    top = _Reader(where, None, {k: v for k, v in data.items() if k not in SECTIONS},
                  TOP_KEYS)
    sub = _section(where, data, "subsystems", SUBSYSTEM_KEYS)
    control = _control(where, data)
    cable = _cable(where, data)
    return Scene(                       # Scene checks how the parts fit (check_scene)
        name=top.string("name", Path(where).stem),
        description=top.string("description", ""),
        path=where, platform=sub.boolean("platform", True),
        leg_model=sub.string("leg_model", "full", LEG_MODELS),
        deck_pose=sub.vector("deck_pose", 6, None, "m, rad"), **_robot(where, data, base),
        gravity=top.vector("gravity", 3, GRAVITY, "m/s²"),
        outputs=top.names("outputs", ACTUATORS),
        methods=top.names("methods", METHODS) or ("kane",), control=control, cable=cable,
        **_trajectory(where, data, base), **_sea(where, data, base))


def _check_values(scene: Scene) -> None:
    """Domain of each field of a scene built in Python (the TOML reader checks first)."""
    where = scene.where()

    def fail(key, value, problem):
        raise SceneError(f"{where}: {key} = {value!r}: {problem}", path=scene.path, name=key)

    if scene.leg_model not in LEG_MODELS:
        fail("subsystems.leg_model", scene.leg_model, f"must be one of {', '.join(LEG_MODELS)}")
    if not scene.methods or any(m not in METHODS for m in scene.methods):
        fail("methods", scene.methods, f"must be names out of {', '.join(METHODS)}")
    if scene.outputs is not None and (not scene.outputs
                                      or any(o not in ACTUATORS for o in scene.outputs)):
        fail("outputs", scene.outputs, f"must be names out of {', '.join(ACTUATORS)}")
    if not _finite_vector(scene.gravity, 3):
        fail("gravity", scene.gravity, "must be 3 finite numbers [m/s²]")
    if scene.deck_pose is not None and not _finite_vector(scene.deck_pose, 6):
        fail("subsystems.deck_pose", scene.deck_pose, "must be 6 finite numbers [m, rad]")


def check_scene(scene: Scene) -> None:
    """Check that the parts of ``scene`` fit together (run on creation and override).

    Raises:
        SceneError: no sub-system left, a deck pose with the platform, a payload without
            arm, outputs that the sub-systems do not have, or an approximate leg model
            with no legs or with a method other than kane.
    """
    where = scene.where()
    if not (scene.platform or scene.arm):
        raise SceneError(f"{where}: [subsystems] platform = false and arm = false: nothing "
                         "is left to simulate", path=scene.path, name="subsystems.arm")
    if scene.deck_pose is not None and scene.platform:
        raise SceneError(f"{where}: [subsystems] deck_pose applies to platform = false (the "
                         "arm on a fixed deck) only", path=scene.path,
                         name="subsystems.deck_pose")
    if scene.payload.mass > 0 and not scene.arm:
        raise SceneError(f"{where}: [payload] mass = {scene.payload.mass:g}: the payload "
                         "hangs from the arm tip, but [subsystems] arm = false",
                         path=scene.path, name="payload.mass")
    if scene.outputs is not None:
        absent = [n for n in scene.outputs if n not in scene.actuators()]
        if absent:
            why = ("[subsystems] platform = false (no legs)" if not scene.platform
                   else "[subsystems] arm = false")
            raise SceneError(f"{where}: outputs = {toml_value(list(scene.outputs))}: "
                             f"{', '.join(absent)} do not exist with {why}",
                             path=scene.path, name="outputs")
    if scene.leg_model != "full" and not scene.platform:
        raise SceneError(f"{where}: [subsystems] leg_model = {toml_value(scene.leg_model)}: "
                         "applies to the Stewart platform, but platform = false (no legs)",
                         path=scene.path, name="subsystems.leg_model")
    if scene.leg_model != "full" and scene.methods != ("kane",):
        raise SceneError(f"{where}: [subsystems] leg_model = {toml_value(scene.leg_model)}: an "
                         f"approximation offered by method kane only, but methods = "
                         f"{toml_value(list(scene.methods))}", path=scene.path,
                         name="subsystems.leg_model")
    hanging = scene.payload.cable_length > 0
    if scene.cable and not hanging:
        raise SceneError(f"{where}: [cable] applies to a payload on a cable, but [payload] "
                         "cable_length = 0 (welded): set cable_length > 0 or remove [cable]",
                         path=scene.path, name="cable")
    if hanging and scene.leg_model != "full":
        raise SceneError(f"{where}: [subsystems] leg_model = {toml_value(scene.leg_model)}: the "
                         "hanging load is computed with the full leg model only",
                         path=scene.path, name="subsystems.leg_model")
    if hanging and "kane-explicit" in scene.methods:
        raise SceneError(f"{where}: methods = {toml_value(list(scene.methods))}: with a payload on "
                         "a cable the methods are kane and rnea (the Pinocchio reference of "
                         "the swing)", path=scene.path, name="methods")


def load_scene(path) -> Scene:
    """Read and check a scene file.

    Args:
        path: The TOML file (str or path-like).

    Raises:
        SceneError: unreadable file, invalid TOML, unknown section or key, bad value; the
            message names the file and the key.
    """
    from offshore_crane.errors import InputError
    from offshore_crane.io import read_toml

    where = os.fspath(path)
    try:
        data = read_toml(where, "scene file")
    except InputError as exc:
        raise SceneError(str(exc), path=where) from None
    return scene_from_dict(data, where, Path(where).parent)


# --------------------------------------------------------------------------- running
def deck_pose(scene: Scene, robot) -> np.ndarray:
    """q1..q6 ``(6,)`` of the fixed deck [m, rad]: ``scene.deck_pose`` or home."""
    if scene.deck_pose is not None:
        return np.array(scene.deck_pose)
    return robot.home_pose()[:6]


def sea_trajectory(scene: Scene, robot, check: bool = True):
    """The model-scale record of a ``source = "sea"`` scene
    (:func:`offshore_crane.motion.sea.platform_trajectory`, analytic rates and accelerations;
    its ``source`` evaluates the same motion at any times).

    Raises:
        SceneError: a bad ``[sea]`` value. SeaWorkspaceError: the record leaves the
            workspace (with the smallest scale that fits).
    """
    from offshore_crane.errors import SeaStateError
    from offshore_crane.motion.sea import platform_trajectory

    args = sea_arguments(scene)
    name = (f"sea Hs {args['hs']:g} m Tp {args['tp']:g} s heading {args['heading_deg']:g}° "
            f"at scale {args['scale']:g}")
    try:
        return platform_trajectory(
            SEA_DURATION if scene.duration is None else scene.duration,
            SEA_RATE if scene.rate is None else scene.rate, robot=robot, check=check,
            name=name, **args)
    except SeaStateError as exc:
        section = "operation" if exc.name == "waypoints" else "sea"
        raise SceneError(f"{scene.where()}: [{section}] {exc}", path=scene.path,
                         name=f"{section}.{exc.name}") from None


def load_robot(scene: Scene, overrides: dict | None = None):
    """The scene's robot; ``overrides`` (dotted names or aliases) are applied on top, for
    a model that differs from the scene's on purpose (a controller's model). Command-line
    ``--set`` goes through :func:`with_robot_overrides` instead, which refuses
    contradictions."""
    from offshore_crane.robot import load_robot as _load
    from offshore_crane.robot.overrides import normalise

    return _load(scene.robot_description,
                 {**scene.robot_overrides(), **normalise(overrides, "robot overrides")})


def _field_owner(scene: Scene, name: str) -> str:
    """The scene's section that sets ``name`` (for messages)."""
    if name in SCENE_FIELDS or name.startswith("actuators."):
        return _scene_field(name)
    return f"[robot] {name}"


def with_robot_overrides(scene: Scene, overrides: dict, source: str = "--set") -> Scene:
    """``scene`` with robot overrides (e.g. ``--set``) added, re-checked.

    Args:
        overrides: Checked overrides (:func:`offshore_crane.robot.overrides.parse_set`).

    Raises:
        SceneError: an override contradicts a field the scene sets (its ``[robot]``,
            ``[payload]`` or ``[subsystems] arm``), or the result does not fit together
            (a payload without arm, ...).
    """
    from offshore_crane.robot.overrides import conflicts

    if not overrides:
        return scene
    where = scene.where()
    clash = conflicts(scene.robot, overrides)
    if clash:
        c = clash[0]
        raise SceneError(f"{where}: {source} {c.field} = {_plain(c.cli)} contradicts the "
                         f"scene's {_field_owner(scene, c.field)} = "
                         f"{_plain(c.scene)}: change the scene or drop the {source}",
                         path=scene.path, name=c.field)
    robot = {**scene.robot, **overrides}
    return replace(scene, robot=robot, arm=None, payload=None,
                   origin=f"{where} with {source}")


def load_trajectory(scene: Scene, robot):
    """The scene's trajectory; with ``platform = false``, q1..q6 held at the deck pose.

    Returns:
        :class:`offshore_crane.motion.trajectories.Trajectory` (``(N, 9)`` arrays).
    """
    from offshore_crane.motion import trajectories

    if scene.trajectory == "sea":
        return sea_trajectory(scene, robot)
    traj = trajectories.load(scene.trajectory, duration=scene.duration, rate=scene.rate,
                             fd_order=scene.fd_order)
    if scene.platform:
        return traj
    q, qd, qdd = traj.q.copy(), traj.qd.copy(), traj.qdd.copy()
    q[:, :6] = deck_pose(scene, robot)
    qd[:, :6] = 0.0
    qdd[:, :6] = 0.0
    return trajectories.Trajectory(f"{traj.name} on a fixed deck", traj.t, q, qd, qdd)


@dataclass
class SceneRun:
    """A scene's results.

    Attributes:
        scene: The scene.
        robot: Its robot.
        trajectory: The trajectory as solved (deck pose applied).
        results: ``{method: Result}`` in the order of ``scene.methods``.
        seconds: ``{method: run time [s]}``.
    """

    scene: Scene
    robot: object
    trajectory: object
    results: dict
    seconds: dict

    @property
    def result(self):
        """The first method's :class:`~offshore_crane.dynamics.Result`."""
        return next(iter(self.results.values()))


def _solve(scene: Scene, robot, traj, method: str, leg_model: str, **options):
    from offshore_crane.dynamics import solve

    if robot.hybrid.cable is not None:
        return _swing(scene, robot, traj, method, **options)
    return solve(robot, traj.q, traj.qd, traj.qdd, method=method, gravity=scene.gravity,
                 leg_model=leg_model, outputs=scene.wanted(), t=traj.t, **options)


#: The hanging load's path for each scene method: Kane's, or the Pinocchio reference.
CABLE_METHODS = {"kane": "kane", "rnea": "pinocchio"}


def _swing(scene: Scene, robot, traj, method: str, limits: bool = True, checks: bool = True,
           thresholds=None, **ignored):
    """A scene with a payload on a cable: :func:`offshore_crane.dynamics.cable.swing` (the
    ``[cable]`` options; ``backend`` and ``threads`` do not apply), as a
    :class:`~offshore_crane.dynamics.Result` holding the :class:`CableResult`."""
    from offshore_crane.dynamics.cable import swing
    from offshore_crane.dynamics import Result
    from offshore_crane.robot.kinematics.workspace import Thresholds

    res = swing(robot, traj, method=CABLE_METHODS[method], gravity=scene.gravity,
                limits=limits, checks=checks, thresholds=thresholds or Thresholds(),
                **scene.cable)
    return Result(X=res.X, method=method, leg_model="full", outputs=scene.wanted(),
                  condition=res.condition, gimbal=None, attitude=None,
                  backend="numba" if method == "kane" else "pinocchio", cable=res)


def run(scene: Scene, robot=None, trajectory=None, **options) -> SceneRun:
    """Solve the scene with each of its methods.

    Args:
        scene: The scene.
        robot: Its robot (default :func:`load_robot`).
        trajectory: Its trajectory (default :func:`load_trajectory`).
        **options: ``limits``, ``checks``, ``thresholds`` of
            :func:`offshore_crane.dynamics.solve`.

    Raises:
        The errors of :func:`offshore_crane.dynamics.solve` and of the loaders.
    """
    robot = robot or load_robot(scene)
    traj = trajectory or load_trajectory(scene, robot)
    results, seconds = {}, {}
    for m in scene.methods:
        t0 = time.perf_counter()
        results[m] = _solve(scene, robot, traj, m, scene.leg_model, **options)
        seconds[m] = time.perf_counter() - t0
    return SceneRun(scene, robot, traj, results, seconds)


def compare_methods(run_: SceneRun) -> list[tuple[str, float, float, int, int]]:
    """Each method after the first against the first, over the wanted actuators.

    Returns:
        ``[(method, max |ΔX|, max |X_first|, relative, sample, column of X), ...]``.
    """
    cols = [k for k, n in enumerate(ACTUATORS) if n in run_.result.outputs]
    ref = run_.result.X[:, cols]
    scale = np.abs(ref).max()
    out = []
    for m, res in list(run_.results.items())[1:]:
        diff = np.abs(res.X[:, cols] - ref)
        i, j = np.unravel_index(np.argmax(diff), diff.shape)
        rel = diff.max() / scale if scale > 0 else diff.max()
        out.append((m, float(diff.max()), float(scale), float(rel), int(i), cols[j]))
    return out


# --------------------------------------------------------------------------- fidelity
@dataclass(frozen=True)
class Fidelity:
    """One leg model against ``full`` (method kane).

    Attributes:
        leg_model: ``"full"``, ``"thin-rod"`` or ``"massless"``.
        seconds: Median run time of :func:`~offshore_crane.dynamics.solve` [s].
        deviation: ``(k,)`` max over time of |X − X_full| per wanted actuator [N·m, N].
        relative: ``(k,)`` ``deviation / max |X_full|`` per actuator.
        approximations: Labels of the approximations used (empty: exact).
        pruned: What the solver skipped.
    """

    leg_model: str
    seconds: float
    deviation: np.ndarray
    relative: np.ndarray
    approximations: tuple
    pruned: tuple


def compare_fidelity(scene: Scene, robot=None, trajectory=None,
                     repeat: int = FIDELITY_REPEAT, **options):
    """Run time and deviation from ``full`` of each leg model (method kane).

    Args:
        scene, robot, trajectory: As :func:`run`.
        repeat: Timed runs per leg model (after one untimed warm-up run); the median is
            reported.
        **options: Options of :func:`offshore_crane.dynamics.solve`.

    Returns:
        ``(names, scale, rows)``: the wanted actuators, ``(k,)`` max |X_full| per
        actuator, and one :class:`Fidelity` per leg model (``full`` first).
    """
    robot = robot or load_robot(scene)
    if robot.hybrid.cable is not None:
        raise SceneError(f"{scene.where()}: the leg models' fidelity is compared on a rigid "
                         "robot; this one's payload hangs on a cable (computed with the full "
                         "leg model only)", path=scene.path, name="payload.cable_length")
    traj = trajectory or load_trajectory(scene, robot)
    names = scene.wanted()
    cols = [ACTUATORS.index(n) for n in names]
    rows, ref = [], None
    for model in LEG_MODELS:
        res = _solve(scene, robot, traj, "kane", model, **options)      # warm-up
        times = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            _solve(scene, robot, traj, "kane", model, **options)
            times.append(time.perf_counter() - t0)
        X = res.X[:, cols]
        if ref is None:
            ref = X
            scale = np.abs(ref).max(axis=0)
        dev = np.abs(X - ref).max(axis=0)
        rel = np.divide(dev, scale, out=np.zeros_like(dev), where=scale > 0)
        rows.append(Fidelity(model, statistics.median(times), dev, rel,
                             res.approximations, res.pruned))
    return names, scale, rows


def format_fidelity(names, scale, rows, n_samples: int, repeat: int = FIDELITY_REPEAT) -> str:
    """The fidelity report of :func:`compare_fidelity` as two fixed-width tables."""
    full = rows[0].seconds
    lines = [f"fidelity of the leg models against 'full' (method kane, {n_samples} samples, "
             f"run time: median of {repeat} runs)",
             f"{'leg model':<10}{'time [ms]':>11}{'speed-up':>10}{'worst rel. dev.':>17}"
             "  approximation"]
    for r in rows:
        worst = float(r.relative.max()) if r.relative.size else 0.0
        lines.append(f"{r.leg_model:<10}{r.seconds * 1e3:>11.3f}{full / r.seconds:>10.2f}"
                     f"{worst:>17.3e}  {'; '.join(r.approximations) or 'exact'}")
    legs_skipped = any("leg kinematics" in p for p in rows[0].pruned)
    if legs_skipped:
        lines.append("(no leg force wanted: the legs are not evaluated, so the leg model "
                     "changes nothing)")
    units = {n: u for n, u in zip(ACTUATORS, ACTUATOR_UNITS)}
    head = f"{'actuator':<9}{'unit':<5}{'max |X_full|':>14}"
    for r in rows[1:]:
        head += f"{'max |ΔX| ' + r.leg_model:>22}{'relative':>11}"
    lines += ["", head]
    for k, n in enumerate(names):
        line = f"{n:<9}{units[n]:<5}{scale[k]:>14.5g}"
        for r in rows[1:]:
            line += f"{r.deviation[k]:>22.4e}{r.relative[k]:>11.2e}"
        lines.append(line)
    return "\n".join(lines)


def with_trajectory(scene: Scene, where: str, source: str | None) -> Scene:
    """``scene`` driven by another trajectory source (``--trajectory``): its ``[sea]``,
    ``[operation]``, span and finite-difference order belong to its own source and are
    dropped; the same source (or None) leaves the scene as it is."""
    if source is None or source == scene.trajectory:
        return scene
    return replace(scene, origin=where, trajectory=source, sea={}, operation=None,
                   duration=None, rate=None, fd_order=4)


def with_overrides(scene: Scene, where: str, **changes) -> Scene:
    """``scene`` with some fields replaced (e.g. by command-line flags), re-checked.

    Raises:
        SceneError: the result does not fit together (:func:`check_scene`).
    """
    changes = {k: v for k, v in changes.items() if v is not None}
    if not changes:
        return scene
    return replace(scene, origin=where, **changes)
