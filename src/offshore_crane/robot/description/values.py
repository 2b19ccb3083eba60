"""A description's values: the TOML document flattened to dotted leaves with their origin (file
or override), checked against the schema, and evaluated (numbers and expressions, in SI
units).
"""

from __future__ import annotations

import difflib
import math

import numpy as np

from offshore_crane.errors import DescriptionError
from offshore_crane.io import toml_value
from offshore_crane.robot.expressions import ExpressionError, evaluate
from offshore_crane.robot.description.schema import (INERTIA_KEYS, LEG_KEYS, Leaf,
                                                     MAGNITUDE_LIMIT, N_LEGS, XYZ,
                                                     leaf_components, schema_lookup)


# ======================================================================= flattening
class Values:
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
            sub = [c for c in leaf_components(leaf) if c[:len(comp)] == comp]
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
            value = as_boolean(value)
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


def as_boolean(value):
    """True/False for true/false, 1/0 (int, float or text); None otherwise."""
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)) and value in (0, 1):
        return bool(value)
    if isinstance(value, str) and value.strip().lower() in ("true", "false", "1", "0"):
        return value.strip().lower() in ("true", "1")
    return None


# ======================================================================= evaluation
class Numbers:
    """Numeric leaves evaluated on demand (expressions resolved, cycles detected)."""

    def __init__(self, values: Values):
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
                if isinstance(node, dict) or (leaf_components(node) != [()] and not comp):
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


def overlap(a: str, b: str) -> bool:
    return a == b or a.startswith(b + ".") or b.startswith(a + ".")
