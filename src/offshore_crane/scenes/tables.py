"""Reading one table of a scene file: :class:`TableReader` checks its keys and values
(numbers with their units and bounds, vectors, names, booleans), naming the file, the
section and the key in every message; :func:`section` opens a section."""

from __future__ import annotations

import math

from offshore_crane.errors import SceneError
from offshore_crane.io import toml_value
from offshore_crane.validation import not_a_number


class TableReader:
    """Checks the values of one scene table; errors name ``where`` and the key."""

    def __init__(self, where: str, section: str | None, table: dict, known: tuple):
        self.where, self.section, self.table = where, section, table
        prefix = f"[{section}] " if section else ""
        for key in table:
            if key not in known:
                self.fail_key(key, f"{prefix}unknown key '{key}': known keys are "
                              f"{', '.join(known)}")

    def key_name(self, key: str) -> str:
        return f"{self.section}.{key}" if self.section else key

    def fail_key(self, key: str, message: str):
        raise SceneError(f"{self.where}: {message}", path=self.where, name=self.key_name(key))

    def fail(self, key: str, problem: str):
        prefix = f"[{self.section}] " if self.section else ""
        self.fail_key(key, f"{prefix}{key} = {toml_value(self.table[key])}: {problem}")

    def get(self, key: str, default=None):
        return self.table.get(key, default)

    def number(self, key: str, default=None, unit: str = "", minimum: float | None = None,
               positive: bool = False):
        if key not in self.table:
            return default
        v = self.table[key]
        problem = not_a_number(v)
        if problem:
            self.fail(key, f"{problem}: give a finite number{f' [{unit}]' if unit else ''}")
        if positive and v <= 0:
            self.fail(key, f"must be > 0{f' {unit}' if unit else ''}")
        if minimum is not None and v < minimum:
            self.fail(key, f"must be ≥ {minimum:g}{f' {unit}' if unit else ''}")
        return float(v)

    def integer(self, key: str, minimum: int, what: str = ""):
        """An integer ≥ ``minimum`` (not a bool), or None when absent; ``what`` says what
        it counts, for the message."""
        if key not in self.table:
            return None
        v = self.table[key]
        if isinstance(v, bool) or not isinstance(v, int) or v < minimum:
            self.fail(key, f"must be an integer ≥ {minimum}" + (f" ({what})" if what else ""))
        return v

    def vector(self, key: str, n: int, default=None, unit: str = ""):
        if key not in self.table:
            return default
        v = self.table[key]
        if (not isinstance(v, list) or len(v) != n
                or any(isinstance(x, bool) or not isinstance(x, (int, float))
                       or not math.isfinite(x) for x in v)):
            self.fail(key, f"must be a list of {n} finite numbers [{unit}]")
        return tuple(float(x) for x in v)

    def boolean(self, key: str, default: bool) -> bool:
        if key not in self.table:
            return default
        if not isinstance(self.table[key], bool):
            self.fail(key, "must be true or false")
        return self.table[key]

    def string(self, key: str, default=None, choices: tuple | None = None):
        if key not in self.table:
            return default
        v = self.table[key]
        if not isinstance(v, str):
            self.fail(key, "must be a string" + (f": one of {', '.join(choices)}"
                                                  if choices else ""))
        if choices and v not in choices:
            self.fail(key, f"must be one of {', '.join(choices)}")
        return v

    def names(self, key: str, choices: tuple):
        """A non-empty list of distinct names out of ``choices`` (in file order)."""
        if key not in self.table:
            return None
        v = self.table[key]
        if not isinstance(v, list) or not v or not all(isinstance(x, str) for x in v):
            self.fail(key, f"must be a non-empty list of names out of {', '.join(choices)}")
        unknown = [x for x in v if x not in choices]
        if unknown:
            self.fail(key, f"unknown {', '.join(map(repr, unknown))}: choose among "
                      f"{', '.join(choices)}")
        if len(set(v)) != len(v):
            self.fail(key, "names a value twice")
        return tuple(v)


def section(where: str, data: dict, name: str, known: tuple) -> TableReader:
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise SceneError(f"{where}: {name} = {toml_value(table)}: must be a table [{name}]",
                         path=where, name=name)
    return TableReader(where, name, table, known)
