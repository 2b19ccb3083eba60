"""The scene format's sections and keys, and the small value checks every table reader shares.
"""

from __future__ import annotations

import math

from offshore_crane.errors import SceneError
from offshore_crane.io import toml_value


SECTIONS = ("robot", "subsystems", "payload", "cable", "actuators", "trajectory", "sea",
            "operation", "control", "lift", "extremes", "sensors")
TOP_KEYS = ("name", "description", "gravity", "outputs", "methods")
SUBSYSTEM_KEYS = ("platform", "arm", "leg_model", "deck_pose")
PAYLOAD_KEYS = ("mass", "offset", "inertia", "cable_length", "sway_damping", "drag_area",
                "air_density", "limits")
#: [payload.limits] keys: the hanging load's limits judged by ``size``.
LOAD_LIMIT_KEYS = ("sway_max_deg", "tension_ratio_min", "tension_max")
CABLE_KEYS = ("initial", "initial_rate", "substeps", "slack", "ea", "damping", "winch")
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
                "noise_qd", "seed", "model", "lower", "upper", "saturation", "anti_sway",
                "compensation", "delay", "target", "ki", "windup")
#: [sensors] keys (:class:`offshore_crane.simulation.instruments.Sensors`).
SENSOR_KEYS = ("noise_q", "noise_qd", "delay", "resolution_q", "resolution_qd", "seed")
#: [actuators] keys that describe the actuators' dynamics
#: (:class:`offshore_crane.simulation.instruments.Actuators`), not the robot's capacities.
ACTUATOR_MODEL_KEYS = ("rate_limit", "lag")
#: [lift] keys: a lift-off from or a set-down onto a deck (docs/cable.md).
LIFT_KEYS = ("event", "deck_height", "deck")
#: [lift] events.
LIFT_EVENTS = ("lift-off", "set-down")
#: [extremes] keys: how a sea scene's extremes are judged (scenes.exposure, docs/sizing.md).
EXTREMES_KEYS = ("exposure", "record", "seeds", "spin_up")
#: [extremes] record: exposure-length stationary records, or the scene's own record.
EXTREMES_RECORDS = ("exposure", "scene")
#: Fewest records a Gumbel fit of their maxima is made on (studies.sizing.MIN_SEEDS): with
#: 5 maxima the maximum-likelihood scale is within about ±40 % (one standard deviation).
GUMBEL_MIN_RECORDS = 5
#: [extremes] defaults: a 3-hour full-scale exposure [h] (the usual duration of a
#: stationary sea state, DNV-RP-C205) on stationary records that long, as many seeds as a
#: Gumbel fit needs, the spin-up from the scene's modes.
EXTREMES_DEFAULTS = {"exposure": 3.0, "record": "exposure", "seeds": GUMBEL_MIN_RECORDS,
                     "spin_up": None}
#: [control] target keys: a point on a second vessel's deck (ship-to-ship transfer).
TARGET_KEYS = ("point", "seed", "vessel")
#: [control] keys that are Controller arguments (the others: simulate's).
CONTROLLER_KEYS = ("law", "kp", "kd", "rate", "lower", "upper", "saturation", "noise_q",
                   "noise_qd", "seed", "anti_sway", "ki", "windup")
#: Where a scene file sets the robot fields it owns besides [robot] (for messages).
SCENE_FIELDS = {"arm.enabled": "[subsystems] arm", "payload.mass": "[payload] mass",
                "payload.com": "[payload] offset", "payload.inertia": "[payload] inertia",
                "payload.cable_length": "[payload] cable_length",
                "payload.sway_damping": "[payload] sway_damping",
                "payload.drag_area": "[payload] drag_area",
                "payload.air_density": "[payload] air_density"}


def scene_field(name: str) -> str:
    """Where a scene file sets the robot field ``name`` besides [robot]."""
    if name.startswith("actuators."):
        return f"[actuators] {name[len('actuators.'):]}"
    return SCENE_FIELDS[name]
#: Run time of the fidelity report: median of this many runs per leg model.
FIDELITY_REPEAT = 5


def _finite(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def is_finite_vector(v, n: int) -> bool:
    return isinstance(v, (tuple, list)) and len(v) == n and all(_finite(x) for x in v)


def same_value(a, b) -> bool:
    from offshore_crane.robot.overrides import conflicts

    return not conflicts({"x": a}, {"x": b})


def normalised(where: str, raw: dict, section: str | None, flatten: bool = False) -> dict:
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
