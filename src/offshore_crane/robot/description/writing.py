"""Writing a description file: the flat values a description resolves from (numbers,
expressions, text, as :class:`.values.Values` holds them) back as TOML that reads to the
same values.

Used to write a description a run derived from another (``identify --out``): the
nominal file's fields, expressions kept, with the derived ones replaced. The file's own
comments are not kept (TOML readers drop them); the caller gives a header and a comment
per field.
"""

from __future__ import annotations

from offshore_crane.errors import DescriptionError
from offshore_crane.io import toml_value
from offshore_crane.robot.description.schema import SCHEMA, Leaf, leaf_components


def description_text(raw: dict, comments: dict | None = None, header: str = "") -> str:
    """The TOML text of a description whose flat values are ``raw``.

    Args:
        raw: ``{dotted leaf name: value}`` (``platform.com.x``, ``legs.3.lower.mass``, ...):
            numbers, expressions (str), bools, text, as :attr:`.values.Values.raw`.
        comments: ``{dotted field name: text}`` written after the field's line
            (``platform.mass``, ``legs.3.lower.inertia``); a field name of a table
            (``legs.3.lower``) puts the text as comment lines above the table.
        header: Comment lines (without ``#``) at the top of the file.

    Returns:
        The file's text; reading it gives ``raw`` back (tested).

    Raises:
        DescriptionError: a vector given in part (one component overridden alone): the
            file could not hold it; a name the format does not know.
    """
    comments = comments or {}
    lines = [f"# {line}".rstrip() for line in header.splitlines()]
    used: set = set()
    body = _table(SCHEMA, "", raw, comments, used)
    unknown = sorted(set(raw) - used)
    if unknown:
        raise DescriptionError(f"description_text: {unknown[0]} is not a field of the "
                               "format (docs/robot-description.md)", field=unknown[0])
    return "\n".join(lines + ([""] if lines else []) + body).rstrip() + "\n"


def _table(schema: dict, prefix: str, raw: dict, comments: dict, used: set) -> list[str]:
    """Lines of the table ``prefix`` (its leaves, then its sub-tables)."""
    leaves, subs = [], []
    for key, node in schema.items():
        name = prefix + key
        if isinstance(node, Leaf):
            value = _leaf(name, node, raw, used)
            if value is not None:
                note = comments.get(name)
                leaves.append(f"{key} = {value}" + (f"    # {note}" if note else ""))
        else:
            subs += _table(node, name + ".", raw, comments, used)
    out = []
    if leaves and prefix:
        note = comments.get(prefix[:-1])
        out = [""] + ([f"# {line}".rstrip() for line in note.splitlines()] if note else [])
        out.append(f"[{prefix[:-1]}]")
    return out + leaves + subs


def _leaf(name: str, leaf: Leaf, raw: dict, used: set) -> str | None:
    """The TOML value of a leaf, None when not given."""
    comps = leaf_components(leaf)
    keys = [".".join((name,) + c) for c in comps]
    given = [k in raw for k in keys]
    if not any(given):
        return None
    if leaf.kind == "inertia":                       # omitted entries are 0: any subset
        used.update(k for k in keys if k in raw)
        return toml_value({c[0]: raw[k] for c, k in zip(comps, keys) if k in raw})
    if not all(given):
        missing = [k for k, g in zip(keys, given) if not g]
        raise DescriptionError(f"description_text: {name} is given in part ({missing[0]} "
                               f"missing): give the whole {leaf.kind}", field=name)
    used.update(keys)
    if comps == [()]:
        return toml_value(raw[name])
    if leaf.kind == "points6":
        return toml_value([[raw[f"{name}.{i}.{c}"] for c in "xyz"] for i in range(1, 7)])
    return toml_value([raw[k] for k in keys])
