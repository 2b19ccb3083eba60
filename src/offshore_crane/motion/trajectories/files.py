"""Trajectory CSV files: ``t_s,q1_m..q9_m`` (units in the names; optionally with the rates
and accelerations), read with every bad line named and written atomically.
"""

from __future__ import annotations

import csv
import os
from pathlib import Path

import numpy as np

from offshore_crane.conventions import LEGACY_COLUMNS, Q_COLUMNS, QD_COLUMNS, QDD_COLUMNS
from offshore_crane.errors import TrajectoryError


#: Header of a trajectory CSV file: time [s] then q1..q9, each with its unit
#: (``q1_m .. q3_m, q4_rad .. q8_rad, q9_m``; :func:`offshore_crane.conventions.
#: coordinate_column`). Files with the bare names of earlier versions (``q1..q9``) are read
#: too.
CSV_COLUMNS = ("t_s",) + Q_COLUMNS
#: The same with the rates and accelerations (written by ``offshore-crane motion``):
#: ``qd1_m_s .. qd9_m_s`` [m/s or rad/s] and ``qdd1_m_s2 ..`` [m/s² or rad/s²], used
#: instead of finite differences when present.
CSV_COLUMNS_DERIVATIVES = CSV_COLUMNS + QD_COLUMNS + QDD_COLUMNS


def read_csv(path, derivatives: bool = False):
    """Read a trajectory CSV file with header ``t_s,q1_m,q2_m,q3_m,q4_rad,..,q8_rad,q9_m``,
    optionally followed by ``qd1_m_s..qd9_m_s,qdd1_m_s2..qdd9_m_s2`` (or the bare names of
    earlier versions, ``q1..q9``, ``qd1..``, ``qdd1..``).

    Whitespace around column names and numbers is ignored, blank lines are skipped. The
    columns must appear in that order.

    Args:
        path: Path of the file (str or path-like).
        derivatives: Also return the derivative columns (None when the file has none).

    Returns:
        ``(t, q)``: ``t`` ``(N,)`` [s], ``q`` ``(N, 9)`` [m or rad], ``N >= 2``; with
        ``derivatives``, ``(t, q, qd, qdd)`` (``qd, qdd`` ``(N, 9)`` or None).

    Raises:
        TrajectoryError: the file is missing, unreadable or empty; the header lacks,
            repeats, misorders or adds columns (``name`` lists them); a row has the wrong
            number of cells, a non-numeric, NaN or infinite cell (``name`` is the column,
            ``index`` the 0-based data row); time is not strictly increasing; fewer than
            2 rows.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise TrajectoryError(f"the trajectory file must be a path, got {path!r}", name="path")
    path = Path(os.fspath(path))
    if not path.is_file():
        raise TrajectoryError(
            f"trajectory file '{path}' does not exist or is not a file: check the path.",
            path=str(path))
    from offshore_crane.errors import InputError
    from offshore_crane.io import read_text

    try:
        text = read_text(path, "trajectory CSV file").removeprefix("\ufeff")
        reader = csv.reader(text.splitlines())
        lines, rows = [], []
        for row in reader:
            if row and any(cell.strip() for cell in row):
                lines.append(reader.line_num)
                rows.append(row)
    except InputError as exc:
        raise TrajectoryError(str(exc), path=str(path)) from None
    except csv.Error as exc:
        raise TrajectoryError(
            f"cannot read trajectory file '{path}': {exc}: give a readable UTF-8 CSV file.",
            path=str(path)) from None
    expected = ",".join(CSV_COLUMNS)
    if not rows:
        raise TrajectoryError(
            f"trajectory file '{path}' is empty: it needs the header line '{expected}' and "
            "at least 2 data rows.", path=str(path))

    header = [LEGACY_COLUMNS.get(cell.strip(), cell.strip()) for cell in rows[0]]
    hline = lines[0]
    columns = CSV_COLUMNS_DERIVATIVES if len(header) > len(CSV_COLUMNS) and any(
        c.startswith("qd") for c in header) else CSV_COLUMNS
    expected_all = ",".join(columns)
    missing = [c for c in columns if c not in header]
    extra = [c for c in header if c not in columns]
    duplicate = sorted({c for c in header if header.count(c) > 1})
    if missing:
        raise TrajectoryError(
            f"{path}, line {hline}: missing column(s) {', '.join(missing)}: the header must be "
            f"'{expected_all}'.", name=",".join(missing), path=str(path))
    if extra:
        raise TrajectoryError(
            f"{path}, line {hline}: unknown column(s) {', '.join(map(repr, extra))}: the header "
            f"must be exactly '{expected_all}'; remove the others.", name=",".join(extra),
            path=str(path))
    if duplicate:
        raise TrajectoryError(
            f"{path}, line {hline}: repeated column(s) {', '.join(duplicate)}: the header must "
            f"be exactly '{expected_all}'.", name=",".join(duplicate), path=str(path))
    if tuple(header) != columns:
        raise TrajectoryError(
            f"{path}, line {hline}: columns are in the order {','.join(header)}: put them in "
            f"the order '{expected_all}'.", name=None, path=str(path))

    data, data_lines = rows[1:], lines[1:]
    ncol = len(columns)
    for i, row in enumerate(data):  # cheap length check; numbers are converted at once below
        if len(row) != ncol:
            raise TrajectoryError(
                f"{path}, line {data_lines[i]}: {len(row)} cells, expected {ncol} "
                f"({expected_all}): fix that row.", name=None, index=i, path=str(path))
    if len(data) < 2:
        raise TrajectoryError(
            f"{path}: {len(data)} data row(s), at least 2 are needed: add samples.",
            index=len(data) - 1 if data else None, path=str(path))
    try:  # NumPy parses str -> float like Python's float(): surrounding blanks allowed
        values = np.array(data, dtype=str).astype(float)
    except ValueError:
        values = None
    if values is None:  # slow path, only on failure: locate the first non-numeric cell
        for i, row in enumerate(data):
            for j, cell in enumerate(row):
                try:
                    float(cell)
                except ValueError:
                    raise TrajectoryError(
                        f"{path}, line {data_lines[i]}, column {columns[j]}: {cell.strip()!r} "
                        "is not a number: write a decimal number there.",
                        name=columns[j], index=i, path=str(path)) from None
        raise TrajectoryError(  # pragma: no cover - NumPy and float() agree on all inputs
            f"{path}: a cell is not a number: write decimal numbers only.")
    finite = np.isfinite(values)
    if not finite.all():
        i, j = (int(k) for k in np.argwhere(~finite)[0])
        raise TrajectoryError(
            f"{path}, line {data_lines[i]}, column {columns[j]}: {data[i][j].strip()!r} "
            "is not finite: give finite values.", name=columns[j], index=i, path=str(path))
    t = values[:, 0]
    bad = np.diff(t) <= 0.0
    if bad.any():
        i = int(np.argmax(bad)) + 1
        raise TrajectoryError(
            f"{path}, line {data_lines[i]}: time t_s = {float(t[i])!r} s does not increase after "
            f"{float(t[i - 1])!r} s on line {data_lines[i - 1]}: sort the rows by time and remove "
            "duplicates.", name="t_s", index=i, path=str(path))
    t, q = np.ascontiguousarray(t), np.ascontiguousarray(values[:, 1:10])
    if not derivatives:
        return t, q
    if columns is CSV_COLUMNS:
        return t, q, None, None
    return t, q, np.ascontiguousarray(values[:, 10:19]), np.ascontiguousarray(values[:, 19:28])


def write_csv(path, t, q, qd=None, qdd=None) -> None:
    """Write a trajectory CSV file readable by :func:`read_csv`, through
    :mod:`offshore_crane.io` (checked, atomic; ``path`` may be an ``io.Target``).

    Numbers are written with ``%.17g``, which round-trips float64 exactly.

    Args:
        path: Destination (str or path-like); overwritten if it exists.
        t: ``(N,)`` time [s], finite.
        q: ``(N, 9)`` generalized coordinates [m or rad], finite.
        qd, qdd: optional ``(N, 9)`` rates and accelerations (both or neither): written as
            the columns ``qd1..qd9,qdd1..qdd9``.

    Raises:
        TrajectoryError: wrong shapes or non-finite values.
        OutputError: the file cannot be written.
    """
    from offshore_crane import io

    t = np.asarray(t, dtype=float)
    arrays = [np.asarray(x, dtype=float) for x in (q, qd, qdd) if x is not None]
    if (qd is None) != (qdd is None):
        raise TrajectoryError("write_csv needs both qd and qdd, or neither.", name="qd")
    if t.ndim != 1 or any(x.shape != (t.shape[0], 9) for x in arrays):
        raise TrajectoryError(
            f"write_csv needs t (N,) and q (N, 9), got {t.shape} and "
            f"{', '.join(str(x.shape) for x in arrays)}.", name="q")
    data = np.column_stack([t, *arrays])
    finite = np.isfinite(data).all(axis=1)
    if not finite.all():
        k = int(np.argmin(finite))
        raise TrajectoryError(
            f"write_csv: sample {k} is not finite: give finite values.", name="q", index=k)
    header = CSV_COLUMNS if len(arrays) == 1 else CSV_COLUMNS_DERIVATIVES
    io.write_csv(path, ",".join(header), data)
