"""A sweep's grid: reading a grid TOML file, checking it against the scene, and the cases it
expands to (their scenes and ids).
"""

from __future__ import annotations

import hashlib
import itertools
import math
import os
from dataclasses import dataclass

from offshore_crane.errors import GridError
from offshore_crane.io import toml_value
from offshore_crane.validation import not_a_number


#: Grid keys that set the scene's ``[sea]`` (full scale): Hs [m], Tp [s], heading [deg],
#: Froude scale [-], random-phase seed.
SEA_KEYS = ("hs", "tp", "heading", "scale", "seed")


def install_hint(module: str, purpose: str):
    from offshore_crane.errors import require

    package = {"distributed": "distributed", "pyarrow": "pyarrow"}.get(module, module)
    return require(module, f"{package} (or: pip install offshore-crane[sweep])", purpose)


# =========================================================================== the grid
@dataclass(frozen=True)
class Grid:
    """A checked grid: ``keys`` in product order, ``values`` their lists; or, made by
    :meth:`listed`, a list of cases (``rows``) instead of a product.

    Attributes:
        keys: Grid keys; robot fields by their dotted names, then the sea keys.
        values: ``{key: tuple of values}``: floats (``seed``: ints).
        where: The grid file (or ``"grid"``), for messages.
        rows: None for a product; else the cases, each a tuple of values in ``keys``'
            order (a design's candidates over its sea states).
    """

    keys: tuple
    values: dict
    where: str = "grid"
    rows: tuple | None = None

    @classmethod
    def listed(cls, keys, rows, where: str = "cases") -> "Grid":
        """The cases ``rows`` (tuples of values in ``keys``' order), run as given, not as
        a product; their values checked by the caller."""
        rows = tuple(tuple(r) for r in rows)
        return cls(tuple(keys), {k: tuple(r[i] for r in rows) for i, k in enumerate(keys)},
                   where, rows)

    def cases(self):
        """The product of the lists, in order, made one at a time (an iterator of
        ``{key: value}``): the last key varies fastest (the seeds of one case are
        consecutive; robot fields vary slowest, so that a worker keeps its robot for many
        cases). A listed grid's cases in their order."""
        if self.rows is not None:
            return (dict(zip(self.keys, r)) for r in self.rows)
        return (dict(zip(self.keys, combo))
                for combo in itertools.product(*(self.values[k] for k in self.keys)))

    @property
    def count(self) -> int:
        """How many cases :meth:`cases` makes."""
        if self.rows is not None:
            return len(self.rows)
        return math.prod(len(self.values[k]) for k in self.keys)

    def as_dict(self) -> dict:
        """The grid as the manifest records it: ``{key: list}`` of a product, ``{"keys":
        [...], "cases": [[...], ...]}`` of a listed grid."""
        if self.rows is not None:
            return {"keys": list(self.keys), "cases": [list(r) for r in self.rows]}
        return {k: list(self.values[k]) for k in self.keys}


def _flatten(table: dict, where: str, prefix: str = "") -> dict:
    out = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(_flatten(value, where, f"{name}."))
        else:
            out[name] = value
    return out


def load_grid(path) -> dict:
    """Read a grid file (TOML): ``{key: list}`` with TOML's dotted keys joined
    (``payload.mass = [...]`` and ``"payload.mass" = [...]`` alike); checked by
    :func:`check_grid` against a scene.

    Raises:
        GridError: unreadable file, invalid TOML.
    """
    from offshore_crane.errors import InputError
    from offshore_crane.io import read_toml

    where = os.fspath(path)
    try:
        data = read_toml(where, "grid file")
    except InputError as exc:
        raise GridError(str(exc), path=where) from None
    return _flatten(data, where)


#: Most cases a grid may make unless raised (``max_cases``, CLI ``--max-cases``): a million
#: rows is ~1 GB of results and days of computation; more is a typing slip more often than
#: a plan.
MAX_CASES = 10**6


def check_grid(scene, grid: dict, where: str = "grid", max_cases: int = MAX_CASES) -> Grid:
    """Check a grid against a scene, value by value, before anything runs.

    Args:
        scene: The :class:`~offshore_crane.scenes.Scene` swept.
        grid: ``{key: list of values}`` (:func:`load_grid`, or a dict).
        where: The grid's name in messages (its file).
        max_cases: The most cases the grid may make (counted from its lists' lengths
            before anything is built).

    Returns:
        :class:`Grid`.

    Raises:
        GridError: more cases than ``max_cases``, not a table of lists, an unknown key (neither a sea key nor a robot
            field), an empty list, a repeated value (headings compared modulo 360°), a value that is not a number (an
            integer ≥ 0 for ``seed``), a sea key on a scene that is not a sea, a key given
            twice (an alias and its dotted name), or a value the scene's own checks refuse
            (``hs <= 0``, a negative mass, ...), naming the key and the index.
    """
    from offshore_crane.errors import DescriptionError, SceneError
    from offshore_crane.robot.overrides import normalise

    if not isinstance(grid, dict) or not grid:
        raise GridError(f"{where}: the grid is empty: give lists of values, e.g. "
                        "hs = [1.0, 2.0]", path=where)
    lengths = [len(v) for v in grid.values() if isinstance(v, (list, tuple))]
    count = math.prod(lengths)
    if count > max_cases:
        raise GridError(f"{where}: the grid makes {count:,} cases ("
                        f"{' × '.join(map(str, lengths))}), more than the limit {max_cases:,}: "
                        "split it, or raise the limit (max_cases, CLI --max-cases)",
                        path=where)
    robot_keys, sea, values = [], [], {}
    for key, raw in grid.items():
        if not isinstance(raw, (list, tuple)):
            raise GridError(f"{where}: {key} = {toml_value(raw)}: must be a list of values, "
                            f"e.g. {key} = [{toml_value(raw)}]", path=where, key=key)
        if not raw:
            raise GridError(f"{where}: {key} = []: the list is empty: give at least one "
                            "value (a grid's cases are the product of its lists)",
                            path=where, key=key)
        if key in SEA_KEYS:
            name = key
            if scene.trajectory != "sea":
                raise GridError(f"{where}: {key}: a sea key, but the scene "
                                f"{scene.where()} is not a sea (its [trajectory] source is "
                                f"{scene.trajectory!r}): use a scene with source = \"sea\"",
                                path=where, key=key)
            sea.append(key)
        else:
            try:
                name = next(iter(normalise({key: 0.0}, where)))
            except DescriptionError as exc:
                raise GridError(f"{where}: unknown grid key {key!r}: neither a sea key "
                                f"({', '.join(SEA_KEYS)}) nor a robot field ({exc})",
                                path=where, key=key) from None
            if name in values:
                raise GridError(f"{where}: {key} and {name} name the same robot field: "
                                "give it once", path=where, key=key)
            robot_keys.append(name)
        checked = []
        for i, v in enumerate(raw):
            if key == "seed":
                if isinstance(v, bool) or not isinstance(v, int) or v < 0:
                    raise GridError(f"{where}: seed[{i}] = {toml_value(v)}: must be an integer "
                                    "≥ 0", path=where, key=key, index=i)
                checked.append(int(v))
                continue
            problem = not_a_number(v)
            if problem:
                raise GridError(f"{where}: {key}[{i}] = {toml_value(v)}: {problem}: give a "
                                "finite number", path=where, key=key, index=i)
            # a heading is a direction: 450° and -270° are the heading 90° (one case)
            checked.append(float(v) % 360.0 if key == "heading" else float(v))
        if len(set(checked)) != len(checked):
            same = " (headings modulo 360°)" if key == "heading" else ""
            raise GridError(f"{where}: {key} = {toml_value(list(raw))}: names a value "
                            f"twice{same}", path=where, key=key)
        for i, v in enumerate(checked):         # the scene's own checks, value by value
            try:
                case_scene(scene, {name: v}, origin=f"{where}: {key}[{i}] = {toml_value(v)}")
            except (SceneError, DescriptionError) as exc:
                raise GridError(str(exc), path=where, key=key, index=i) from None
        values[name] = tuple(checked)
    keys = tuple(sorted(robot_keys)) + tuple(k for k in SEA_KEYS if k in sea)
    return Grid(keys, values, where)


def case_scene(scene, params: dict, origin: str | None = None):
    """``scene`` with a case's values: sea keys into ``[sea]``, robot fields (dotted
    names) over the scene's own (a grid value replaces the scene's, on purpose)."""
    from offshore_crane.scenes.assembly import with_values

    return with_values(scene, params, origin or f"{scene.where()} case {params}")


class CaseIds:
    """Case ids of one scene's cases: 16 hex digits of the SHA-256 of the *resolved* case —
    the digest of the robot the case's fields resolve to
    (:meth:`offshore_crane.robot.description.Description.digest`) and the case's sea
    values that differ from the scene's own (defaults of the sea functions filled in,
    headings modulo 360°, numbers as floats).

    So a grid value equal to the scene's own (``hs = [2.5]`` on a scene of Hs 2.5 m,
    ``"payload.mass" = [2.0]`` on a payload of 2 kg) is the scene's own case, whatever the
    grid that names it; an id is stable across runs, processes, grid orders and
    spellings (ids identify cases of one scene: a results directory holds one scene's).
    The robot is resolved once per combination of robot fields (cached); an id costs
    ~5 µs after that.
    """

    def __init__(self, scene):
        self.scene = scene
        self._robots: dict = {}
        self._sea = (_canonical_sea(_sea_defaults(scene)) if scene.trajectory == "sea"
                     else {})

    def robot_digest(self, robot: dict) -> str:
        """Digest of the scene's robot with the fields ``robot`` (dotted names) over its
        own."""
        from offshore_crane.robot.description import resolve

        key = tuple(sorted(robot.items()))
        if key not in self._robots:
            self._robots[key] = resolve(self.scene.robot_description,
                                        {**self.scene.robot, **robot}).digest()
        return self._robots[key]

    def __call__(self, params: dict) -> str:
        robot, sea = {}, []
        for key, value in params.items():
            if key in SEA_KEYS:
                value = _canonical_value(key, value)
                if value != self._sea.get(key):
                    sea.append(f"{key}={value!r}")
            else:
                robot[key] = value
        text = self.robot_digest(robot) + ";" + ";".join(sorted(sea))
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def _sea_defaults(scene) -> dict:
    """The scene's ``[sea]`` with the sea motion's defaults for the keys it omits."""
    import inspect

    from offshore_crane.motion.sea import sea_motion

    defaults = {("heading" if n == "heading_deg" else n): p.default
                for n, p in inspect.signature(sea_motion).parameters.items()
                if p.default is not inspect.Parameter.empty and n not in ("check",)}
    return {**defaults, **scene.sea}


def _canonical_value(key: str, v):
    """A sea value as the motion sees it: numbers as floats (``seed`` an int), the heading
    modulo 360°, sequences as lists."""
    if isinstance(v, bool) or v is None or isinstance(v, str):
        return v
    if isinstance(v, (int, float)):
        if key == "seed":
            return int(v)
        return float(v) % 360.0 if key == "heading" else float(v)
    if isinstance(v, (list, tuple)):
        return [_canonical_value(key, x) for x in v]
    return v


def _canonical_sea(sea: dict) -> dict:
    return {k: _canonical_value(k, v) for k, v in sea.items()}


def scene_values(scene, keys) -> dict:
    """The scene's own value of each grid key it has one for: a sea key's (defaults
    filled in), a robot field's as its description resolves it (a field the description
    leaves to a default it does not list is left out)."""
    from offshore_crane.robot.description import resolve

    out: dict = {}
    sea = _canonical_sea(_sea_defaults(scene)) if scene.trajectory == "sea" else {}
    spec = None
    for key in keys:
        if key in SEA_KEYS:
            if key in sea:
                out[key] = sea[key]
            continue
        if spec is None:
            spec = resolve(scene.robot_description, scene.robot)
        value = spec.values.get(key)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            out[key] = float(value)
    return out


def case_id(scene, params: dict) -> str:
    """The id of one case of ``scene`` (:class:`CaseIds`; for many cases make one
    :class:`CaseIds` and call it, the robot is then resolved once per combination)."""
    return CaseIds(scene)(params)
