"""One naming scheme and one validation path for every robot parameter override.

Every number of a robot description has a dotted name (``legs.lower.mass``,
``platform.inertia.ixx``, ``payload.com.z``, ``actuators.Fl.push_max``; see
:mod:`offshore_crane.robot.description`). The same names are used by

- the library: ``load_robot(overrides={"legs.lower.mass": 3.1})``;
- the command line: ``--set legs.lower.mass=3.1`` (:func:`parse_set`);
- scenes: ``[robot]`` tables (``legs.lower.mass = 3.1`` or ``"legs.lower.mass" = 3.1``),
  ``[payload]`` and ``[subsystems] arm`` (:mod:`offshore_crane.scenes`);
- sweep grids (a list of override dicts).

All of them go through :func:`normalise` (names, aliases, value types, finiteness,
magnitude) and then through the description's own checks
(:func:`offshore_crane.robot.description.resolve`), so an override is checked exactly as
the same value written in the file. :func:`conflicts` tells where a command-line override
contradicts a scene.

The flat names of earlier versions stay as aliases (:data:`ALIASES`):
``load_robot(platform_mass=55)`` is ``load_robot(overrides={"platform.mass": 55})``.
Their meaning is the dotted field's; in the shipped lab description the fields that
depended on a flat parameter are expressions of its field, so each alias changes the
robot exactly as the xacro argument of the same name did.

Values: numbers (int, float), expressions over other fields (str, e.g.
``"legs.lower.length / 2"``), booleans for ``arm.enabled`` (``true``/``false``/``1``/``0``
only), lists for vectors (``payload.com = [0, 0, -0.05]``), tables for composite fields.
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from functools import lru_cache

from offshore_crane.errors import DescriptionError, InputError
from offshore_crane.io import toml_value
from offshore_crane.robot.description import (MAGNITUDE_LIMIT, Leaf, as_boolean, leaf_components, field_names,
                          schema_lookup)
from offshore_crane.robot.expressions import ExpressionError, names as expression_names, shorten

#: Flat parameter names of earlier versions (the xacro arguments) -> dotted names.
ALIASES = {
    "base_radius": "base.joints.radius",
    "base_anchor_height": "base.joints.height",
    "base_half_angle_deg": "base.joints.half_angle_deg",
    "platform_radius": "platform.joints.radius",
    "platform_half_angle_deg": "platform.joints.half_angle_deg",
    "platform_plate_radius": "platform.shape.radius",
    "platform_thickness": "platform.shape.length",
    "platform_mass": "platform.mass",
    "home_height": "home.height",
    "leg_lower_length": "legs.lower.length",
    "leg_lower_radius": "legs.lower.radius",
    "leg_lower_mass": "legs.lower.mass",
    "leg_upper_length": "legs.upper.length",
    "leg_upper_radius": "legs.upper.radius",
    "leg_upper_mass": "legs.upper.mass",
    "leg_min_length": "legs.stroke.min",
    "leg_max_length": "legs.stroke.max",
    "ujoint_limit": "legs.ujoint.limit",
    "column_height": "arm.column.shape.length",
    "column_radius": "arm.column.shape.radius",
    "column_mass": "arm.column.mass",
    "link1_length": "arm.link1.shape.size.x",
    "link1_width": "arm.link1.shape.size.y",
    "link1_height": "arm.link1.shape.size.z",
    "link1_mass": "arm.link1.mass",
    "link2_length": "arm.link2.shape.size.x",
    "link2_width": "arm.link2.shape.size.y",
    "link2_height": "arm.link2.shape.size.z",
    "link2_mass": "arm.link2.mass",
    "slider_offset": "arm.slider.origin.x",
    "slider_length": "arm.slider.shape.size.x",
    "slider_width": "arm.slider.shape.size.y",
    "slider_mass": "arm.slider.mass",
    "arm_joint1_limit": "arm.link1.max",
    "arm_joint2_limit": "arm.link2.max",
    "arm_slide_limit": "arm.slider.max",
    "leg_force_limit": "actuators.Fl.push_max",
    "arm_torque_limit": "actuators.T1.push_max",
    "with_arm": "arm.enabled",
    "payload_mass": "payload.mass",
    "payload_x": "payload.com.x",
    "payload_y": "payload.com.y",
    "payload_z": "payload.com.z",
    **{f"payload_{k}": f"payload.inertia.{k}"
       for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")},
}


@dataclass(frozen=True)
class Conflict:
    """A field set to different values by a scene and by the command line.

    Attributes:
        field: Dotted name (the longer one when one contains the other).
        scene: The scene's value. cli: The command line's value.
    """

    field: str
    scene: object
    cli: object

    def __str__(self) -> str:
        return f"{self.field}: the scene sets {toml_value(self.scene)}, --set gives {toml_value(self.cli)}"


def _fail(source: str, name: str, message: str):
    raise DescriptionError(f"{source}: {message}", path=source, field=name)


def canonical(name: str, source: str = "override") -> str:
    """The dotted name of ``name`` (an alias or a dotted name), checked against the format.

    Raises:
        DescriptionError: an unknown name (the message suggests the closest names).
    """
    if not isinstance(name, str):
        _fail(source, str(name), f"robot parameter names are text, got {name!r}")
    if name in ALIASES:
        return ALIASES[name]
    try:
        schema_lookup(name)
    except KeyError as exc:
        detail = exc.args[0] if "." in name else f"unknown robot parameter '{name}'"
        known = list(ALIASES) + [n for n, _ in field_names()]
        close = difflib.get_close_matches(name, known, n=3)
        hint = (f"; did you mean {', '.join(close)}?"
                if close and "did you mean" not in detail else "")   # suggested once
        _fail(source, name, f"{detail}{hint} (all names: docs/robot-description.md)")
    return name


def _value(name: str, value, source: str, shown: str):
    """Check one override value; numbers written as text become floats."""
    _, node, comp = schema_lookup(name)
    if isinstance(node, Leaf) and node.kind == "bool":
        b = as_boolean(value)
        if b is None:
            _fail(source, name, f"robot parameter {shown}={value!r} must be true or false "
                  "(1 or 0)")
        return b
    if isinstance(value, bool):
        _fail(source, name, f"robot parameter {shown}={value!r} is not a number")
    if isinstance(value, (int, float)):
        if not math.isfinite(value) and not (value == math.inf
                                              and name.startswith("actuators.")):
            _fail(source, name, f"robot parameter {shown}={value!r} is not finite")
        if math.isfinite(value) and abs(value) > MAGNITUDE_LIMIT:
            _fail(source, name, f"robot parameter {shown}={value!r} exceeds the magnitude "
                  f"limit {MAGNITUDE_LIMIT:g} (products of such values overflow float64)")
        return value if isinstance(node, Leaf) and node.kind == "int" else float(value)
    if isinstance(value, str):
        if isinstance(node, Leaf) and node.kind in ("text", "choice"):
            return value
        try:
            number = float(value)
        except ValueError:
            number = None
        if number is not None:
            return _value(name, number, source, shown)
        try:
            refs = expression_names(value)
        except ExpressionError as exc:
            _fail(source, name, f"robot parameter {shown}: {exc}")
        for ref in refs:
            try:
                schema_lookup(ref)
            except KeyError:
                _fail(source, name, f"robot parameter {shown}={shorten(value)!r} is not a "
                      f"number, and as an expression it names '{ref}', which is no field")
        return value
    if isinstance(value, (list, tuple)):
        return [_value_item(name, v, source, shown) for v in value]
    if isinstance(value, dict):
        return {k: _value_item(name, v, source, shown) for k, v in value.items()}
    _fail(source, name, f"robot parameter {shown}={value!r} is not a number")


def _value_item(name, v, source, shown):
    """Elements of list or table values: finiteness and magnitude (shapes: the resolver)."""
    if isinstance(v, (list, tuple, dict)):
        return _value(name, v, source, shown)
    if isinstance(v, float) and (not math.isfinite(v) or abs(v) > MAGNITUDE_LIMIT) and not (
            v == math.inf and name.startswith("actuators.")):
        _fail(source, name, f"robot parameter {shown} holds {v!r}, not a finite number "
              f"within ±{MAGNITUDE_LIMIT:g}")
    return v


def normalise(overrides, source: str = "override") -> dict:
    """Check overrides and give them their dotted names.

    Args:
        overrides: ``{name: value}``, names dotted or aliases.
        source: Where they come from, for messages (``"--set"``, a scene file, ...).

    Returns:
        ``{dotted name: value}`` in the given order; numbers given as text are floats.

    Raises:
        DescriptionError: unknown name, a value that is no number/expression (or no
            boolean for ``arm.enabled``), not finite, beyond :data:`MAGNITUDE_LIMIT`, or two
            names (an alias and its dotted name) given different values.
    """
    if overrides is None:
        return {}
    if not isinstance(overrides, dict):
        raise InputError(f"robot overrides must be a dict {{name: value}}, got "
                         f"{type(overrides).__name__}", name="overrides")
    out, given_as = {}, {}
    for name, value in overrides.items():
        dotted = canonical(name, source)
        shown = name if name == dotted else f"{name} ({dotted})"
        v = _value(dotted, value, source, shown)
        if dotted in out and not _same(out[dotted], v):
            _fail(source, dotted, f"{given_as[dotted]} and {name} name the same field "
                  f"{dotted} with different values {out[dotted]!r} and {v!r}")
        out[dotted] = v
        given_as[dotted] = name
    return out


def parse_set(items, source: str = "--set") -> dict:
    """``["NAME=VALUE", ...]`` (the command line's ``--set``) -> checked overrides.

    VALUE is read as a TOML value when it is one (``3.1``, ``true``, ``[0, 0, -0.05]``,
    ``{ ixx = 1e-3, iyy = 1e-3, izz = 1e-3 }``), else as an expression (text).

    Raises:
        InputError: an item without ``=``.
        DescriptionError: as :func:`normalise`.
    """
    import tomllib

    raw = {}
    for item in items or ():
        name, sep, text = str(item).partition("=")
        name, text = name.strip(), text.strip()
        if not sep or not name:
            raise InputError(f"--set expects name=value, got '{item}'", name="--set")
        try:
            value = tomllib.loads(f"v = {text}")["v"]
        except tomllib.TOMLDecodeError:
            value = text
        if name in raw and not _same(raw[name], value):
            _fail(source, name, f"{name} is set twice, to {raw[name]!r} and {value!r}")
        raw[name] = value
    return normalise(raw, source)


def flatten_table(table: dict, source: str, prefix: str = "") -> dict:
    """A nested TOML table of overrides (``legs = { lower = { mass = 3 } }``, what TOML
    makes of ``legs.lower.mass = 3``) -> ``{"legs.lower.mass": 3}``; leaf values that are
    tables themselves (an inertia) stay whole.

    Raises:
        DescriptionError: one field spelled twice, as one quoted key
            (``"legs.lower.mass" = 3.1``) and as dotted keys (``legs.lower.mass = 3.2``):
            TOML keeps both, and one would silently win.
    """
    out: dict = {}
    spelled: dict = {}

    def put(name: str, value, spelling: str) -> None:
        if name in out:
            first, second = sorted((spelled[name], spelling))
            _fail(source, name, f"{name} is given twice, as {first} and as {second}: "
                  "give it once")
        out[name], spelled[name] = value, spelling

    for key, value in table.items():
        name = f"{prefix}{key}"
        spelling = f'"{key}" (a quoted key)' if "." in key else f"{name} (dotted keys)"
        if isinstance(value, dict) and not prefix and key in ALIASES:
            put(name, value, spelling)
            continue
        try:
            _, node, comp = schema_lookup(canonical(name, source))
        except DescriptionError:
            if isinstance(value, dict):                    # keep walking: maybe a.b.c
                for sub, v in flatten_table(value, source, name + ".").items():
                    put(sub, v, f"{sub} (dotted keys)")
                continue
            raise
        if isinstance(value, dict) and not isinstance(node, Leaf):
            for sub, v in flatten_table(value, source, name + ".").items():
                put(sub, v, f"{sub} (dotted keys)")
        else:
            put(name, value, spelling)
    return out


def _same(a, b) -> bool:
    if isinstance(a, bool) or isinstance(b, bool):
        return isinstance(a, bool) and isinstance(b, bool) and a == b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return float(a) == float(b)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    return a == b


def _part(value, suffix: list[str]):
    """The component ``suffix`` of a composite value, or a sentinel when absent."""
    for key in suffix:
        if isinstance(value, dict) and key in value:
            value = value[key]
        elif isinstance(value, (list, tuple)) and key in ("x", "y", "z") and len(value) == 3:
            value = value["xyz".index(key)]
        elif isinstance(value, (list, tuple)) and key.isdigit() and 1 <= int(key) <= len(value):
            value = value[int(key) - 1]
        else:
            return _ABSENT
    return value


_ABSENT = object()


def conflicts(scene_overrides: dict, cli_overrides: dict) -> list[Conflict]:
    """Fields that a scene and the command line both set, to different values.

    Args:
        scene_overrides, cli_overrides: Checked overrides (:func:`normalise`,
            :func:`parse_set`, a scene's ``robot``).

    Returns:
        One :class:`Conflict` per contradiction (empty: none). A field and one of its
        components (``payload.com`` and ``payload.com.z``) contradict each other when the
        component's values differ.
    """
    out = []
    for a, va in scene_overrides.items():
        for b, vb in cli_overrides.items():
            if a == b:
                same = _same(va, vb)
            elif b.startswith(a + "."):
                part = _part(va, b[len(a) + 1:].split("."))
                same = part is not _ABSENT and _same(part, vb)
            elif a.startswith(b + "."):
                part = _part(vb, a[len(b) + 1:].split("."))
                same = part is not _ABSENT and _same(va, part)
            else:
                continue
            if not same:
                out.append(Conflict(max(a, b, key=len), va, vb))
    return out


def legacy_parameters(values: dict, has_arm: bool) -> dict[str, str]:
    """``{alias: value as text}`` of a resolved description's numbers (the earlier xacro
    arguments), for the aliases whose field the description gives."""
    out = {}
    for alias, name in ALIASES.items():
        if alias == "with_arm":
            out[alias] = "1" if has_arm else "0"
        elif name in values:
            out[alias] = repr(float(values[name]))
    return out


def alias_table() -> list[tuple[str, str, str]]:
    """``[(alias, dotted name, unit)]`` for the documentation."""
    units = {}
    for name, leaf in field_names():
        for comp in leaf_components(leaf):
            units[".".join((name, *comp))] = leaf.unit
    return [(a, n, units.get(n, "")) for a, n in ALIASES.items()]


def xacro_arguments() -> dict[str, str]:
    """The flat parameter names of earlier versions (now aliases of dotted names,
    :data:`ALIASES`) and their values (as text) in the default description, in alias
    order (kept for callers of the former xacro arguments)."""
    return dict(_default_parameters())


@lru_cache(maxsize=1)
def _default_parameters() -> tuple:
    from offshore_crane.robot.description import resolve

    d = resolve()
    return tuple(legacy_parameters(d.values, d.has_arm).items())
