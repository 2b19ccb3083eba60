"""Finding, reading and resolving description files (cached per file and overrides)."""

from __future__ import annotations

import hashlib
import os

from offshore_crane.robot.description.files import (default_description, label, read_description,
                                                    read_toml)
from offshore_crane.robot.description.resolver import Resolver
from offshore_crane.robot.description.results import Description
from offshore_crane.robot.description.schema import SCHEMA
from offshore_crane.robot.description.values import Values


# ===================================================================== resolution
def resolve(path=None, overrides: dict | None = None, content: bytes | None = None
            ) -> Description:
    """Read a description file, apply overrides, evaluate and check it.

    Args:
        path: The TOML file (default: the shipped ``lab.toml``).
        overrides: ``{dotted name: value}`` (canonical names, see
            :func:`offshore_crane.robot.overrides.canonical`); a value may be a number, an
            expression (str), a bool, a list or a table for a composite field.
        content: The file's bytes when already read (a pipe is read once).

    Raises:
        DescriptionError: the first problem, naming the file (or ``override``) and the
            field.
    """
    path = os.fspath(path) if path is not None else os.fspath(default_description())
    if content is None:
        content = read_description(path)
    try:
        key = (os.path.abspath(path), hashlib.sha256(content).digest(),
               frozen(overrides or {}))
    except TypeError:
        key = None                              # unhashable overrides: resolve names them
    if key is not None and key in _RESOLVED:
        return _RESOLVED[key]
    spec = resolve_data(read_toml(path, content), path, overrides)
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


def resolve_data(data: dict, path: str, overrides: dict | None = None) -> Description:
    """:func:`resolve` for an already parsed document ``data`` (``path`` for messages)."""
    return Resolver(flat_values(data, path, overrides), path, dict(overrides or {})).build()


def flat_values(data: dict, path: str, overrides: dict | None = None) -> Values:
    """The document ``data`` flattened to its leaves, checked against the format, with
    the overrides applied (not yet evaluated: expressions are kept).

    Raises:
        DescriptionError: an unknown key, a wrong type or shape (naming the field).
    """
    values = Values(label(path))
    values.add_table(data, SCHEMA, "", values.path)
    for name, value in (overrides or {}).items():
        values.override(name, value)
    for name, value in (overrides or {}).items():
        _shadowed(values, name, value)
    return values


def _shadowed(values: Values, name: str, value) -> None:
    """Refuse an override of a field for all legs (``legs.lower.mass``) that the file's
    per-leg tables (``[legs.N.lower]``) give for some legs: those take precedence, so the
    override would change nothing there, silently.

    Raises:
        DescriptionError: naming the legs and their own fields.
    """
    from offshore_crane.errors import DescriptionError
    from offshore_crane.io import toml_value
    from offshore_crane.robot.description.schema import LEG_KEYS

    parts = name.split(".")
    if parts[0] != "legs" or len(parts) < 2 or parts[1] in LEG_KEYS:
        return
    rest = ".".join(parts[1:])
    legs = [i for i in LEG_KEYS if any(
        values.origin.get(k) == values.path and (k == f"legs.{i}.{rest}" or k.startswith(
            f"legs.{i}.{rest}.")) for k in values.raw)]
    if legs:
        which = f"legs {legs[0]}-{legs[-1]}" if len(legs) == len(LEG_KEYS) else (
            "leg " if len(legs) == 1 else "legs ") + ", ".join(legs)
        raise DescriptionError(f"{values.path} with {name} = {toml_value(value)}: {which} "
                               f"have their own legs.N.{rest} (per-leg tables), which take "
                               f"precedence: set legs.{legs[0]}.{rest} (and each other leg's) "
                               "instead", path=values.path, field=name)
