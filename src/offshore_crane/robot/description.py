"""Robot description files: any 6-U-P-S platform with a crane arm, from its data.

A robot description is a TOML file holding every number of the robot: where the twelve
joints are, what each body weighs, where its centre of mass sits and its inertia tensor,
the strokes and joint limits, the actuators' capacities and the payload.
``models/descriptions/lab.toml`` (the placeholder lab design, the default) and
``models/descriptions/harib_srinivasan_2003.toml`` (a platform from the literature) are
the shipped examples; ``docs/robot-description.md`` is the user's guide. The robot's URDF
is still expanded from the one xacro ``models/offshore_crane.urdf.xacro``: this module
reads, checks and resolves the description, and the xacro reads the resolved numbers
(:meth:`Description.xacro_data`, written as YAML and loaded with ``xacro.load_yaml``).

Units are SI throughout (m, kg, kg·m², rad, N, N·m, m/s, rad/s, W); the only exception
is spelled in the key (``*_deg``: degrees). Frames (docs/conventions.md):

- **base**: fixed, z up; the URDF root. P_i, the U-joint centres, are in it.
- **platform**: origin O2, the platform's *reference point*, whose position in the base
  frame is (q1, q2, q3); axes turned by ``R_base_platform = Rz(q6) Ry(q5) Rx(q4)``. The
  S_i (sphere centres), the platform's centre of mass ``platform.com`` and the arm
  column's placement are in it. O2 is the centre of mass when ``platform.com`` is zero
  (the default, as in the paper); a description may put O2 anywhere, e.g. at the centre
  of the joint circle, and q1..q3 are then that point's position.
- **leg part frames**: the lower part's frame has its origin at P_i, the upper part's at
  S_i; both have z along the leg from P_i towards S_i and x along the U-joint's second
  axis a2 (``R_base_leg = R_base_U Ry(θ1) Rx(θ2)``, columns ``[a2, u × a2, u]``).
  A part's centre of mass and inertia are given in its frame.
- **arm frames**: ``arm_column`` is welded to the platform at ``arm.column.origin``
  (platform frame, rotated by ``arm.column.rpy``); each joint's origin and axis are in
  its parent body's frame (link1 in the column's, link2 in link1's, the slider in
  link2's); the tip frame ``arm_tip`` is placed in the slider's frame; the payload in
  the tip's.
- rpy angles follow URDF: ``R = Rz(yaw) Ry(pitch) Rx(roll)`` for ``rpy = [roll, pitch,
  yaw]`` [rad].
- Inertia tensors are about the body's centre of mass, in its frame's axes, as the six
  URDF numbers ``{ ixx, iyy, izz, ixy, ixz, iyz }`` [kg·m²] (products ``ixy = -∫xy dm``
  as in URDF; omitted products are 0).

Format (every key; ``*`` required)::

    format = 1                  # version of this format
    name = "lab"                # label (default: the file's stem)
    source = "..."              # free text: where the numbers come from

    [home]
    height = 0.5                # * q3 of the home pose [m]: O2's height with q1 = q2 =
                                # q4 = q5 = q6 = 0. The loops must close there (every leg
                                # inside its stroke) and the U-joints are oriented there.

    [base.joints]               # * the U-joint centres P_i, base frame [m], EITHER
    points = [[x, y, z], ...]   #   six points (leg 1 first), OR on a circle:
    radius = 0.6                #   radius [m],
    height = 0.05               #   height of the circle's plane [m],
    angles_deg = [...]          #   the six polar angles [deg], or pairs: legs 2k-1, 2k
    half_angle_deg = 15         #   at pair_angles_deg[k] -/+ half_angle_deg,
    pair_angles_deg = [0, 120, 240]      # (default [0, 120, 240])
    [base]
    ujoint_axes = [[x, y, z], ...]  # first U-joint axis a1 of each leg, base frame (unit
                                # length not required). Default: horizontal and
                                # perpendicular to the leg at home, so both U-joint angles
                                # are zero at home.
    ujoint_axes2 = [[...], ...] # second axis a2 at zero U-joint angles (perpendicular to
                                # a1); the leg direction at zero angles is a2 x a1.
                                # Default: the leg's home direction fixes it.
    shape = {...}               # the base's drawing (a shape table, below)

    [platform]
    mass = 40.0                 # * [kg]
    com = [0, 0, 0]             # centre of mass relative to O2, platform frame [m]
    inertia = { ixx = ..., iyy = ..., izz = ..., ixy = 0, ixz = 0, iyz = 0 }
                                # * about the CoM [kg·m²] (or derived from shape)
    shape = { type = "cylinder", radius = 0.4, length = 0.04, xyz = [0, 0, 0] }
    [platform.joints]           # * the sphere centres S_i, platform frame [m]: as
                                # [base.joints]; pairs: legs 2k, 2k+1 (leg 7 = leg 1) at
                                # pair_angles_deg[k] -/+ half_angle_deg, default
                                # [60, 180, 300]

    [legs.lower]                # * the lower part (cylinder, on the U-joint); frame: origin
                                # P_i, z along the leg
    mass = 2.0                  # * [kg]
    length = 0.42               # * extent from P_i along z [m]; the CoM must lie in 0..length
    radius = 0.035              # drawing radius [m]; without inertia: a solid cylinder
    com = [0, 0, 0.21]          # default (0, 0, length/2) [m]
    inertia = {...}             # about the CoM, part frame [kg·m²]
    [legs.upper]                # * the upper part (rod, on the sphere); frame: origin S_i,
                                # z along the leg; extent -length..0; CoM default
                                # (0, 0, -length/2)
    [legs.stroke]
    min = 0.40                  # * shortest |P_i S_i| [m]
    max = 0.82                  # * longest [m]
    [legs.ujoint]
    limit = 1.2                 # * |angle| limit of both U-joint axes [rad], 0 < limit <= pi/2
    [legs.3.lower]              # per-leg values: any key of lower, upper, stroke, ujoint
    mass = 2.1                  # for leg 3 only (the others keep [legs.lower])

    [arm]
    enabled = true              # false: the Stewart platform alone (alias with_arm).
                                # Without an [arm] table the robot has no arm.
    [arm.column]                # body 2, welded to the platform
    origin = [0, 0, 0.02]       # * in the platform frame [m]
    rpy = [0, 0, 0]             # [rad]
    mass, com, inertia, shape   # as the platform
    [arm.link1]                 # body 3 on arm_joint1 (revolute, q7); also link2 (body 4,
                                # arm_joint2, q8) and slider (body 5, arm_slide, prismatic, q9)
    origin = [0, 0, 0.33]       # * joint origin in the parent body's frame [m]
    rpy = [0, 0, 0]             # joint frame orientation [rad]
    axis = [0, 0, 1]            # joint axis in the joint frame (default z; slider x)
    min = -3.3                  # * lower joint limit [rad] (slider [m])
    max = 3.3                   # * upper joint limit
    mass, com, inertia, shape   # body in the joint frame
    [arm.tip]
    origin = [0.3, 0, 0]        # * frame arm_tip in the slider's frame [m]
    rpy = [0, 0, 0]

    [payload]                   # a rigid body welded to arm_tip (requires the arm)
    mass = 0.0                  # [kg], 0: no payload
    com = [0, 0, 0]             # its centre of mass in the arm_tip frame [m]
    inertia = {...}             # about its CoM [kg·m²]; omitted entries 0 (default: a
                                # point mass)
    cable_length = 0.0          # [m]; 0: welded. > 0 is read by the hanging-load model
                                # (issue 12); the URDF always welds the payload.

    [actuators.Fl]              # capacities of the six leg actuators (Fl1..Fl6 for one);
                                # also T1, T2 (arm motors [N·m], [rad/s]) and Fs (slider)
    push_max = 5000             # largest force along + (extension) [N] (torque [N·m])
    pull_max = 5000             # largest force along - [N] (magnitude)
    speed_max = 0.5             # largest |rate| [m/s] ([rad/s])
    power_max = 2000            # largest |force x rate| [W]; default: no limit
                                # (unlimited: inf, TOML's literal)

    shape = { type = "cylinder" | "box" | "sphere" | "none", radius = r, length = h,
              size = [a, b, c], xyz = [x, y, z] }
        A solid of uniform density centred at xyz (cylinder axis z, box edges along
        x, y, z): the body's drawing, and its inertia (with com = xyz) when the body
        gives no inertia. Default drawings are made from the dimensions.

Expressions: any number may be a string holding an arithmetic expression over other
fields (:mod:`offshore_crane.robot.expressions`), e.g. ``z = "-platform.shape.length / 2"``;
an override of a field moves every number computed from it.

Dotted names: every number has one (``legs.lower.mass``, ``platform.inertia.ixx``,
``payload.com.z``, ``base.joints.points.3.z``, ``actuators.Fl.push_max``); overrides
(``load_robot(overrides=...)``, ``--set NAME=VALUE``, a scene's ``[robot]`` table) use
them, and the flat names of earlier versions are aliases
(:mod:`offshore_crane.robot.overrides`).

Validation (:func:`resolve`, one path for the file and every override; errors are
:class:`~offshore_crane.errors.DescriptionError` naming the file and the field): unknown
keys, missing fields, wrong shapes and types, unit strings, non-finite numbers,
magnitudes above :data:`MAGNITUDE_LIMIT`; negative masses, inertias that no rigid body has
(not positive semi-definite, or breaking the triangle inequality, relative tolerance
:data:`INERTIA_RTOL`), a leg part's centre of mass outside the part; coincident or
collinear anchors; empty ranges; a home pose that does not close the loops (a leg outside
its stroke, a sphere centre below its U-joint, a U-joint outside its limits); U-joint
axes parallel to the leg; a singular leg arrangement at home.
"""

from __future__ import annotations

import difflib
import hashlib
import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from offshore_crane.conventions import INERTIA_RTOL
from offshore_crane.errors import DescriptionError
from offshore_crane.io import toml_value
from offshore_crane.robot.expressions import ExpressionError, evaluate

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
                                     "(hanging payload; 0: none)")},
    "actuators": {g: ACTUATOR for g in ACTUATOR_GROUPS},
}


def _components(leaf: Leaf) -> list[tuple[str, ...]]:
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
        valid = _components(node) if isinstance(node, Leaf) else []
        if not any(v[:len(comp)] == comp for v in valid):
            raise KeyError(f"unknown field '{name}': {path} has no component "
                           f"'{'.'.join(comp)}'")
    return path, node, comp


# ===================================================================== reading files
def description_dir() -> Path:
    """Folder of the shipped descriptions (inside the package, else the source tree)."""
    here = Path(__file__).resolve()
    for candidate in (here.parents[1] / "models" / DESCRIPTION_DIR,
                      here.parents[3] / "models" / DESCRIPTION_DIR):
        if candidate.is_dir():
            return candidate
    raise DescriptionError(f"cannot find the folder {DESCRIPTION_DIR}/ of the shipped robot "
                           "descriptions: reinstall offshore-crane")


def default_description() -> Path:
    """The shipped default description (the placeholder lab design)."""
    return description_dir() / DEFAULT_DESCRIPTION


def read_toml(path) -> dict:
    """Parse a description file.

    Raises:
        DescriptionError: unreadable file, not UTF-8, not TOML (naming the file).
    """
    import tomllib

    where = os.fspath(path)
    try:
        data = Path(where).read_bytes()
    except OSError as exc:
        raise DescriptionError(f"{where}: cannot read the robot description: "
                               f"{exc.strerror or exc}", path=where) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise DescriptionError(f"{where}: line {line}: not UTF-8 text (byte "
                               f"0x{data[exc.start]:02x}); save the file as UTF-8",
                               path=where) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DescriptionError(f"{where}: not valid TOML: {exc}", path=where) from None


# ======================================================================= flattening
class _Values:
    """The description as flat ``{dotted leaf name: raw value}`` with each leaf's origin.

    A raw value is a number (int/float), an expression (str) for numeric kinds, a bool
    or a str. Components of vectors and tables are separate leaves (``platform.com.x``).
    """

    def __init__(self, path: str):
        self.path = path
        self.raw: dict[str, object] = {}
        self.origin: dict[str, str] = {}

    def fail(self, name: str, message: str, origin: str | None = None):
        where = origin or self.origin.get(name) or self.path
        raise DescriptionError(f"{where}: {name}: {message}", path=where, field=name)

    # ------------------------------------------------------------- flatten a document
    def add_table(self, table, schema: dict, prefix: str, origin: str):
        name = prefix[:-1] if prefix else ""
        if not isinstance(table, dict):
            self.fail(name, f"{toml_value(table)} must be a table (keys "
                      f"{', '.join(schema)})", origin)
        for key, value in table.items():
            full = prefix + key
            if key not in schema:
                close = difflib.get_close_matches(key, list(schema), n=1)
                hint = f" (did you mean '{prefix}{close[0]}'?)" if close else ""
                known = [k for k in schema if k not in LEG_KEYS] + (
                    ["1 ... 6"] if prefix == "legs." else [])
                self.fail(full, f"unknown key{hint}; known keys here: {', '.join(known)}",
                          origin)
            sub = schema[key]
            if isinstance(sub, Leaf):
                self.add_leaf(full, sub, value, origin)
            else:
                self.add_table(value, sub, full + ".", origin)

    def add_leaf(self, name: str, leaf: Leaf, value, origin: str, comp: tuple = ()):
        """Store ``value`` for ``name`` (a leaf, or one of its components ``comp``)."""
        kind = leaf.kind
        if comp:
            sub = [c for c in _components(leaf) if c[:len(comp)] == comp]
            if sub == [comp]:
                self._scalar(f"{name}.{'.'.join(comp)}", leaf, value, origin)
            else:                                   # a point of points6
                self._vector(f"{name}.{'.'.join(comp)}", leaf, value, origin, 3, XYZ)
            return
        if kind in ("number", "int", "text", "choice", "bool"):
            self._scalar(name, leaf, value, origin)
        elif kind == "vec3":
            self._vector(name, leaf, value, origin, 3, XYZ)
        elif kind in ("numbers6", "numbers3"):
            n = 6 if kind == "numbers6" else 3
            self._vector(name, leaf, value, origin, n, [str(i) for i in range(1, n + 1)])
        elif kind == "points6":
            if not isinstance(value, list) or len(value) != N_LEGS:
                self.fail(name, f"{toml_value(value)} must be a list of 6 points [x, y, z] "
                          f"{_unit(leaf)}(leg 1 first)", origin)
            for i, point in enumerate(value, 1):
                self._vector(f"{name}.{i}", leaf, point, origin, 3, XYZ)
        elif kind == "inertia":
            if not isinstance(value, dict):
                self.fail(name, f"{toml_value(value)} must be a table {{ ixx = ..., iyy = ..., "
                          "izz = ..., ixy = ..., ixz = ..., iyz = ... }} [kg·m²]", origin)
            for key, v in value.items():
                if key not in INERTIA_KEYS:
                    self.fail(f"{name}.{key}", "unknown key; an inertia has "
                              f"{', '.join(INERTIA_KEYS)}", origin)
                self._scalar(f"{name}.{key}", leaf, v, origin)

    def _vector(self, name, leaf, value, origin, n, names):
        if not isinstance(value, list) or len(value) != n:
            self.fail(name, f"{toml_value(value)} must be a list of {n} numbers {_unit(leaf)}"
                      .rstrip(), origin)
        for c, v in zip(names, value):
            self._scalar(f"{name}.{c}", leaf, v, origin)

    def _scalar(self, name, leaf, value, origin):
        kind = leaf.kind
        if kind == "text":
            ok = isinstance(value, str)
            need = "text in quotes"
        elif kind == "choice":
            ok = value in leaf.choices
            need = f"one of {', '.join(map(repr, leaf.choices))}"
        elif kind == "int":
            ok = isinstance(value, int) and not isinstance(value, bool)
            need = "an integer"
        elif kind == "bool":
            value = _boolean(value)
            ok = value is not None
            need = "true or false (or 1 / 0)"
        else:
            ok = (isinstance(value, (int, float, str)) and not isinstance(value, bool))
            need = (f"a number {_unit(leaf)}".rstrip() + " or an expression in quotes")
        if not ok:
            self.fail(name, f"{toml_value(value)} must be {need}", origin)
        if isinstance(value, float) and not math.isfinite(value) and not (
                value == math.inf and name.startswith("actuators.")):
            self.fail(name, f"{toml_value(value)} is not a finite number", origin)
        self.raw[name] = value
        self.origin[name] = origin

    # ----------------------------------------------------------------- overrides
    def override(self, name: str, value, origin: str = "override"):
        """Replace a field (a leaf, a component or a whole table) by ``value``."""
        try:
            path, node, comp = schema_lookup(name)
        except KeyError as exc:
            raise DescriptionError(f"{origin}: {exc.args[0]}", path=origin,
                                   field=name) from None
        full = path + ("." + ".".join(comp) if comp else "")
        for key in [k for k in self.raw if k == full or k.startswith(full + ".")]:
            del self.raw[key]
            self.origin.pop(key, None)
        if isinstance(node, Leaf):
            self.add_leaf(path, node, value, origin, comp)
        else:
            self.add_table(value, node, path + ".", origin)

    # ----------------------------------------------------------------- queries
    def has(self, prefix: str) -> bool:
        return prefix in self.raw or any(k.startswith(prefix + ".") for k in self.raw)

    def overridden(self, *prefixes) -> list[str]:
        return [k for k in self.raw if self.origin.get(k) != self.path
                and any(k == p or k.startswith(p + ".") for p in prefixes)]


def _unit(leaf: Leaf) -> str:
    return f"[{leaf.unit}] " if leaf.unit else ""


def _boolean(value):
    """True/False for true/false, 1/0 (int, float or text); None otherwise."""
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)) and value in (0, 1):
        return bool(value)
    if isinstance(value, str) and value.strip().lower() in ("true", "false", "1", "0"):
        return value.strip().lower() in ("true", "1")
    return None


# ======================================================================= evaluation
class _Numbers:
    """Numeric leaves evaluated on demand (expressions resolved, cycles detected)."""

    def __init__(self, values: _Values):
        self.values = values
        self.cache: dict[str, float] = {}
        self.stack: list[str] = []
        self.deps: dict[str, set] = {}          # expression field -> fields it reads

    def __call__(self, name: str) -> float:
        if name in self.cache:
            return self.cache[name]
        v = self.values
        if name not in v.raw:
            raise KeyError(name)
        raw = v.raw[name]
        if isinstance(raw, bool) or not isinstance(raw, (int, float, str)):
            v.fail(name, f"{toml_value(raw)} is not a number")
        if name in self.stack:
            cycle = " -> ".join(self.stack[self.stack.index(name):] + [name])
            v.fail(name, f"expressions refer to each other in a cycle: {cycle}")
        if isinstance(raw, str):
            self.stack.append(name)
            try:
                value = evaluate(raw, self._reference(name))
            except ExpressionError as exc:
                v.fail(name, str(exc))
            finally:
                self.stack.pop()
        else:
            value = float(raw)
        if math.isfinite(value) and abs(value) > MAGNITUDE_LIMIT:
            v.fail(name, f"{value:.6g} exceeds the magnitude limit {MAGNITUDE_LIMIT:g} "
                   "(products of such values overflow float64 in the dynamics)")
        self.cache[name] = value
        return value

    def depends(self, names) -> set:
        """``names`` and every field their expressions read, transitively."""
        out, todo = set(), list(names)
        while todo:
            n = todo.pop()
            if n not in out:
                out.add(n)
                todo += self.deps.get(n, ())
        return out

    def _reference(self, owner: str):
        def lookup(name):
            self.deps.setdefault(owner, set()).add(name)
            try:
                return self(name)
            except KeyError:
                try:
                    _, node, comp = schema_lookup(name)
                except KeyError as exc:
                    raise ExpressionError(str(exc.args[0])) from None
                if isinstance(node, dict) or (_components(node) != [()] and not comp):
                    raise ExpressionError(f"'{name}' is not a number: name a component "
                                          "(.x, .ixx, .1, ...)") from None
                raise ExpressionError(f"refers to {name}, which the description does not "
                                      "give (an expression may use given fields only)"
                                      ) from None
        return lookup

    def get(self, name: str, default=None):
        """The number ``name``, or ``default`` when not given."""
        try:
            return self(name)
        except KeyError:
            return default

    def need(self, name: str, what: str) -> float:
        value = self.get(name)
        if value is None:
            self.values.fail(name, f"missing: give {what}", self.values.path)
        return value

    def vector(self, name: str, default=None):
        """``(3,)`` array, missing components from ``default`` (None: all required)."""
        out = []
        for k, c in enumerate(XYZ):
            x = self.get(f"{name}.{c}")
            if x is None:
                if default is None:
                    self.values.fail(name, f"missing: give [x, y, z]")
                x = float(default[k])
            out.append(x)
        return np.array(out)


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
        capacities: :class:`Capacities`.
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

    @property
    def has_arm(self) -> bool:
        """True when the crane arm is present."""
        return self.arm is not None

    def xacro_data(self) -> dict:
        """The numbers the xacro reads (plain lists and floats; see the xacro)."""
        return _xacro_data(self)


# ===================================================================== resolution
def resolve(path=None, overrides: dict | None = None) -> Description:
    """Read a description file, apply overrides, evaluate and check it.

    Args:
        path: The TOML file (default: the shipped ``lab.toml``).
        overrides: ``{dotted name: value}`` (canonical names, see
            :func:`offshore_crane.robot.overrides.canonical`); a value may be a number, an
            expression (str), a bool, a list or a table for a composite field.

    Raises:
        DescriptionError: the first problem, naming the file (or ``override``) and the
            field.
    """
    path = os.fspath(path) if path is not None else os.fspath(default_description())
    try:
        key = (os.path.abspath(path), hashlib.sha256(Path(path).read_bytes()).digest(),
               frozen(overrides or {}))
    except (OSError, TypeError):
        key = None                              # read_toml names the problem
    if key is not None and key in _RESOLVED:
        return _RESOLVED[key]
    spec = resolve_data(read_toml(path), path, overrides)
    if key is not None:
        _RESOLVED.setdefault(key, spec)
    return spec


#: Resolved descriptions by (file, its content's hash, overrides): a scene and the robot
#: it loads resolve the same description once (~15 ms each otherwise). Entries are never
#: mutated (the arrays of a Description are shared like the Robot that holds them).
_RESOLVED: dict = {}


def frozen(value):
    """A hashable image of an override value (dicts sorted, lists as tuples, each leaf
    tagged with its type so that 1 and 1.0 and True stay apart)."""
    if isinstance(value, dict):
        return tuple(sorted((k, frozen(v)) for k, v in value.items()))
    if isinstance(value, (list, tuple)):
        return tuple(frozen(v) for v in value)
    return (type(value).__name__, value)


def label(path: str) -> str:
    """How messages name a description file: as given, the default one by its name."""
    try:
        if Path(path).resolve() == default_description().resolve():
            return f"{Path(path).name} (the default description)"
    except DescriptionError:
        pass
    return path


def resolve_data(data: dict, path: str, overrides: dict | None = None) -> Description:
    """:func:`resolve` for an already parsed document ``data`` (``path`` for messages)."""
    values = _Values(label(path))
    values.add_table(data, SCHEMA, "", values.path)
    for name, value in (overrides or {}).items():
        values.override(name, value)
    return _Resolver(values, path, dict(overrides or {})).build()


def _overlap(a: str, b: str) -> bool:
    return a == b or a.startswith(b + ".") or b.startswith(a + ".")


class _Resolver:
    def __init__(self, values: _Values, path: str, overrides: dict):
        self.v = values
        self.n = _Numbers(values)
        self.path = path
        self.overrides = overrides

    def fail(self, name, message, *involved):
        """Error on field ``name``; the overrides that touch it or ``involved`` are shown."""
        fields = [k for k in self.v.raw if any(_overlap(k, p) for p in (name, *involved))]
        fields = self.n.depends(fields) | {name, *involved}
        over = [f"{k} = {toml_value(v)}" for k, v in self.overrides.items()
                if any(_overlap(k, p) for p in fields)]
        where = self.v.path + (f" with override {', '.join(over)}" if over else "")
        raise DescriptionError(f"{where}: {name}: {message}", path=self.path, field=name)

    # ------------------------------------------------------------------ build
    def build(self) -> Description:
        fmt = self.v.raw.get("format", FORMAT)
        if fmt != FORMAT:
            self.fail("format", f"{fmt} is not a known format version (this library reads "
                      f"format {FORMAT})")
        for name in list(self.v.raw):                    # every number, evaluated once
            if not isinstance(self.v.raw[name], bool) and not (
                    name in ("name", "source", "format") or name.endswith(".type")):
                self.n(name)
        h = self.n.need("home.height", "home.height = O2's height at the home pose [m]")
        P = self._anchors("base", "P")
        S = self._anchors("platform", "S")
        platform = self._body("platform", "platform")
        if not self.v.has("platform.shape"):              # drawn as a disc at the S_i
            platform = Body(platform.mass, platform.com, platform.inertia,
                            _disc(S, above=True))
        parts, lengths = self._parts()
        stroke = np.array([[self._leg_number(i, "stroke.min", "m"),
                            self._leg_number(i, "stroke.max", "m")] for i in range(N_LEGS)])
        ulim = np.array([self._leg_number(i, "ujoint.limit", "rad") for i in range(N_LEGS)])
        self._check_ranges(stroke, ulim)
        a1, R_U, rpy_U = self._ujoints(P, S, h)
        self._check_home(P, S, h, stroke, R_U, ulim)
        arm = self._arm()
        payload, cable, damping = self._payload(arm is not None)
        caps = self._capacities()
        return Description(
            name=self.v.raw.get("name", Path(self.path).stem), source=self.v.raw.get(
                "source", ""), path=self.path, overrides=self.overrides, home_height=h,
            p_base_P=P, p_platform_S=S, a1=a1, R_base_U=R_U, rpy_U=rpy_U, lower=tuple(p[0] for p in parts),
            upper=tuple(p[1] for p in parts), part_length=lengths, stroke=stroke,
            ujoint_limit=ulim, platform=platform, base_visual=self._base_visual(P),
            arm=arm, payload=payload, cable_length=cable, sway_damping=damping,
            capacities=caps, values=dict(self.n.cache))

    # ------------------------------------------------------------------ anchors
    def _anchors(self, side: str, letter: str) -> np.ndarray:
        pre = f"{side}.joints"
        points, circle = self.v.has(f"{pre}.points"), [
            k for k in ("radius", "height", "angles_deg", "half_angle_deg", "pair_angles_deg")
            if self.v.has(f"{pre}.{k}")]
        frame = "base" if side == "base" else "platform"
        if points and circle:
            self.fail(pre, f"give either points or the circle ({', '.join(circle)}), not "
                      "both")
        if points:
            X = np.array([self.n.vector(f"{pre}.points.{i}") for i in range(1, 7)])
        elif circle:
            r = self.n.need(f"{pre}.radius", "the circle's radius [m]")
            z = self.n.need(f"{pre}.height", "the circle's height [m]")
            th = self._angles(pre, side)
            X = np.array([[r * math.cos(t), r * math.sin(t), z] for t in th])
        else:
            self.fail(pre, f"missing: give the six {letter}_i ({frame} frame) as "
                      f"{pre}.points = [[x, y, z], ...] or on a circle ({pre}.radius, "
                      "height, angles_deg)")
        self._check_anchors(pre, X, letter)
        return X

    def _angles(self, pre: str, side: str) -> list[float]:
        if self.v.has(f"{pre}.angles_deg"):
            if self.v.has(f"{pre}.half_angle_deg"):
                self.fail(pre, "give either angles_deg or half_angle_deg (pairs), not both")
            return [math.radians(self.n.need(f"{pre}.angles_deg.{i}", "6 angles [deg]"))
                    for i in range(1, 7)]
        a = math.radians(self.n.need(f"{pre}.half_angle_deg",
                                     "angles_deg (6 angles) or half_angle_deg (pairs)"))
        default = (0.0, 120.0, 240.0) if side == "base" else (60.0, 180.0, 300.0)
        c = [self.n.get(f"{pre}.pair_angles_deg.{k}", default[k - 1]) for k in (1, 2, 3)]
        if side == "base":                    # legs 2k-1, 2k around c_k
            return [math.radians(c[k // 2]) + (a if k % 2 else -a) for k in range(6)]
        # platform: legs 2k, 2k+1 around c_k; leg 1 closes the third pair (c3 - 360°)
        th = [math.radians(c[2] - 360.0) + a]
        th += [math.radians(c[k // 2]) + (a if k % 2 else -a) for k in range(5)]
        return th

    def _check_anchors(self, name: str, X: np.ndarray, letter: str):
        centred = X - X.mean(axis=0)
        spread = float(np.abs(centred).max())
        for i in range(N_LEGS):
            for j in range(i + 1, N_LEGS):
                if np.linalg.norm(X[i] - X[j]) <= ANCHOR_RTOL * spread or spread == 0.0:
                    self.fail(name, f"{letter}{i + 1} and {letter}{j + 1} coincide at "
                              f"({', '.join(f'{x:.6g}' for x in X[i])}) m: give each leg "
                              "its own joint centre")
        sv = np.linalg.svd(centred, compute_uv=False)
        if sv[1] <= ANCHOR_RTOL * sv[0]:
            self.fail(name, f"the six {letter}_i lie on one line: the platform could turn "
                      "about it freely (a singular design)")

    # ------------------------------------------------------------------ bodies
    def _inertia(self, name: str, zero_default: bool = False) -> np.ndarray | None:
        """The inertia table ``name``; products default to 0, the moments too when
        ``zero_default`` (a point mass plus the moments given), else they are required."""
        if not self.v.has(name):
            return None
        ixx, iyy, izz = (self.n.get(f"{name}.{k}", 0.0) if zero_default else self.n.need(
            f"{name}.{k}", "ixx, iyy and izz [kg·m²]") for k in ("ixx", "iyy", "izz"))
        ixy, ixz, iyz = (self.n.get(f"{name}.{k}", 0.0) for k in ("ixy", "ixz", "iyz"))
        return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])

    def _shape(self, name: str) -> dict | None:
        if not self.v.has(name):
            return None
        kind = self.v.raw.get(f"{name}.type")
        if kind is None:
            self.fail(f"{name}.type", "missing: give type = \"cylinder\", \"box\", "
                      "\"sphere\" or \"none\"")
        shape = {"type": kind, "xyz": self.n.vector(f"{name}.xyz", (0.0, 0.0, 0.0))}
        need = {"cylinder": ("radius", "length"), "sphere": ("radius",), "box": ("size",),
                "none": ()}[kind]
        for key in ("radius", "length", "size"):
            given = self.v.has(f"{name}.{key}")
            if key in need and not given:
                self.fail(f"{name}.{key}", f"missing: a {kind} needs "
                          f"{' and '.join(need)} [m]")
            if given and key not in need:
                self.fail(f"{name}.{key}", f"does not apply to a {kind}")
            if given:
                value = (self.n.vector(f"{name}.size") if key == "size"
                         else self.n(f"{name}.{key}"))
                if np.any(np.asarray(value) < 0.0):
                    self.fail(f"{name}.{key}", f"{toml_value(np.asarray(value).tolist())} m "
                              "must not be negative")
                shape[key] = value
        return shape

    def _body(self, name: str, label: str, length_hint: float = 0.0) -> Body:
        m = self.n.need(f"{name}.mass", f"the mass of the {label} [kg]")
        if m < 0.0:
            self.fail(f"{name}.mass", f"{m:g} kg is negative; give a mass >= 0")
        shape = self._shape(f"{name}.shape")
        I = self._inertia(f"{name}.inertia")
        com_default = shape["xyz"] if shape is not None else (0.0, 0.0, 0.0)
        com = self.n.vector(f"{name}.com", com_default)
        if I is None:
            if shape is None or shape["type"] == "none":
                self.fail(f"{name}.inertia", f"missing: give the {label}'s inertia about "
                          "its centre of mass, or a shape (a solid of uniform density)")
            I = _solid_inertia(m, shape)
        self._check_inertia(f"{name}.inertia", m, I, f"{name}.mass", f"{name}.shape")
        visual = shape if shape is not None else {"type": "sphere", "radius": max(
            length_hint, 0.0) * ARM_DRAW_RATIO, "xyz": com}
        return Body(m, com, I, visual)

    def _check_inertia(self, name: str, m: float, I: np.ndarray, *involved):
        lam = np.linalg.eigvalsh(I)                           # ascending
        tol = INERTIA_RTOL * float(np.abs(lam).sum())
        shown = ", ".join(f"{x:.6g}" for x in lam)
        if lam[0] < -tol:
            self.fail(name, f"not positive definite: principal moments ({shown}) kg·m² "
                      "include a negative one; no body has them", *involved)
        if lam[2] > lam[0] + lam[1] + tol:
            self.fail(name, f"principal moments ({shown}) kg·m² break the triangle "
                      f"inequality ({lam[2]:.6g} > {lam[0]:.6g} + {lam[1]:.6g}); no rigid "
                      "body has them", *involved)
        if m == 0.0 and lam[2] > 0.0:
            self.fail(name, "an inertia without mass: give the mass too", *involved)

    def _leg_name(self, i: int, key: str) -> str:
        """``legs.{i+1}.key`` when given for that leg, else ``legs.key``."""
        own = f"legs.{i + 1}.{key}"
        return own if self.v.has(own) else f"legs.{key}"

    def _leg_number(self, i: int, key: str, unit: str) -> float:
        name = self._leg_name(i, key)
        return self.n.need(name, f"legs.{key} [{unit}] (for all legs, or legs.N.{key})")

    def _parts(self):
        parts, lengths = [], []
        for i in range(N_LEGS):
            pair = []
            for part, sign in (("lower", 1.0), ("upper", -1.0)):
                pair.append(self._part(i, part, sign))
            parts.append(tuple(b for b, _ in pair))
            lengths.append([L for _, L in pair])
        return parts, np.array(lengths)

    def _part(self, i: int, part: str, sign: float):
        key = lambda k: self._leg_name(i, f"{part}.{k}")            # noqa: E731
        label = f"leg {i + 1}'s {part} part"
        m = self.n.need(key("mass"), f"the mass of the {part} leg part [kg]")
        L = self.n.need(key("length"), f"the {part} part's length along the leg [m]")
        if m < 0.0:
            self.fail(key("mass"), f"{m:g} kg is negative; give a mass >= 0")
        if not L > 0.0:
            self.fail(key("length"), f"{L:g} m must be positive: links 'leg{{i}}_{part}' "
                      "would have zero length")
        r = self.n.get(key("radius"))
        if r is not None and r < 0.0:
            self.fail(key("radius"), f"{r:g} m must not be negative")
        default_com = (0.0, 0.0, sign * L / 2)
        com = np.array([self.n.get(self._leg_name(i, f"{part}.com.{c}"), default_com[k])
                        for k, c in enumerate(XYZ)])
        names = [self._leg_name(i, f"{part}.inertia.{k}") for k in INERTIA_KEYS]
        if any(self.v.has(n) for n in names):
            ixx, iyy, izz = (self.n.need(n, "ixx, iyy and izz [kg·m²]") for n in names[:3])
            ixy, ixz, iyz = (self.n.get(n, 0.0) for n in names[3:])
            I = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        elif r is None:
            self.fail(key("inertia"), f"missing: give the {part} part's inertia about its "
                      "centre of mass, or its radius (a solid cylinder)")
        else:
            I = _solid_inertia(m, {"type": "cylinder", "radius": r, "length": L})
        self._check_inertia(key("inertia"), m, I, key("mass"), key("radius"), key("length"))
        lo, hi = (0.0, L) if sign > 0 else (-L, 0.0)
        tol = COM_RTOL * L
        if not lo - tol <= com[2] <= hi + tol:
            self.fail(key("com"), f"z = {com[2]:.6g} m lies outside the {part} part "
                      f"({lo:g} to {hi:g} m along the leg from its joint): {label}",
                      key("length"))
        visual = {"type": "cylinder", "radius": r if r is not None else L * LEG_DRAW_RATIO,
                  "length": L, "xyz": np.array([0.0, 0.0, sign * L / 2])}
        return Body(m, com, I, visual), L

    def _check_ranges(self, stroke, ulim):
        for i in range(N_LEGS):
            lo, hi = stroke[i]
            name = self._leg_name(i, "stroke")
            if not lo < hi:
                self.fail(name, f"the stroke [{lo:g}, {hi:g}] m of leg {i + 1} is empty "
                          "(need min < max)")
            if not lo > 0.0:
                self.fail(name, f"min = {lo:g} m: a leg length must be positive")
            name = self._leg_name(i, "ujoint.limit")
            if not 0.0 < ulim[i] <= math.pi / 2:
                hint = (" (degrees given for radians?)" if ulim[i] > math.pi / 2 else "")
                self.fail(name, f"{ulim[i]:g} rad: need 0 < limit <= pi/2 (both U-joint "
                          f"axes turn within ±limit; at pi/2 the joint locks){hint}")

    # ------------------------------------------------------------------ U-joints
    def _axes(self, name: str):
        if not self.v.has(name):
            return None
        A = np.array([self.n.vector(f"{name}.{i}") for i in range(1, 7)])
        norm = np.linalg.norm(A, axis=1)
        for i in range(N_LEGS):
            if not norm[i] > 0.0:
                self.fail(f"{name}.{i + 1}", "a zero vector is no axis")
        return A / norm[:, None]

    def _ujoints(self, P, S, h):
        d = S + np.array([0.0, 0.0, h]) - P                  # S_i − P_i at home
        A1 = self._axes("base.ujoint_axes")
        A2 = self._axes("base.ujoint_axes2")
        a1s, Rs, rpys = [], [], []
        for i in range(N_LEGS):
            dx, dy, dz = (float(x) for x in d[i])
            if A1 is None and A2 is None:      # a1 horizontal, z at S_i: both angles 0
                rpy = np.array([0.0, math.atan2(math.sqrt(dx * dx + dy * dy), dz),
                                math.atan2(dy, dx)])
                R = _rpy_matrix(*rpy)
            elif A1 is None:
                self.fail("base.ujoint_axes2", "give ujoint_axes (a1) with ujoint_axes2")
            else:
                a1 = A1[i]
                u = d[i] / np.linalg.norm(d[i])
                kappa = 1.0 / max(math.sqrt(max(1.0 - float(a1 @ u) ** 2, 0.0)), 1e-300)
                if kappa >= GIMBAL_LIMIT:
                    self.fail(f"base.ujoint_axes.{i + 1}", f"a1 of leg {i + 1} is parallel "
                              "to the leg at the home pose (U-joint gimbal lock): turn it "
                              "across the leg")
                if A2 is None:
                    z = u - (u @ a1) * a1
                    z /= np.linalg.norm(z)
                    x = np.cross(a1, z)
                else:
                    x = A2[i]
                    if abs(float(x @ a1)) > ORTHOGONAL_TOL:
                        self.fail(f"base.ujoint_axes2.{i + 1}", f"a2 is not perpendicular "
                                  f"to a1 (cos = {float(x @ a1):.3g}) for leg {i + 1}")
                    x = x - (x @ a1) * a1
                    x /= np.linalg.norm(x)
                    z = np.cross(x, a1)
                R = np.column_stack([x, a1, z])
                rpy = _rpy(R)
                R = _rpy_matrix(*rpy)          # the frame the URDF will hold
            a1s.append(R[:, 1])
            Rs.append(R)
            rpys.append(rpy)
        return np.array(a1s), np.array(Rs), np.array(rpys)

    def _check_home(self, P, S, h, stroke, R_U, ulim):
        d = S + np.array([0.0, 0.0, h]) - P
        length = np.linalg.norm(d, axis=1)
        for i in range(N_LEGS):
            if d[i, 2] <= 0.0:
                self.fail("home.height", f"at the home pose sphere centre S{i + 1} is "
                          f"{-d[i, 2]:.4g} m below its U-joint (platform below the base)",
                          "base.joints", "platform.joints")
            lo, hi = stroke[i]
            if not lo <= length[i] <= hi:
                self.fail(self._leg_name(i, "stroke"), f"leg {i + 1} cannot reach the home "
                          f"pose: |P{i + 1}S{i + 1}| = {length[i]:.6g} m is outside the "
                          f"stroke [{lo:g}, {hi:g}] m", "home.height", "base.joints",
                          "platform.joints")
            u = R_U[i].T @ (d[i] / length[i])              # (c2 s1, −s2, c2 c1)
            th2 = -math.asin(max(-1.0, min(1.0, float(u[1]))))
            th1 = math.atan2(float(u[0]), float(u[2]))
            for k, th in ((1, th1), (2, th2)):
                if abs(th) > ulim[i]:
                    self.fail(self._leg_name(i, "ujoint.limit"), f"at the home pose the "
                              f"U-joint angle {k} of leg {i + 1} is {th:.4g} rad, outside "
                              f"±{ulim[i]:g} rad: orient the U-joint (base.ujoint_axes) or "
                              "widen the limit", "base.ujoint_axes", "base.ujoint_axes2")
        u = d / length[:, None]
        L = float(np.linalg.norm(S, axis=1).mean())
        A = np.concatenate([u.T, np.cross(S, u).T / L])
        with np.errstate(all="ignore"):
            kappa = float(np.linalg.cond(A, 1)) if np.all(np.isfinite(A)) else np.inf
        if not kappa < HOME_CONDITION_LIMIT:
            self.fail("platform.joints", f"the legs are singular at the home pose (Stewart "
                      f"matrix condition number {kappa:.3g}): move the anchors",
                      "base.joints", "home.height")

    # ------------------------------------------------------------------ arm
    def _arm(self):
        enabled = self.v.raw.get("arm.enabled", self.v.has("arm"))
        if not enabled:
            return None
        arm = {}
        col_origin = self.n.vector("arm.column.origin")
        col_rpy = self.n.vector("arm.column.rpy", (0.0, 0.0, 0.0))
        parents = ["column", *ARM_BODIES]
        origins = {}
        for body in ARM_BODIES:
            origins[body] = self.n.vector(f"arm.{body}.origin")
        tip_origin = self.n.vector("arm.tip.origin")
        tip_rpy = self.n.vector("arm.tip.rpy", (0.0, 0.0, 0.0))
        child_distance = {"column": float(np.linalg.norm(origins["link1"])),
                          "link1": float(np.linalg.norm(origins["link2"])),
                          "link2": float(np.linalg.norm(origins["slider"])),
                          "slider": float(np.linalg.norm(tip_origin))}
        arm["column"] = (col_origin, col_rpy, self._body("arm.column", "arm column",
                                                         child_distance["column"]))
        for k, body in enumerate(ARM_BODIES):
            pre = f"arm.{body}"
            prismatic = body == "slider"
            axis = self.n.vector(f"{pre}.axis", (1.0, 0.0, 0.0) if prismatic else
                                 (0.0, 0.0, 1.0))
            norm = float(np.linalg.norm(axis))
            if not norm > 0.0:
                self.fail(f"{pre}.axis", "a zero vector is no axis")
            lo = self.n.need(f"{pre}.min", f"the joint's lower limit [{'m' if prismatic else 'rad'}]")
            hi = self.n.need(f"{pre}.max", f"the joint's upper limit [{'m' if prismatic else 'rad'}]")
            if not lo < hi:
                self.fail(f"{pre}.min", f"the range [{lo:g}, {hi:g}] is empty (need min < "
                          "max)", f"{pre}.max")
            if not prismatic and max(abs(lo), abs(hi)) > REVOLUTE_LIMIT:
                self.fail(f"{pre}.max", f"[{lo:g}, {hi:g}] rad spans more than two turns "
                          "(degrees given for radians?)", f"{pre}.min")
            arm[body] = ArmJoint(origins[body], self.n.vector(f"{pre}.rpy", (0.0, 0.0, 0.0)),
                                 axis / norm, lo, hi, prismatic,
                                 self._body(pre, f"arm {body}", child_distance[body]))
        self._check_coaxial(arm)
        arm["tip"] = (tip_origin, tip_rpy)
        return arm

    def _check_coaxial(self, arm):
        for parent, child in (("link1", "link2"),):
            pj, cj = arm[parent], arm[child]
            axis = _rpy_matrix(*cj.rpy) @ cj.axis            # in the parent body frame
            if (abs(abs(float(axis @ pj.axis)) - 1.0) < 1e-12
                    and np.linalg.norm(np.cross(cj.origin, pj.axis)) <= 1e-12):
                self.fail(f"arm.{child}.origin", f"arm_joint2 lies on arm_joint1's axis: "
                          f"link 'arm_{parent}' would have zero length")

    # ------------------------------------------------------------------ payload
    def _payload(self, has_arm: bool):
        m = self.n.get("payload.mass", 0.0)
        if m < 0.0:
            self.fail("payload.mass", f"{m:g} kg is negative; give a mass >= 0")
        if m > 0.0 and not has_arm:
            self.fail("payload.mass", f"{m:g} kg: the payload hangs from the arm tip, but "
                      "the robot has no arm (arm.enabled = false)", "arm.enabled")
        com = self.n.vector("payload.com", (0.0, 0.0, 0.0))
        I = self._inertia("payload.inertia", zero_default=True)
        I = np.zeros((3, 3)) if I is None else I
        self._check_inertia("payload.inertia", m, I, "payload.mass")
        cable = self.n.get("payload.cable_length", 0.0)
        if cable < 0.0:
            self.fail("payload.cable_length", f"{cable:g} m must not be negative (0: the "
                      "payload welded to arm_tip; > 0: hanging on a cable of that length)")
        damping = self.n.get("payload.sway_damping", 0.0)
        if not damping >= 0.0:
            self.fail("payload.sway_damping", f"{damping:g} N·m·s/rad must not be negative")
        if damping > 0.0 and not cable > 0.0:
            self.fail("payload.sway_damping", f"{damping:g} N·m·s/rad damps the swing of a "
                      "payload on a cable, but payload.cable_length = 0 (welded)",
                      "payload.cable_length")
        if cable > 0.0:
            if not m > 0.0:
                self.fail("payload.cable_length", f"{cable:g} m: a cable needs a payload to "
                          "hang from it: give payload.mass > 0, or cable_length = 0",
                          "payload.mass")
            if np.any(com != 0.0) or np.any(I != 0.0):
                self.fail("payload.com" if np.any(com != 0.0) else "payload.inertia",
                          "with a cable (payload.cable_length > 0) the payload is a point "
                          "mass at the cable's end: set payload.com = [0, 0, 0] and "
                          "payload.inertia to zero (the cable length is measured to the "
                          "centre of mass)", "payload.cable_length")
        return Body(m, com, I, {"type": "none"}), cable, damping

    # ------------------------------------------------------------------ actuators
    def _capacities(self) -> Capacities:
        cols = {k: [] for k in ACTUATOR}
        for name in ACTUATORS:
            group = "Fl" if name.startswith("Fl") else name
            for key in ACTUATOR:
                own, common = f"actuators.{name}.{key}", f"actuators.{group}.{key}"
                field_ = own if self.v.has(own) else common
                x = self.n.get(field_, math.inf)
                positive = key in ("speed_max", "power_max")
                if x < 0.0 or (positive and x == 0.0):
                    self.fail(field_, f"{x:g} must be {'> 0' if positive else '>= 0'}")
                cols[key].append(x)
        return Capacities(ACTUATORS, *(np.array(cols[k]) for k in ACTUATOR))

    def _base_visual(self, P):
        shape = self._shape("base.shape")
        return shape if shape is not None else _disc(P, above=False)


def _disc(X: np.ndarray, above: bool) -> dict:
    """Default drawing: a disc just beyond the anchors ``X``, above or below them."""
    r = DISC_MARGIN * float(np.linalg.norm(X[:, :2], axis=1).max())
    t = DISC_THICKNESS * r
    z = float(X[:, 2].max()) + t / 2 if above else float(X[:, 2].min()) - t / 2
    return {"type": "cylinder", "radius": r, "length": t, "xyz": np.array([0.0, 0.0, z])}


# ==================================================================== small helpers
def _solid_inertia(m: float, shape: dict) -> np.ndarray:
    """Central inertia of a solid of uniform density (same arithmetic as the xacro had)."""
    kind = shape["type"]
    if kind == "cylinder":
        r, h = shape["radius"], shape["length"]
        t = m * (3 * r * r + h * h) / 12
        return np.diag([t, t, m * r * r / 2])
    if kind == "box":
        a, b, c = shape["size"]
        return np.diag([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                        m * (a * a + b * b) / 12])
    r = shape["radius"]
    return np.eye(3) * (2.0 * m * r * r / 5.0)


def _rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``Rz(yaw) Ry(pitch) Rx(roll)`` (URDF)."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch),
                              math.sin(pitch), math.cos(yaw), math.sin(yaw))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _rpy(R: np.ndarray) -> np.ndarray:
    """URDF rpy of a rotation matrix; for ``Rz(y) Ry(p)`` (roll 0, the historical U-joint
    frames) it returns the angles that built it up to round-off."""
    pitch = math.atan2(-R[2, 0], math.hypot(R[0, 0], R[1, 0]))
    if math.hypot(R[0, 0], R[1, 0]) < 1e-12:                 # pitch = ±pi/2
        return np.array([0.0, pitch, math.atan2(-R[0, 1], R[1, 1])])
    return np.array([math.atan2(R[2, 1], R[2, 2]), pitch, math.atan2(R[1, 0], R[0, 0])])


def _floats(x) -> list:
    return [float(v) for v in np.asarray(x, dtype=float).ravel()]


def _inertia6(I) -> list:
    return [float(I[0, 0]), float(I[1, 1]), float(I[2, 2]), float(I[0, 1]), float(I[0, 2]),
            float(I[1, 2])]


def _visual(v: dict) -> dict:
    out = {"type": v["type"]}
    for key in ("radius", "length"):
        if key in v:
            out[key] = float(v[key])
    if "size" in v:
        out["size"] = _floats(v["size"])
    out["xyz"] = _floats(v.get("xyz", (0.0, 0.0, 0.0)))
    return out


def _body_data(b: Body) -> dict:
    return {"mass": float(b.mass), "com": _floats(b.com), "inertia": _inertia6(b.inertia),
            "visual": _visual(b.visual)}


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
            "i": i + 1, "P": _floats(d.p_base_P[i]), "rpy": _floats(d.rpy_U[i]),
            "S": _floats(d.p_platform_S[i]), "ulim": float(d.ujoint_limit[i]),
            "stroke": _floats(d.stroke[i]), "effort": float(effort[3 + i]),
            "velocity": float(speed[3 + i]), "lower": _body_data(d.lower[i]),
            "upper": _body_data(d.upper[i])})
    data = {"format": FORMAT, "name": d.name, "base": {"visual": _visual(d.base_visual)},
            "platform": _body_data(d.platform), "legs": legs, "arm": None,
            "payload": {"mass": float(d.payload.mass), "com": _floats(d.payload.com),
                        "inertia": _inertia6(d.payload.inertia),
                        "cable_length": float(d.cable_length),
                        "sway_damping": float(d.sway_damping)}}
    if d.arm is not None:
        origin, rpy, column = d.arm["column"]
        arm = {"column": {"origin": _floats(origin), "rpy": _floats(rpy),
                          **_body_data(column)}}
        for k, body in enumerate(ARM_BODIES):
            j = d.arm[body]
            arm[body] = {"origin": _floats(j.origin), "rpy": _floats(j.rpy),
                         "axis": _floats(j.axis), "lower": float(j.lower),
                         "upper": float(j.upper), "effort": float(effort[k]),
                         "velocity": float(speed[k]), **_body_data(j.body)}
        tip_origin, tip_rpy = d.arm["tip"]
        arm["tip"] = {"origin": _floats(tip_origin), "rpy": _floats(tip_rpy)}
        data["arm"] = arm
    return data
