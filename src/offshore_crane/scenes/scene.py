"""What a scene is: :class:`Payload` and :class:`Scene` (one choice per column of the
pipeline), checked as a whole when created: its robot (description, overrides, payload), its
sea state and the values that depend on each other.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from offshore_crane.conventions import (AIR_DENSITY, ARM_ACTUATORS, ACTUATORS, GRAVITY,
                                        LEG_ACTUATORS)
from offshore_crane.dynamics import LEG_MODELS, METHODS
from offshore_crane.errors import SceneError
from offshore_crane.io import toml_value
from offshore_crane.scenes.keys import (INERTIA_KEYS, SEA_KEYS, SEA_REQUIRED, is_finite_vector,
                                        normalised, same_value)


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
        drag_area: the payload's drag area C_d·A [m²] (with a cable; 0: no drag).
        air_density: [kg/m³] of the air the drag acts in.
    """

    mass: float = 0.0
    offset: tuple = (0.0, 0.0, 0.0)
    inertia: tuple = (0.0,) * 6
    cable_length: float = 0.0
    sway_damping: float = 0.0
    drag_area: float = 0.0
    air_density: float = AIR_DENSITY

    def overrides(self) -> dict:
        """The dotted robot fields this payload sets."""
        return {"payload.mass": self.mass, "payload.com": list(self.offset),
                "payload.inertia": dict(zip(INERTIA_KEYS, self.inertia)),
                "payload.cable_length": self.cable_length,
                "payload.sway_damping": self.sway_damping,
                "payload.drag_area": self.drag_area, "payload.air_density": self.air_density}


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
        control: ``[control]``: a controller (simulate), or a compensation.
        cable: ``[cable]``: the hanging load's options.
        lift: ``[lift]``: ``{"event": "lift-off" | "set-down", "deck_height": [m],
            "deck": {point, seed, vessel}}`` or empty.
        sensors: ``[sensors]``: the measured q, q̇'s noise, delay, quantisation
            (:class:`~offshore_crane.simulation.instruments.Sensors`' arguments).
        actuator_models: ``[actuators] rate_limit, lag``: the actuators' dynamics
            (:class:`~offshore_crane.simulation.instruments.Actuators`' arguments).
        extremes: ``[extremes]``: how a sea scene's extremes are judged
            (:mod:`offshore_crane.scenes.exposure`): ``exposure`` [h] full scale,
            ``record`` (``"exposure"`` or ``"scene"``), ``seeds``, ``spin_up`` [s] model
            scale; absent keys take :data:`~offshore_crane.scenes.keys.EXTREMES_DEFAULTS`.
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
    lift: dict = field(default_factory=dict)
    extremes: dict = field(default_factory=dict)
    sensors: dict = field(default_factory=dict)
    actuator_models: dict = field(default_factory=dict)
    #: Where the scene comes from, for messages (the file, or the file with the
    #: command-line options applied).
    origin: str | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        _check_robot(self)
        _check_values(self)
        check_scene(self)
        _check_sea(self)

    @property
    def simulated(self) -> bool:
        """True when the scene is run forward under a controller (a ``[control]`` law);
        ``compensation``, ``delay`` and ``target`` alone prescribe a compensated lift
        instead."""
        return bool(set(self.control) - {"compensation", "delay", "target"})

    @property
    def compensation(self) -> str:
        """``[control] compensation``: ``"none"``, ``"arm"`` or ``"arm+winch"``."""
        return self.control.get("compensation", "none")

    @property
    def varying_cable(self) -> list[str]:
        """The scene's keys that make its cable other than rigid at a fixed length (an
        elastic cable, a winch, a compensation's winch or arm): ``["[cable] ea", ...]``,
        empty for none — what the forward simulation and the pictures do not handle."""
        return [f"[cable] {k}" for k in ("ea", "winch") if k in self.cable] + (
            ["[control] compensation"] if self.compensation != "none" else []) + (
            ["[lift]"] if self.lift else [])

    def where(self) -> str:
        """Where the scene comes from, for messages."""
        return self.origin or self.path or f"scene '{self.name}'"

    def data_files(self) -> list[str]:
        """The files running this scene reads besides the scene file itself: the robot
        description (the shipped default when none is named), a trajectory CSV, a
        vessel's RAO table given as a file."""
        from offshore_crane.robot.description import default_description

        files = [self.robot_description or str(default_description())]
        if self.trajectory not in ("table1", "sea"):
            files.append(self.trajectory)
        for vessel in (self.sea.get("vessel"), self.control.get("target", {}).get("vessel"),
                       self.lift.get("deck", {}).get("vessel")):
            if vessel is not None and os.path.isfile(str(vessel)):
                files.append(str(vessel))
        return files

    def inputs(self) -> list[str]:
        """Every file running this scene reads (the scene file and :meth:`data_files`):
        no output may be one of them."""
        return ([self.path] if self.path else []) + self.data_files()

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
    robot = normalised(where, scene.robot, None)
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
        for name, value in normalised(where, own, None).items():
            if name in robot and not same_value(robot[name], value):
                raise SceneError(f"{where}: {name} = {toml_value(value)} contradicts robot "
                                 f"{name} = {toml_value(robot[name])}: give it once",
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
        # the description's error names its file and the overrides involved; a scene
        # read from a file adds where it is, the default scene nothing
        prefix = f"{scene.where()}: " if scene.path else ""
        raise SceneError(f"{prefix}{exc}", path=scene.path, name=exc.field) from None


def _payload_of(spec) -> Payload:
    """The :class:`Payload` of a resolved description."""
    p = spec.payload
    return Payload(float(p.mass), tuple(float(x) for x in p.com),
                   tuple(float(p.inertia[i, j]) for i, j in
                         ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))),
                   float(spec.cable_length), float(spec.sway_damping), float(spec.drag_area),
                   float(spec.air_density))


def _check_sea(scene: "Scene") -> None:
    """The ``[sea]`` / ``[operation]`` sections against the trajectory source and the
    sea module's argument checks (what :func:`offshore_crane.motion.sea.sea_state` would say)."""
    where = scene.where()

    def fail(key, message):
        raise SceneError(f"{where}: {message}", path=scene.path, name=key)

    hoisted = scene.operation is not None and len(scene.operation[0]) == 5
    if scene.cable.get("winch") and not hoisted:
        fail("cable.winch", "[cable] winch = true needs the hoist column in [operation] "
             "waypoints: rows [t, q7, q8, q9, L] with L the cable length [m]")
    if hoisted and not scene.cable.get("winch"):
        fail("operation.waypoints", "[operation] waypoints have a fifth column (the cable "
             "length L): set [cable] winch = true to hoist the load")
    if hoisted and min(row[4] for row in scene.operation) <= 0.0:
        fail("operation.waypoints", "[operation] the hoist column L must stay > 0 m")
    if scene.lift:
        _check_lift(scene, fail)
    from offshore_crane.scenes.bounds import check_bounds

    check_bounds(scene, fail)
    on_line = scene.control.get("law") in ("arm-compensation", "arm-winch-compensation")
    if "target" in scene.control and "compensation" not in scene.control and not on_line:
        fail("control.target", "[control] target is tracked by the motion compensation: "
             "set [control] compensation = \"arm\" or \"arm+winch\" (\"none\": the "
             "uncompensated lift measured against the target), or law = "
             "\"arm-compensation\" (on line)")
    if on_line and scene.control.get("compensation", "none") != "none":
        fail("control.law", f"[control] law = \"{scene.control['law']}\" solves the arm on "
             "line: drop [control] compensation (the reference computed beforehand)")
    if scene.trajectory != "sea":
        if "target" in scene.control:
            fail("control.target", "[control] target is a point on a second vessel in the "
                 "scene's sea: it needs [trajectory] source = \"sea\"")
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
    for name, point in (("[control] target", scene.control.get("target")),
                        ("[lift] deck", scene.lift.get("deck"))):
        if point is not None:                           # a second vessel's record
            try:
                check_arguments(**{**sea_arguments(scene), **point})
            except SeaStateError as exc:
                fail(name.replace("[", "").replace("] ", "."), f"{name}: {exc}")


def _check_lift(scene: "Scene", fail) -> None:
    """``[lift]`` against the rest: an elastic cable (the load leaves or meets the deck
    on it), a set-down's deck height, a heaving deck's sea, no compensation."""
    event = scene.lift.get("event")
    if event not in ("lift-off", "set-down"):
        fail("lift.event", f"[lift] event = {event!r}: use \"lift-off\" or \"set-down\"")
    if "ea" not in scene.cable:
        fail("lift", f"[lift] {event} needs an elastic cable: set [cable] ea (and damping)")
    if "deck_height" not in scene.lift:
        fail("lift.deck_height", f"[lift] {event} needs deck_height [m], the deck's (mean) "
             "height in the base frame under the load (model scale; the tip's height less "
             "the cable's length is where a hanging load would touch it)")
    if scene.compensation != "none":
        fail("lift", "[lift] and [control] compensation together are not modelled: drop "
             "one of them")
    if "deck" in scene.lift and scene.trajectory != "sea":
        fail("lift.deck", "[lift] deck is a point on a second vessel in the scene's sea: "
             "it needs [trajectory] source = \"sea\"")


def sea_arguments(scene: "Scene") -> dict:
    """``scene.sea`` as keyword arguments of :func:`offshore_crane.motion.sea.sea_motion` (but
    duration, rate and robot)."""
    args = dict(scene.sea)
    args["heading_deg"] = args.pop("heading", None)
    if scene.operation is not None:
        args["operation"] = [list(row[:4]) for row in scene.operation]
    return args


def hoist_waypoints(scene: "Scene") -> list | None:
    """The winch's ``[(t [s], L [m]), ...]`` from the hoist column of ``[operation]``
    (``[cable] winch = true``), or None."""
    if not scene.cable.get("winch") or scene.operation is None:
        return None
    return [(row[0], row[4]) for row in scene.operation]


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
    if not is_finite_vector(scene.gravity, 3):
        fail("gravity", scene.gravity, "must be 3 finite numbers [m/s²]")
    if scene.deck_pose is not None and not is_finite_vector(scene.deck_pose, 6):
        fail("subsystems.deck_pose", scene.deck_pose, "must be 6 finite numbers [m, rad]")
    _check_extremes(scene, fail)


def _check_extremes(scene: Scene, fail) -> None:
    """``[extremes]``: its keys' domains, and a sea to judge."""
    from offshore_crane.scenes.keys import EXTREMES_KEYS, EXTREMES_RECORDS

    x = scene.extremes
    for key in x:
        if key not in EXTREMES_KEYS:
            fail(f"extremes.{key}", x[key], f"unknown key: known keys are "
                 f"{', '.join(EXTREMES_KEYS)}")
    if x and scene.trajectory != "sea":
        fail("extremes", x, "[extremes] judges a random sea's extremes: it needs "
             "[trajectory] source = \"sea\"")
    number = (int, float)
    if "exposure" in x and not (isinstance(x["exposure"], number)
                                and not isinstance(x["exposure"], bool)
                                and 0.0 < x["exposure"] < float("inf")):
        fail("extremes.exposure", x["exposure"], "must be a positive number of hours "
             "(full scale)")
    if x.get("record") == "exposure" and scene.lift:
        fail("extremes.record", x["record"], "a [lift] event happens once: it is judged on "
             "its own record, not on exposure records (drop [extremes] record)")
    if "record" in x and x["record"] not in EXTREMES_RECORDS:
        fail("extremes.record", x["record"], f"must be one of {', '.join(EXTREMES_RECORDS)}")
    if "seeds" in x and (isinstance(x["seeds"], bool) or not isinstance(x["seeds"], int)
                         or x["seeds"] < 1):
        fail("extremes.seeds", x["seeds"], "must be an integer ≥ 1 (records per sea state)")
    if x.get("spin_up") is not None and not (
            isinstance(x["spin_up"], number) and not isinstance(x["spin_up"], bool)
            and 0.0 <= x["spin_up"] < float("inf")):
        fail("extremes.spin_up", x["spin_up"], "must be a finite number of seconds ≥ 0 "
             "(model scale)")


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
