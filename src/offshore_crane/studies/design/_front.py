"""The front as a table: ``pareto.csv`` (one row per non-dominated feasible design: its
number, its variables by their dotted names, its objectives as written in the space file,
its constraints' values), written whole, and read back for ``--pick``.
"""

from __future__ import annotations

import csv
import io
import os

from offshore_crane.errors import InputError

#: The front's file in a design's output directory.
PARETO = "pareto.csv"


def front_columns(space) -> list[str]:
    """The columns of ``pareto.csv``: ``design``, the variables, the objectives, then each
    constraint's quantity not already an objective."""
    objectives = [o.quantity.text for o in space.objectives]
    constraints = [c.quantity.text for c in space.constraints]
    return (["design", *space.names, *objectives]
            + [q for q in dict.fromkeys(constraints) if q not in objectives])


def front_rows(design) -> list[dict]:
    """``pareto.csv``'s rows: ``{column: value}``, numbered from 1."""
    space = design.space
    rows = []
    for n, c in enumerate(design.front, start=1):
        row = {"design": n, **c.values}
        row.update({o.quantity.text: x for o, x in zip(space.objectives, c.objectives)})
        for k, x in zip(space.constraints, c.constraints):
            row.setdefault(k.quantity.text, x)
        rows.append(row)
    return rows


def front_text(design) -> str:
    """The text of ``pareto.csv``: numbers with 17 significant digits (they read back to
    the same floats)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    columns = front_columns(design.space)
    writer.writerow(columns)
    for row in front_rows(design):
        writer.writerow([row["design"]] + [f"{float(row[c]):.17g}" for c in columns[1:]])
    return buffer.getvalue()


def write_front(directory, design) -> str:
    """Write ``directory/pareto.csv`` (whole or not at all); returns its path."""
    from offshore_crane.io import write_text

    path = os.path.join(os.fspath(directory), PARETO)
    write_text(path, front_text(design))
    return path


def read_front(path) -> list[dict]:
    """The rows of a ``pareto.csv``: ``{column: float}`` (``design`` an int).

    Raises:
        InputError: unreadable, or not a front (no ``design`` column, a cell that is not
            a number).
    """
    from offshore_crane.io import read_text

    where = os.fspath(path)
    text = read_text(where, "design front (pareto.csv)")
    reader = csv.DictReader(io.StringIO(text))
    if not reader.fieldnames or reader.fieldnames[0] != "design":
        raise InputError(f"{where}: not a design front (its first column must be 'design'):"
                         " give the --out directory of a finished design", name=where)
    rows = []
    for line, row in enumerate(reader, start=2):
        try:
            rows.append({k: (int(v) if k == "design" else float(v)) for k, v in row.items()})
        except (TypeError, ValueError):
            raise InputError(f"{where}, line {line}: a cell is not a number: the file is "
                             "damaged; rerun the design", name=where) from None
    return rows


def picked(rows: list[dict], n: int, names, where: str) -> dict:
    """The variables ``{name: value}`` of design ``n`` of a front's ``rows``.

    Raises:
        InputError: no design ``n``, or a variable missing from the front's columns.
    """
    match = [r for r in rows if r["design"] == n]
    if not match:
        raise InputError(f"--pick {n}: {where} has designs 1..{len(rows)}: pick one of "
                         "them", name="--pick")
    missing = [k for k in names if k not in match[0]]
    if missing:
        raise InputError(f"--pick {n}: {where} has no column {missing[0]!r}: it is the "
                         "front of another space", name="--pick")
    return {k: match[0][k] for k in names}
