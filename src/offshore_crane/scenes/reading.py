"""Reading a scene file: every table checked key by key, errors naming the file, the section
and the key.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from offshore_crane.conventions import ACTUATORS, GRAVITY
from offshore_crane.dynamics import LEG_MODELS, METHODS
from offshore_crane.errors import SceneError
from offshore_crane.io import toml_value
from offshore_crane.scenes.keys import (ACTUATOR_MODEL_KEYS, SENSOR_KEYS, CABLE_KEYS,
                                        CONTROLLER_KEYS, CONTROL_KEYS, INERTIA_KEYS,
                                        OPERATION_KEYS, PAYLOAD_KEYS, SEA_KEYS, SECTIONS,
                                        LOAD_LIMIT_KEYS, TARGET_KEYS, LIFT_KEYS,
                                        LIFT_EVENTS,
                                        SUBSYSTEM_KEYS, TOP_KEYS, TRAJECTORY_KEYS, normalised,
                                        same_value, scene_field)
from offshore_crane.scenes.scene import Scene
from offshore_crane.scenes.tables import TableReader, section


# --------------------------------------------------------------------------- reading
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
    overrides = normalised(where, robot, "[robot]", flatten=True)
    r = section(where, data, "payload", PAYLOAD_KEYS)
    payload = {}
    if "inertia" in r.table and not isinstance(r.get("inertia"), dict):
        r.fail("inertia", f"must be a table of {', '.join(INERTIA_KEYS)} [kg·m²]")
    if "inertia" in r.table:
        TableReader(where, "payload.inertia", r.get("inertia"), INERTIA_KEYS)  # known keys
    if "limits" in r.table:
        if not isinstance(r.get("limits"), dict):
            r.fail("limits", f"must be a table of {', '.join(LOAD_LIMIT_KEYS)}")
        limits = TableReader(where, "payload.limits", r.get("limits"), LOAD_LIMIT_KEYS)
        for key in LOAD_LIMIT_KEYS:
            if key in limits.table:
                payload[f"payload.limits.{key}"] = limits.get(key)
    for key, name in (("mass", "payload.mass"), ("offset", "payload.com"),
                      ("inertia", "payload.inertia"), ("cable_length", "payload.cable_length"),
                      ("sway_damping", "payload.sway_damping"),
                      ("drag_area", "payload.drag_area"),
                      ("air_density", "payload.air_density")):
        if key in r.table:
            payload[name] = r.get(key)
    sub = data.get("subsystems", {})
    if isinstance(sub, dict) and "arm" in sub:
        payload["arm.enabled"] = sub["arm"]
    actuators = data.get("actuators", {})
    if not isinstance(actuators, dict):
        raise SceneError(f"{where}: actuators = {toml_value(actuators)}: must be a table "
                         "[actuators]", path=where, name="actuators")
    actuators = {k: v for k, v in actuators.items() if k not in ACTUATOR_MODEL_KEYS}
    payload.update(normalised(where, {"actuators": actuators}, "[actuators]", flatten=True))
    for name, value in normalised(where, payload, None).items():
        if name in overrides and not same_value(overrides[name], value):
            raise SceneError(f"{where}: {scene_field(name)} = {toml_value(value)} contradicts "
                             f"[robot] {name} = {toml_value(overrides[name])}: give it once",
                             path=where, name=name)
        overrides[name] = value
    return dict(robot=overrides, robot_description=description)


def _trajectory(where: str, data: dict, base: Path | None) -> dict:
    r = section(where, data, "trajectory", TRAJECTORY_KEYS)
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
    r = section(where, data, "sea", SEA_KEYS)
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
        sea["vessel"] = _vessel(vessel, base)
        if sea["vessel"] is None:
            from offshore_crane.motion.sea import vessel_names

            r.fail("vessel", f"neither a shipped vessel ({', '.join(vessel_names())}) nor "
                   f"a file {vessel} (relative paths start at the scene file's folder)")
    o = section(where, data, "operation", OPERATION_KEYS)
    operation = None
    if "waypoints" in o.table:
        w = o.get("waypoints")
        if (not isinstance(w, list) or not w or any(
                not isinstance(row, list) or len(row) != len(w[0]) or len(row) not in (4, 5)
                or any(isinstance(x, bool) or not isinstance(x, (int, float))
                       or not math.isfinite(x) for x in row) for row in w)):
            o.fail("waypoints", "must be a list of [t, q7, q8, q9] rows of finite numbers "
                   "[s, rad, rad, m] (with a winch: [t, q7, q8, q9, L], L [m])")
        operation = tuple(tuple(float(x) for x in row) for row in w)
    return dict(sea=sea, operation=operation)


def _lift(where: str, data: dict, base: Path | None) -> dict:
    """``[lift]``: ``event`` (``"lift-off"`` or ``"set-down"``), ``deck_height`` [m]
    (model scale, base frame: the deck's mean height under the load; required), ``deck`` (a point
    on a second vessel heaving in the scene's sea, as ``[control] target``; none: a still
    deck)."""
    r = section(where, data, "lift", LIFT_KEYS)
    if not r.table:
        return {}
    out = {"event": r.string("event", None, LIFT_EVENTS)}
    if out["event"] is None:
        r.fail_key("event", f"[lift] needs event = one of {', '.join(LIFT_EVENTS)}")
    if "deck_height" in r.table:
        out["deck_height"] = r.number("deck_height", unit="m")
    if "deck" in r.table:
        out["deck"] = _target(where, r.get("deck"), base, "[lift] deck")
    return out


def _target(where: str, value, base: Path | None, what: str = "[control] target") -> dict:
    """``[control] target = {point = [x, y, z], seed = n, vessel = "..."}``: a point on a
    second vessel's deck, full scale [m] in that vessel's axes from its RAO reference
    point; its own phases (``seed``, required: another vessel is another record); the
    scene's vessel unless ``vessel`` names another (a shipped one or a RAO file)."""
    def fail(problem):
        raise SceneError(f"{where}: {what}: {problem}", path=where,
                         name=what.replace("[", "").replace("] ", "."))

    if not isinstance(value, dict):
        fail("must be a table {point = [x, y, z], seed = n} (a point on a second "
             "vessel's deck [m], full scale, and its record's seed)")
    unknown = [k for k in value if k not in TARGET_KEYS]
    if unknown:
        fail(f"unknown key '{unknown[0]}' (use {', '.join(TARGET_KEYS)})")
    point = value.get("point")
    if (not isinstance(point, list) or len(point) != 3 or any(
            isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x)
            for x in point)):
        fail(f"point = {point!r} must be 3 finite numbers [m] (full scale, the second "
             "vessel's axes from its RAO reference point)")
    seed = value.get("seed")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        fail(f"seed = {seed!r} must be an integer ≥ 0 (the second vessel's record: give "
             "another than [sea] seed)")
    out = {"point": tuple(float(x) for x in point), "seed": seed}
    if "vessel" in value:
        vessel = value["vessel"]
        path = _vessel(vessel, base) if isinstance(vessel, str) else None
        if path is None:
            fail(f"vessel = {vessel!r} is {_NOT_A_VESSEL}")
        out["vessel"] = path
    return out


#: What a ``vessel`` value must be, for messages.
_NOT_A_VESSEL = ("neither a shipped vessel nor a RAO file (relative paths start at the "
                 "scene file's folder)")


def _vessel(vessel: str, base: Path | None) -> str | None:
    """A shipped vessel's name, or the RAO file it names (relative to the scene's
    folder) as a path; None when it is neither."""
    from offshore_crane.motion.sea import vessel_names

    if vessel in vessel_names():
        return vessel
    p = Path(vessel)
    if not p.is_absolute() and base is not None:
        p = base / p
    return str(p) if p.is_file() else None


def _control(where: str, data: dict, base: Path | None = None) -> dict:
    """The ``[control]`` section of ``offshore-crane simulate``: checked values, as a dict
    of :func:`controller`'s and :func:`offshore_crane.simulation.rigid.simulate`'s arguments."""
    from offshore_crane.simulation.control import Controller
    from offshore_crane.errors import InputError
    from offshore_crane.simulation.rigid import INTEGRATORS

    r = section(where, data, "control", CONTROL_KEYS)
    out: dict = {}
    if "law" in r.table:
        out["law"] = r.string("law")          # a law of the registry: checked below
    if "ki" in r.table:
        v = r.get("ki")
        out["ki"] = r.vector("ki", 9, unit="N·m/(rad·s), N/(m·s)") if isinstance(
            v, list) else r.number("ki", unit="N·m/(rad·s), N/(m·s)", minimum=0.0)
    if "windup" in r.table:
        out["windup"] = r.number("windup", unit="s", positive=True)
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
    if "compensation" in r.table:
        from offshore_crane.simulation.compensation import MODES

        out["compensation"] = r.string("compensation", choices=MODES)
    if "delay" in r.table:
        out["delay"] = r.number("delay", unit="s", minimum=0.0)
    if "target" in r.table:
        out["target"] = _target(where, r.get("target"), base)
    if "step" in r.table:
        out["step"] = r.number("step", unit="s", positive=True)
    if "integrator" in r.table:
        out["integrator"] = r.string("integrator", choices=INTEGRATORS)
    if "saturation" in r.table:
        out["saturation"] = r.boolean("saturation", True)
    if "seed" in r.table:
        out["seed"] = r.integer("seed", 0)
    if "model" in r.table:
        model = r.get("model")
        if not isinstance(model, dict):
            r.fail("model", "must be a table of robot parameters (the controller's model)")
        out["model"] = normalised(where, model, "[control] model", flatten=True)
    try:                                # the law's own checks (gains, limits), named here
        Controller(**{k: v for k, v in out.items() if k in CONTROLLER_KEYS})
    except InputError as exc:
        raise SceneError(f"{where}: [control] {exc}", path=where, name="control") from None
    return out


def _instruments(where: str, data: dict) -> dict:
    """``[sensors]`` and the actuator models of ``[actuators]`` (``rate_limit``, ``lag``):
    ``{"sensors": {...}, "actuator_models": {...}}`` of
    :class:`~offshore_crane.simulation.instruments.Sensors`' and ``Actuators``' arguments,
    checked by them."""
    from offshore_crane.errors import InputError
    from offshore_crane.simulation.instruments import Actuators, Sensors

    r = section(where, data, "sensors", SENSOR_KEYS)
    sensors: dict = {}
    for key, unit in (("noise_q", "m, rad"), ("noise_qd", "m/s, rad/s"),
                      ("resolution_q", "m, rad"), ("resolution_qd", "m/s, rad/s")):
        if key in r.table:
            v = r.get(key)
            sensors[key] = r.vector(key, 9, unit=unit) if isinstance(v, list) else r.number(
                key, unit=unit, minimum=0.0)
    if "delay" in r.table:
        sensors["delay"] = r.number("delay", unit="s", minimum=0.0)
    if "seed" in r.table:
        sensors["seed"] = r.integer("seed", 0)
    table = data.get("actuators", {})
    actuators: dict = {}
    for key in ("rate_limit", "lag"):
        if isinstance(table, dict) and key in table:
            actuators[key] = table[key]
    for name, cls, values in (("sensors", Sensors, sensors),
                              ("actuators", Actuators, actuators)):
        try:
            cls(**values)
        except (InputError, TypeError) as exc:
            raise SceneError(f"{where}: [{name}] {exc}", path=where, name=name) from None
    return {"sensors": sensors, "actuator_models": actuators}


def _cable(where: str, data: dict) -> dict:
    """The ``[cable]`` section: :func:`offshore_crane.dynamics.cable.inverse_dynamics`'s
    ``initial``, ``initial_rate``, ``substeps`` and ``slack``; an elastic cable's ``ea``
    [N] and ``damping`` [N·s/m]; ``winch`` (the hoist column of ``[operation]``),
    checked."""
    from offshore_crane.dynamics.cable import SLACK

    r = section(where, data, "cable", CABLE_KEYS)
    out: dict = {}
    if "initial" in r.table:
        out["initial"] = r.vector("initial", 2, unit="rad")
    if "initial_rate" in r.table:
        out["initial_rate"] = r.vector("initial_rate", 2, unit="rad/s")
    if "substeps" in r.table:
        out["substeps"] = r.integer("substeps", 1, "RK4 steps per sample interval")
    if "slack" in r.table:
        out["slack"] = r.string("slack", choices=SLACK)
    if "ea" in r.table:
        out["ea"] = r.number("ea", None, "N", positive=True)
    if "damping" in r.table:
        out["damping"] = r.number("damping", None, "N·s/m", minimum=0.0)
    if "winch" in r.table:
        out["winch"] = r.boolean("winch", False)
    return out


def _extremes(where: str, data: dict) -> dict:
    """The ``[extremes]`` section (:mod:`offshore_crane.scenes.exposure`): ``exposure``
    [h], ``record``, ``seeds``, ``spin_up`` [s], checked."""
    from offshore_crane.scenes.keys import EXTREMES_KEYS, EXTREMES_RECORDS

    r = section(where, data, "extremes", EXTREMES_KEYS)
    out: dict = {}
    if "exposure" in r.table:
        out["exposure"] = r.number("exposure", None, "h", positive=True)
    if "record" in r.table:
        out["record"] = r.string("record", choices=EXTREMES_RECORDS)
    if "seeds" in r.table:
        out["seeds"] = r.integer("seeds", 1, "records per sea state")
    if "spin_up" in r.table:
        out["spin_up"] = r.number("spin_up", None, "s", minimum=0.0)
    return out


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
    top = TableReader(where, None, {k: v for k, v in data.items() if k not in SECTIONS},
                  TOP_KEYS)
    sub = section(where, data, "subsystems", SUBSYSTEM_KEYS)
    control = _control(where, data, base)
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
        lift=_lift(where, data, base), extremes=_extremes(where, data),
        **_instruments(where, data),
        **_trajectory(where, data, base),
        **_sea(where, data, base))


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
