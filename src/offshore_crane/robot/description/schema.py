"""The description format: every field with its kind, unit and meaning (:data:`SCHEMA`), the
names of the fields and the limits that apply to every description.
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass


FORMAT = 1
DESCRIPTION_DIR = "descriptions"
DEFAULT_DESCRIPTION = "lab.toml"
N_LEGS = 6
#: Largest magnitude of any number in a description. The inverse dynamics forms
#: products of at most three description quantities in one term (a mass times two
#: lengths: m r², m c × (ω × (ω × c)) with the rates from the trajectory, m g l); with each
#: factor below 1e100 such a product stays below 1e300, a factor 1e8 under the largest
#: float64 (1.8e308), which leaves room for the trajectory's rates and for sums over the
#: 17 bodies. No machine comes near: 1e100 kg is 1e48 solar masses.
MAGNITUDE_LIMIT = 1e100
#: Relative tolerance (of the part's length) of the centre-of-mass-inside-the-part check,
#: for CoMs written at the part's end with a few digits.
COM_RTOL = 1e-9
#: Anchors closer than this fraction of the anchors' spread are coincident; the same
#: fraction bounds the distance from a common line for "collinear". Machined joint
#: positions are not specified below a nanometre per metre, so smaller separations are the
#: round-off of written coordinates, not a design.
ANCHOR_RTOL = 1e-9
#: Two axes given as perpendicular (a1, a2) may be off by this cosine (9 digits written).
ORTHOGONAL_TOL = 1e-9
#: A design whose leg-Jacobian (Stewart matrix) condition number at home reaches this is
#: refused: the error threshold of the run-time singularity policy (checks.Thresholds).
HOME_CONDITION_LIMIT = 1e8
#: The U-joint gimbal condition number 1/cos θ2 at home at or above which a1 counts as
#: parallel to the leg (same threshold as above).
GIMBAL_LIMIT = 1e8
#: Revolute arm limits beyond two turns are refused: likely degrees given for radians.
REVOLUTE_LIMIT = 2.0 * math.pi
#: Default drawings (visual only, never mass properties): the base and platform discs
#: reach this factor beyond the outermost anchor, are this fraction of their radius
#: thick; a leg part without radius is drawn this fraction of its length thick; an arm
#: body without shape is a sphere of this radius fraction of the distance to its child
#: joint (or of the platform's anchor radius for a body without child).
DISC_MARGIN = 1.15
DISC_THICKNESS = 0.08
LEG_DRAW_RATIO = 0.05
ARM_DRAW_RATIO = 0.15

LEG_KEYS = tuple(str(i) for i in range(1, N_LEGS + 1))
ACTUATOR_GROUPS = ("T1", "T2", "Fs", "Fl") + tuple(f"Fl{i}" for i in range(1, N_LEGS + 1))
ACTUATORS = ("T1", "T2", "Fs") + tuple(f"Fl{i}" for i in range(1, N_LEGS + 1))
ARM_BODIES = ("link1", "link2", "slider")
INERTIA_KEYS = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
XYZ = ("x", "y", "z")


# ============================================================================ schema
@dataclass(frozen=True)
class Leaf:
    """One field of the format: its kind, unit and meaning (the documentation's table).

    ``kind``: ``number``, ``int``, ``text``, ``choice``, ``bool``, ``vec3`` (3 numbers,
    components ``.x .y .z``), ``numbers6``/``numbers3`` (components ``.1``...),
    ``points6`` (6 vec3, ``.1`` ... ``.6`` then ``.x``...), ``inertia`` (``.ixx``...).
    """

    kind: str
    unit: str = ""
    doc: str = ""
    choices: tuple = ()


def _num(unit, doc):
    return Leaf("number", unit, doc)


def _anchors(points_doc: str, pairs_doc: str) -> dict:
    return {
        "points": Leaf("points6", "m", points_doc),
        "radius": _num("m", "radius of the anchors' circle"),
        "height": _num("m", "height of the circle's plane"),
        "angles_deg": Leaf("numbers6", "deg", "polar angle of each anchor"),
        "half_angle_deg": _num("deg", "half the angle between the two anchors of a pair"),
        "pair_angles_deg": Leaf("numbers3", "deg", pairs_doc),
    }


SHAPE = {
    "type": Leaf("choice", "", "solid drawn (and, without inertia, weighed)",
                 ("cylinder", "box", "sphere", "none")),
    "radius": _num("m", "cylinder or sphere radius"),
    "length": _num("m", "cylinder length along z"),
    "size": Leaf("vec3", "m", "box edges along x, y, z"),
    "xyz": Leaf("vec3", "m", "centre of the solid in the body frame"),
}
BODY = {
    "mass": _num("kg", "mass"),
    "com": Leaf("vec3", "m", "centre of mass in the body frame"),
    "inertia": Leaf("inertia", "kg·m²", "inertia about the centre of mass, body axes"),
    "shape": SHAPE,
}
PART = {
    "mass": _num("kg", "mass of the part"),
    "length": _num("m", "extent along the leg from its joint (lower: 0..length from P_i; "
                   "upper: -length..0 from S_i)"),
    "radius": _num("m", "drawing radius; without inertia: a solid cylinder's"),
    "com": Leaf("vec3", "m", "centre of mass in the part frame (default on the axis at "
                "half length)"),
    "inertia": Leaf("inertia", "kg·m²", "inertia about the centre of mass, part axes"),
}
LEG = {
    "lower": PART,
    "upper": PART,
    "stroke": {"min": _num("m", "shortest leg length |P_i S_i|"),
               "max": _num("m", "longest leg length")},
    "ujoint": {"limit": _num("rad", "|angle| limit of both U-joint axes")},
}
ACTUATOR = {
    "push_max": _num("N or N·m", "largest force (torque) along + of the joint"),
    "pull_max": _num("N or N·m", "largest force (torque) along − (magnitude)"),
    "speed_max": _num("m/s or rad/s", "largest |rate|"),
    "power_max": _num("W", "largest |force × rate|"),
}
WINCH = {
    "pull_max": _num("N", "largest line pull the winch holds"),
    "speed_max": _num("m/s", "largest |hoisting speed| (haul in or pay out)"),
    "acceleration_max": _num("m/s²", "largest |hoisting acceleration|"),
    "power_max": _num("W", "largest |line pull × hoisting speed|"),
    "reflected_mass": _num("kg", "drum and drive inertia reflected to the line, J/r² (> 0: "
                           "a commanded winch in the elastic lift's simulation)"),
}
PLACEMENT = {"origin": Leaf("vec3", "m", "origin in the parent frame"),
             "rpy": Leaf("vec3", "rad", "orientation in the parent frame (URDF rpy)")}
JOINT_BODY = {**PLACEMENT,
              "axis": Leaf("vec3", "", "joint axis in the joint frame"),
              "min": _num("rad or m", "lower joint limit"),
              "max": _num("rad or m", "upper joint limit"),
              **BODY}
SCHEMA = {
    "format": Leaf("int", "", f"format version ({FORMAT})"),
    "name": Leaf("text", "", "label"),
    "source": Leaf("text", "", "where the numbers come from"),
    "home": {"height": _num("m", "q3 of the home pose (O2's height at q = 0 otherwise)")},
    "base": {
        "joints": _anchors("U-joint centres P_i, base frame",
                           "centres of the pairs (legs 2k-1, 2k); default 0, 120, 240"),
        "ujoint_axes": Leaf("points6", "", "first U-joint axis a1 of each leg, base frame"),
        "ujoint_axes2": Leaf("points6", "", "second U-joint axis a2 at zero angles, base "
                             "frame"),
        "shape": SHAPE,
    },
    "platform": {**BODY,
                 "joints": _anchors("sphere centres S_i, platform frame",
                                    "centres of the pairs (legs 2k, 2k+1, leg 7 = 1); "
                                    "default 60, 180, 300")},
    "legs": {**LEG, **{k: LEG for k in LEG_KEYS}},
    "arm": {"enabled": Leaf("bool", "", "the crane arm is present"),
            "column": {**PLACEMENT, **BODY},
            **{b: JOINT_BODY for b in ARM_BODIES},
            "tip": PLACEMENT},
    "payload": {"mass": _num("kg", "payload mass (0: none)"),
                "com": Leaf("vec3", "m", "payload centre of mass in the arm_tip frame"),
                "inertia": Leaf("inertia", "kg·m²", "about its centre of mass, arm_tip axes"),
                "cable_length": _num("m", "cable length (0: welded)"),
                "sway_damping": _num("N·m·s/rad", "viscous damping of each sway angle "
                                     "(hanging payload; 0: none)"),
                "drag_area": _num("m²", "drag area C_d·A of the payload in air: drag "
                                  "½ ρ C_d A |v| v against its velocity v relative to "
                                  "still air (hanging payload; 0: none)"),
                "air_density": _num("kg/m³", "density ρ of the air the drag acts in "
                                    "(default 1.225, sea level at 15 °C)"),
                "limits": {
                    "sway_max_deg": _num("deg", "largest angle of the cable from the "
                                         "tip's vertical (hanging load; none: no limit)"),
                    "tension_ratio_min": _num("", "smallest cable tension over the static "
                                              "tension m·g (slack criterion, e.g. 0.1; "
                                              "none: not judged)"),
                    "tension_max": _num("N", "largest cable tension (none: no limit)")}},
    "actuators": {**{g: ACTUATOR for g in ACTUATOR_GROUPS}, "winch": WINCH},
}


def leaf_components(leaf: Leaf) -> list[tuple[str, ...]]:
    """Component suffixes of a leaf (``[()]`` for a scalar)."""
    if leaf.kind == "vec3":
        return [(c,) for c in XYZ]
    if leaf.kind == "inertia":
        return [(c,) for c in INERTIA_KEYS]
    if leaf.kind in ("numbers6", "numbers3"):
        return [(str(i),) for i in range(1, (6 if leaf.kind == "numbers6" else 3) + 1)]
    if leaf.kind == "points6":
        return [(str(i), c) for i in range(1, 7) for c in XYZ]
    return [()]


def field_names(table: dict = SCHEMA, prefix: str = "", per_leg: bool = False):
    """``[(dotted name, Leaf)]`` of every field of the format, in schema order.

    Args:
        per_leg: Also list the per-leg copies ``legs.1.*`` ... ``legs.6.*``.
    """
    out = []
    for key, sub in table.items():
        if not per_leg and prefix == "legs." and key in LEG_KEYS:
            continue
        name = prefix + key
        if isinstance(sub, Leaf):
            out.append((name, sub))
        else:
            out += field_names(sub, name + ".", per_leg)
    return out


def schema_lookup(name: str):
    """Locate a dotted name: ``(leaf path, Leaf or table, component tuple)``.

    Raises:
        KeyError: with a message naming the unknown part and the known ones.
    """
    parts = name.split(".")
    node, i = SCHEMA, 0
    while i < len(parts):
        if isinstance(node, Leaf):
            break
        key = parts[i]
        if key not in node:
            known = list(node)
            close = difflib.get_close_matches(key, known, n=1)
            hint = f"; did you mean '{'.'.join(parts[:i] + close)}'?" if close else ""
            where = ".".join(parts[:i]) or "the top level"
            raise KeyError(f"unknown field '{name}': {where} has no '{key}'{hint}")
        node = node[key]
        i += 1
    path, comp = ".".join(parts[:i]), tuple(parts[i:])
    if comp:
        valid = leaf_components(node) if isinstance(node, Leaf) else []
        if not any(v[:len(comp)] == comp for v in valid):
            raise KeyError(f"unknown field '{name}': {path} has no component "
                           f"'{'.'.join(comp)}'")
    return path, node, comp
