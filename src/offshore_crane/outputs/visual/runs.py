"""A run's CSV read as it streams: the rows parsed a chunk at a time, only the columns a
:class:`~offshore_crane.outputs.visual.motion.Motion` holds kept, so that memory is the
numbers read and one chunk of text (a 30-minute log at 1 kHz is a gigabyte of text, which
read whole and split into cells took ten times that). :func:`read_fields` reads;
:func:`offshore_crane.outputs.visual.motion.read_run` makes its :class:`Motion`.

The accepted files are :mod:`~offshore_crane.outputs.visual.motion`'s. A force column
that is ``nan`` on every row is an actuator the run did not have (``offshore-crane id``
writes the arm's forces so for a platform without the arm): its values stay NaN and the
caller decides; a ``nan`` among numbers is an error naming its row.
"""

from __future__ import annotations

import csv
import io
import os
import stat

import numpy as np

from offshore_crane.conventions import (ACTUATOR_UNITS, ACTUATORS, LEGACY_COLUMNS, Q_COLUMNS,
                                        QD_COLUMNS, QDD_COLUMNS, coordinate_column)
from offshore_crane.errors import InputError, TrajectoryError
from offshore_crane.validation import check_memory

#: Columns of a run's CSV that are read (others are refused, or ignored if known).
FORCE_COLUMNS = tuple(f"{a}_{u.replace('·', '')}" for a, u in zip(ACTUATORS, ACTUATOR_UNITS))
SWAY_COLUMNS = ("phi1_rad", "phi2_rad")
KNOWN_COLUMNS = (("t_s",) + Q_COLUMNS
                 + tuple(coordinate_column(k, tag="_ref") for k in range(9))
                 + QD_COLUMNS + QDD_COLUMNS + FORCE_COLUMNS + SWAY_COLUMNS + ("tension_N",))

#: Bytes of text parsed at a time (whole lines): ~10× this is its parse's peak.
CHUNK_BYTES = 1 << 20
#: The columns kept, in this order (those the file has).
KEPT = ("t_s",) + Q_COLUMNS + QD_COLUMNS + QDD_COLUMNS + FORCE_COLUMNS + SWAY_COLUMNS


def read_fields(path, option: str = "--from", header_check=None, memory=None) -> tuple:
    """Read a run's CSV: ``(name, t (N,), q (N, 9), qd, qdd, X (N, 9), sway (N, 2))``
    [s, m, rad, N, N·m], None for what the file does not give; ``option`` is the
    command-line option that named it, for the messages.

    Args:
        path: A file, or a pipe that ends (read once, :data:`~offshore_crane.io.PIPE_TIMEOUT`).
        header_check: ``header_check(columns)`` called with the header's column names
            (legacy names made current) before they are checked here: a caller's own
            refusals (e.g. a hanging load's columns).
        memory: ``memory(rows) -> bytes`` the caller needs for a file of that many rows,
            checked (:func:`~offshore_crane.validation.check_memory`) once the first
            chunk gives the rows' size (default: the numbers kept, twice).

    Raises:
        TrajectoryError: the file is missing, a directory or a device, unreadable, lacks
            ``t_s`` or one of q1..q9 (an ``offshore-crane id`` CSV: named as such), has
            an unknown column, a row of the wrong length, a non-numeric or non-finite cell
            (naming the line and column), or a time that does not increase.
        InputError: more memory than the limit.
    """
    where = os.fspath(path)
    fh, size = _open(where, option)
    with fh:
        return _parse(fh, size, where, option, header_check, memory)


def _open(where: str, option: str):
    """``(binary stream, its size in bytes)`` of a regular file or a pipe."""
    from offshore_crane.io import read_bytes

    try:
        mode = os.stat(where).st_mode
    except (FileNotFoundError, NotADirectoryError):
        raise TrajectoryError(f"{option} {where}: no such file (a CSV of offshore-crane "
                              "simulate --out, or a trajectory t_s,q1..q9)",
                              path=where) from None
    except OSError as exc:
        raise TrajectoryError(f"{option} {where}: cannot read the run CSV: {exc.strerror}",
                              path=where) from None
    if stat.S_ISFIFO(mode):
        try:
            data = read_bytes(where, "run CSV")
        except InputError as exc:
            raise TrajectoryError(f"{option} {exc}", path=where) from None
        return io.BytesIO(data), len(data)
    if not stat.S_ISREG(mode):
        kind = ("a directory" if stat.S_ISDIR(mode) else "a character device"
                if stat.S_ISCHR(mode) else "a block device" if stat.S_ISBLK(mode) else
                "a socket" if stat.S_ISSOCK(mode) else "no regular file")
        raise TrajectoryError(f"{option} {where}: is {kind}, not a run's CSV: give the "
                              "file (or a pipe that ends)", path=where)
    try:
        fh = open(where, "rb")
    except OSError as exc:
        raise TrajectoryError(f"{option} {where}: cannot read the run CSV: {exc.strerror}",
                              path=where) from None
    return fh, os.fstat(fh.fileno()).st_size


def _chunks(fh, where: str):
    """The stream's text a chunk of whole lines at a time (a byte-order mark before the
    header ignored)."""
    line = 0
    while True:
        lines = fh.readlines(CHUNK_BYTES)
        if not lines:
            return
        raw = b"".join(lines)
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError as exc:
            at = line + raw.count(b"\n", 0, exc.start) + 1
            column = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
            raise TrajectoryError(f"{where}, line {at}, column {column}: byte "
                                  f"0x{raw[exc.start]:02x} is not UTF-8: save the run CSV "
                                  "as UTF-8 text", path=where) from None
        yield text.removeprefix("\ufeff") if line == 0 else text
        line += len(lines)


def _rows(text: str) -> list:
    """The CSV rows of ``text`` that hold something (blank rows dropped)."""
    return [r for r in csv.reader(text.splitlines()) if r and any(c.strip() for c in r)]


def _header(rows: list, where: str, header_check) -> list[str]:
    """The header's column names, checked."""
    header = [LEGACY_COLUMNS.get(c.strip(), c.strip()) for c in rows[0]]
    if header_check is not None:
        header_check(header)
    if "t_s" in header and Q_COLUMNS[0] not in header and "T1_Nm" in header:
        raise TrajectoryError(f"{where}: holds actuator forces only (the CSV of "
                              "offshore-crane id): give the trajectory it was computed on "
                              "with --trajectory (the forces are recomputed)", path=where)
    missing = [c for c in ("t_s",) + Q_COLUMNS if c not in header]
    if missing:
        raise TrajectoryError(f"{where}, line 1: missing column(s) {', '.join(missing)}: "
                              "a run's CSV needs t_s,q1_m..q9_m", name=",".join(missing),
                              path=where)
    unknown = [c for c in header if c not in KNOWN_COLUMNS]
    repeated = sorted({c for c in header if header.count(c) > 1})
    if unknown or repeated:
        bad = unknown or repeated
        raise TrajectoryError(f"{where}, line 1: {'unknown' if unknown else 'repeated'} "
                              f"column(s) {', '.join(map(repr, bad))}: accepted are t_s, "
                              "q1..q9, q1_ref..q9_ref, qd1..qd9, qdd1..qdd9, "
                              f"{FORCE_COLUMNS[0]}..{FORCE_COLUMNS[-1]}, phi1_rad, phi2_rad, "
                              "tension_N", name=bad[0], path=where)
    return header


class _Numbers:
    """The kept columns' numbers, checked chunk by chunk (rows counted over the file)."""

    def __init__(self, header: list[str], where: str):
        self.header, self.where = header, where
        self.names = [c for c in KEPT if c in header]
        self.index = [header.index(c) for c in self.names]
        self.forces = [k for k, c in enumerate(self.names) if c in FORCE_COLUMNS]
        self.others = [k for k, c in enumerate(self.names) if c not in FORCE_COLUMNS]
        self.parts: list = []
        self.rows = 0
        self.last_t = None
        self.numbers = np.zeros(len(self.names), dtype=bool)  # a force column has one
        self.bad: dict = {}                 # force column -> (row, text) of its first bad

    def add_text(self, text: str) -> None:
        """Add a chunk of data lines: read by NumPy's parser when every row is whole and
        every kept value finite, else row by row (the checks naming the row and cell)."""
        if not text.strip():
            return
        try:
            values = np.loadtxt(io.StringIO(text), delimiter=",", comments=None, ndmin=2)
        except ValueError:
            values = None
        if (values is None or values.shape[1] != len(self.header)
                or not np.isfinite(values[:, self.index]).all()):
            self.add(_rows(text))
        else:
            self._take(values[:, self.index], None)

    def add(self, data: list) -> None:
        """Add parsed rows (lists of cells), each checked."""
        where, n = self.where, len(self.header)
        for i, row in enumerate(data):
            if len(row) != n:
                raise TrajectoryError(f"{where}, data row {self.rows + i + 1}: {len(row)} "
                                      f"cells, expected {n}", index=self.rows + i,
                                      path=where)
        if not data:
            return
        try:
            values = np.array([[row[j] for j in self.index] for row in data],
                              dtype=str).astype(float).reshape(len(data), len(self.index))
        except ValueError:
            self._not_a_number(data)
            raise
        self._take(values, data)

    def _take(self, values: np.ndarray, data: list | None) -> None:
        """Check and keep ``values`` (the kept columns); ``data``: their cells' text, for
        the messages (None: every value is finite)."""
        where = self.where
        bad = ~np.isfinite(values)
        wrong = np.argwhere(bad[:, self.others])
        if len(wrong):
            i, j = (int(x) for x in wrong[0])
            self._not_finite(self.rows + i, self.names[self.others[j]],
                             data[i][self.index[self.others[j]]])
        for k in self.forces:
            nan = np.isnan(values[:, k])
            wrong = np.flatnonzero(bad[:, k])
            if len(wrong) and k not in self.bad:
                self.bad[k] = (self.rows + int(wrong[0]), data[wrong[0]][self.index[k]])
            if not nan.all() or not (bad[:, k] == nan).all():
                self.numbers[k] = True   # a number, or an inf: no actuator left unlogged
        t = values[:, 0]
        steps = np.diff(t if self.last_t is None else np.r_[self.last_t, t])
        back = np.flatnonzero(steps <= 0.0)
        if len(back):
            i = int(back[0]) + (1 if self.last_t is None else 0)
            before = float(t[i - 1]) if i > 0 else float(self.last_t)
            raise TrajectoryError(f"{where}, data row {self.rows + i + 1}: t_s = "
                                  f"{float(t[i])!r} s does not increase after {before!r} s",
                                  name="t_s", index=self.rows + i, path=where)
        self.last_t = float(t[-1])
        self.parts.append(values)
        self.rows += len(values)

    def _not_a_number(self, data: list) -> None:
        for i, row in enumerate(data):
            for j, cell in zip(self.index, (row[j] for j in self.index)):
                try:
                    float(cell)
                except ValueError:
                    raise TrajectoryError(f"{self.where}, data row {self.rows + i + 1}, "
                                          f"column {self.header[j]}: {cell.strip()!r} is not "
                                          "a number", name=self.header[j], index=self.rows + i,
                                          path=self.where) from None

    def _not_finite(self, row: int, name: str, text: str) -> None:
        raise TrajectoryError(f"{self.where}, data row {row + 1}, column {name}: "
                              f"{text.strip()!r} is not finite (a simulation that stopped "
                              "early keeps every sample it computed: cut the file there)",
                              name=name, index=row, path=self.where)

    def fields(self) -> tuple:
        """The fields of :func:`read_fields` of the numbers read (a force column ``nan``
        throughout stays NaN: an actuator the run did not have)."""
        if self.rows < 2:
            raise TrajectoryError(f"{self.where}: {self.rows} data row(s), at least 2 are "
                                  "needed", path=self.where)
        wrong = sorted((row, k, text) for k, (row, text) in self.bad.items()
                       if self.numbers[k])          # nan throughout: an absent actuator
        if wrong:
            row, k, text = wrong[0]
            self._not_finite(row, self.names[k], text)

        def block(names):
            given = [n in self.names for n in names]
            if not all(given):
                if any(given):
                    missing = [n for n, g in zip(names, given) if not g]
                    raise TrajectoryError(f"{self.where}, line 1: missing column(s) "
                                          f"{', '.join(missing)} of {names[0]}..{names[-1]}: "
                                          "give all of them or none", name=missing[0],
                                          path=self.where)
                return None
            cols = [self.names.index(n) for n in names]
            return np.concatenate([p[:, cols] for p in self.parts])

        t = block(["t_s"])[:, 0]
        fields = [block(list(c)) for c in (Q_COLUMNS, QD_COLUMNS, QDD_COLUMNS,
                                            FORCE_COLUMNS, SWAY_COLUMNS)]
        self.parts = []
        return (os.path.splitext(os.path.basename(self.where))[0], t, *fields)


def _parse(fh, size: int, where: str, option: str, header_check, memory) -> tuple:
    numbers = None
    for text in _chunks(fh, where):
        if numbers is None:
            lines = text.splitlines(keepends=True)
            first = next((k for k, ln in enumerate(lines) if _rows(ln)), None)
            if first is None:
                continue
            numbers = _Numbers(_header(_rows(lines[first]), where, header_check), where)
            text = "".join(lines[first + 1:])
            rows = max(len(lines) - first - 1, 1)
            estimate = size / (fh.tell() / rows) if len(lines) > first + 1 else 0.0
            need = (memory(estimate) if memory is not None
                    else 16.0 * len(numbers.names) * estimate)
            check_memory(need, f"{option} {where} (about {estimate:.3g} rows)",
                         "give a shorter log (cut it in parts) or raise "
                         "OFFSHORE_CRANE_MEMORY_LIMIT", name=option)
        numbers.add_text(text)
    if numbers is None:
        raise TrajectoryError(f"{where}: the file is empty: it needs a header line with "
                              "t_s,q1_m..q9_m and at least 2 rows", path=where)
    return numbers.fields()
