"""A design's space file: its variables (description fields and their bounds or choices),
its objectives and constraints (verdict columns or expressions of description fields) and
its sea states, checked against the scene before anything runs.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

from offshore_crane.errors import SpaceError
from offshore_crane.io import toml_value
from offshore_crane.validation import not_a_number

#: The tables a space file may hold.
TABLES = ("variables", "objectives", "constraints", "sea")
#: The comparisons a constraint may make.
OPERATORS = ("<=", ">=")
#: The constraint every design meets unless the space constrains it itself: every
#: actuator within its capacities (``worst_util``: the worst utilisation over actuators
#: and capacities, 1 = 100 %).
DEFAULT_CONSTRAINT = ("worst_util", "<=", 1.0)


@dataclass(frozen=True)
class Variable:
    """A design variable: a robot description field by its dotted name.

    Attributes:
        name: The canonical dotted name (``arm.link1.shape.size.x``).
        low, high: Continuous bounds (``choices`` None), ``low < high``.
        choices: A tuple of the values it may take, or None (continuous).
    """

    name: str
    low: float
    high: float
    choices: tuple | None = None

    def decode(self, x: float) -> float:
        """The field's value of the optimiser's number ``x``: itself for a continuous
        variable, the choice of index ``floor(x)`` (``x`` in ``[0, n)``) for a list."""
        if self.choices is None:
            return float(x)
        return self.choices[min(max(int(math.floor(x)), 0), len(self.choices) - 1)]

    @property
    def bounds(self) -> tuple[float, float]:
        """The optimiser's bounds of ``x`` (:meth:`decode`)."""
        return (self.low, self.high) if self.choices is None else (0.0,
                                                                   float(len(self.choices)))


@dataclass(frozen=True)
class Quantity:
    """What an objective or a constraint judges: a verdict column (``kind = "column"``,
    :func:`offshore_crane.studies.sweep.verdict_quantities`: over several sea states the
    largest, the smallest of a ``*_min`` column) or an expression of description fields
    in the description's expression language (``kind = "expression"``)."""

    text: str
    kind: str

    @property
    def smallest(self) -> bool:
        """A column whose worst over sea states is its smallest (``tension_ratio_min``)."""
        return self.kind == "column" and self.text.endswith("_min")


@dataclass(frozen=True)
class Objective:
    quantity: Quantity
    sense: str              # "minimise" or "maximise"


@dataclass(frozen=True)
class Constraint:
    quantity: Quantity
    op: str                 # "<=" or ">="
    bound: float

    def violation(self, value: float) -> float:
        """How far ``value`` is beyond the bound (0 when it meets it, inf when NaN)."""
        if math.isnan(value):
            return math.inf
        return max(0.0, value - self.bound if self.op == "<=" else self.bound - value)

    def describe(self) -> str:
        return f"{self.quantity.text} {self.op} {self.bound:g}"


@dataclass(frozen=True)
class Space:
    """A checked design space (:func:`check_space`).

    Attributes:
        variables: Tuple of :class:`Variable`.
        objectives: Tuple of :class:`Objective` in the file's order (minimise first).
        constraints: Tuple of :class:`Constraint` (with :data:`DEFAULT_CONSTRAINT` unless
            the file constrains ``worst_util`` or ``overall_util`` from above).
        sea: The sea cases every candidate runs (``{sea key: value}`` dicts: the
            product of ``[sea]``'s lists, seeds fastest), ``({},)`` for a scene without
            a sea.
        where: The space file (or ``"space"``).
    """

    variables: tuple
    objectives: tuple
    constraints: tuple
    sea: tuple
    where: str = "space"

    @property
    def names(self) -> tuple:
        return tuple(v.name for v in self.variables)

    def quantities(self) -> tuple:
        """Every quantity judged, each once: objectives first, then constraints."""
        out = [o.quantity for o in self.objectives] + [c.quantity for c in self.constraints]
        return tuple(dict.fromkeys(out))


def load_space(path) -> dict:
    """Read a space file (TOML) as a dict (checked by :func:`check_space`).

    Raises:
        SpaceError: unreadable file, invalid TOML.
    """
    from offshore_crane.errors import InputError
    from offshore_crane.io import read_toml

    where = os.fspath(path)
    try:
        return read_toml(where, "space file")
    except InputError as exc:
        raise SpaceError(str(exc), path=where) from None


def _flat(table: dict, stop) -> dict:
    """TOML's dotted keys joined (``arm.link1.x = ...`` as ``"arm.link1.x" = ...``), down
    to the tables ``stop(value)`` says are values."""
    out = {}
    for key, value in table.items():
        if isinstance(value, dict) and not stop(value):
            out.update({f"{key}.{k}": v for k, v in _flat(value, stop).items()})
        else:
            out[key] = value
    return out


def check_space(scene, data: dict, where: str = "space") -> Space:
    """Check a space against the scene, before anything runs.

    Args:
        scene: The :class:`~offshore_crane.scenes.Scene` every candidate runs.
        data: The space (:func:`load_space`, or a dict of the same tables).
        where: The space's name in messages (its file).

    Raises:
        SpaceError: an empty space or one without variables or objectives, an unknown
            table or key, a variable that is not a description field or that the scene
            sets itself, bounds that are not two increasing finite numbers or that the
            description refuses (each bound and each choice resolved alone), a
            quantity naming no verdict column and no description field (a constraint's
            pattern matching none), a constraint that is not ``{ "<=" = x }`` or
            ``{ ">=" = x }``.
        GridError: a ``[sea]`` list the scene's own checks refuse.
    """
    def fail(message: str, key: str | None = None):
        raise SpaceError(f"{where}: {message}", path=None if where == "space" else where,
                         key=key)

    if not isinstance(data, dict) or not any(data.get(t) for t in TABLES):
        fail("the space is empty: give [variables] (description fields and their bounds) "
             "and [objectives] (minimise = [...], maximise = [...])")
    unknown = [k for k in data if k not in TABLES]
    if unknown:
        fail(f"unknown table [{unknown[0]}]: a space holds {', '.join(TABLES)}", unknown[0])
    variables = _variables(scene, data.get("variables") or {}, fail, where)
    known = _description_values(scene, {})
    objectives = _objectives(data.get("objectives"), known, fail)
    constraints = _constraints(data.get("constraints") or {}, known, fail)
    return Space(variables, objectives, constraints, _sea(scene, data.get("sea"), where),
                 where)


def _description_values(scene, robot: dict) -> dict:
    """The numbers of the scene's robot with ``robot``'s fields over its own."""
    from offshore_crane.robot.description import resolve

    return resolve(scene.robot_description, {**scene.robot, **robot}).values


def _variables(scene, table, fail, where: str) -> tuple:
    from offshore_crane.errors import DescriptionError
    from offshore_crane.robot.overrides import normalise

    if not isinstance(table, dict) or not table:
        fail("[variables] is empty: name at least one description field and its bounds, "
             'e.g. "arm.link1.shape.size.x" = [0.3, 0.7]', "variables")
    out = []
    for key, raw in _flat(table, lambda v: "choices" in v).items():
        shown = f"[variables] {key} = {toml_value(raw)}"
        try:
            name = next(iter(normalise({key: 0.0}, where)))
        except DescriptionError as exc:
            fail(f"{shown}: not a field of the robot description ({exc})", key)
        if name in scene.robot:
            fail(f"{shown}: the scene sets {name} itself ({toml_value(scene.robot[name])}):"
                 " remove it from the scene or from the space", key)
        if name in (v.name for v in out):
            fail(f"{shown}: names {name} a second time", key)
        variable = _variable(name, raw, shown, key, fail)
        for label, value in _ends(variable):
            problem = not_a_number(value)
            if problem:
                fail(f"{shown}: the {label} {toml_value(value)} {problem}", key)
            try:
                _description_values(scene, {name: value})
            except DescriptionError as exc:
                fail(f"{shown}: the {label} {value:g} is refused by the description: "
                     f"{exc}", key)
        out.append(variable)
    return tuple(out)


def _variable(name, raw, shown, key, fail) -> Variable:
    if isinstance(raw, dict):
        if set(raw) != {"choices"} or not isinstance(raw["choices"], list) or not raw[
                "choices"]:
            fail(f"{shown}: a list of choices is {{ choices = [a, b, ...] }} (a non-empty "
                 "list of numbers)", key)
        choices = raw["choices"]
        for c in choices:
            problem = not_a_number(c)
            if problem:
                fail(f"{shown}: the choice {toml_value(c)} {problem}", key)
        values = tuple(float(c) for c in choices)
        if len(set(values)) != len(values):
            fail(f"{shown}: names a choice twice", key)
        return Variable(name, min(values), max(values), values)
    if not isinstance(raw, list) or len(raw) != 2:
        fail(f"{shown}: give the bounds as [low, high], or a list of choices as "
             "{ choices = [a, b, ...] }", key)
    for x in raw:
        problem = not_a_number(x)
        if problem:
            fail(f"{shown}: the bound {toml_value(x)} {problem}: give finite numbers", key)
    low, high = float(raw[0]), float(raw[1])
    if not low < high:
        fail(f"{shown}: the bounds are reversed or equal (low {low:g} ≥ high {high:g}): "
             "give [low, high] with low < high", key)
    return Variable(name, low, high)


def _ends(v: Variable):
    if v.choices is not None:
        return [(f"choice {i + 1}", c) for i, c in enumerate(v.choices)]
    return [("lower bound", v.low), ("upper bound", v.high)]


def quantity(text, known: dict, what: str, fail) -> Quantity:
    """A :class:`Quantity` of ``text``: a verdict column, else an expression whose every
    name is a field of the description (``known``: its resolved values).

    Raises:
        SpaceError (through ``fail``): neither.
    """
    from offshore_crane.robot.expressions import ExpressionError, evaluate
    from offshore_crane.studies.sweep import verdict_quantities

    if not isinstance(text, str) or not text.strip():
        fail(f"{what} = {toml_value(text)}: give a verdict column (e.g. worst_util) or an "
             "expression of description fields, as text", what)
    columns = verdict_quantities()
    if text in columns:
        return Quantity(text, "column")

    def lookup(name):
        if name not in known:
            raise ExpressionError(f"{name!r} is no description field")
        return known[name]

    try:
        evaluate(text, lookup)
    except ExpressionError as exc:
        fail(f"{what} {text!r} names no verdict column ({', '.join(columns[:2])}, "
             f"T1_util_push, ..., worst_util, load_util, overall_util) and is no "
             f"expression of description fields ({exc})", text)
    return Quantity(text, "expression")


def _objectives(table, known: dict, fail) -> tuple:
    if not isinstance(table, dict) or not any(table.get(k) for k in ("minimise",
                                                                     "maximise")):
        fail("[objectives] is empty: give minimise = [...] and/or maximise = [...] (verdict "
             "columns or expressions of description fields)", "objectives")
    out = []
    for key, texts in table.items():
        if key not in ("minimise", "maximise"):
            fail(f"[objectives] {key}: unknown key (minimise, maximise)", key)
        if not isinstance(texts, list):
            fail(f"[objectives] {key} = {toml_value(texts)}: must be a list, e.g. {key} = "
                 f"[{toml_value(texts)}]", key)
        for text in texts:
            q = quantity(text, known, f"[objectives] {key}", fail)
            if q in (o.quantity for o in out):
                fail(f"[objectives] {text!r} is named twice", text)
            out.append(Objective(q, key))
    return tuple(out)


def _constraints(table, known: dict, fail) -> tuple:
    out = []
    def rule_table(v: dict) -> bool:            # a bound's table, not a dotted name's
        return any(not (k.isidentifier() or k.isdigit()) for k in v) or not v

    for key, rule in _flat(table, rule_table).items():
        shown = f"[constraints] {key} = {toml_value(rule)}"
        if not isinstance(rule, dict) or not rule:
            fail(f"{shown}: give a bound as {{ \"<=\" = x }} or {{ \">=\" = x }}", key)
        if set(rule) - set(OPERATORS):
            fail(f"{shown}: give a bound as {{ \"<=\" = x }} or {{ \">=\" = x }}", key)
        for op, bound in rule.items():
            problem = not_a_number(bound)
            if problem:
                fail(f"{shown}: the bound {toml_value(bound)} {problem}", key)
            out += [Constraint(q, op, float(bound)) for q in _matching(key, known, fail)]
    if not any(c.quantity.text in ("worst_util", "overall_util") and c.op == "<="
               for c in out):
        name, op, bound = DEFAULT_CONSTRAINT
        out.append(Constraint(Quantity(name, "column"), op, bound))
    return tuple(out)


def _matching(key: str, known: dict, fail) -> list:
    """The quantities a constraint's key names: one, or with ``*``, ``?`` or ``[...]``
    every verdict column it matches (``"Fl?_util_pu*"``: each leg's push and pull)."""
    import fnmatch

    from offshore_crane.studies.sweep import verdict_quantities

    if not any(c in key for c in "*?["):
        return [quantity(key, known, "[constraints]", fail)]
    names = fnmatch.filter(verdict_quantities(), key)
    if not names:
        fail(f"[constraints] {key!r} matches no verdict column (e.g. \"Fl?_util_pu*\": "
             "each leg's push and pull utilisations)", key)
    return [Quantity(n, "column") for n in names]


def _sea(scene, table, where: str) -> tuple:
    """The sea cases of every candidate: ``[sea]``'s product (checked as a sweep grid by
    the scene's own checks); its seeds, when it gives none, those ``size`` runs (the
    scene's ``[extremes] seeds`` from its ``[sea] seed``)."""
    from offshore_crane.scenes.exposure import extremes_option
    from offshore_crane.studies.sweep import SEA_KEYS, check_grid

    sea = scene.trajectory == "sea"
    table = dict(table or {})
    other = [k for k in table if k not in SEA_KEYS]
    if other:
        raise SpaceError(f"{where}: [sea] {other[0]}: unknown key: [sea] lists sea states "
                         f"({', '.join(SEA_KEYS)}); robot fields are [variables]",
                         path=where, key=other[0])
    if not sea:
        if table:
            check_grid(scene, table, f"{where} [sea]")        # refused: not a sea
        return ({},)
    if "seed" not in table and not scene.lift:
        first = int(scene.sea.get("seed", 0))
        table["seed"] = list(range(first, first + extremes_option(scene, "seeds")))
    return tuple(check_grid(scene, table, f"{where} [sea]").cases()) if table else ({},)
