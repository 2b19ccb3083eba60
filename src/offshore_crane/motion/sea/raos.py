"""Vessel RAO tables: reading, checking and interpolating a vessel's response amplitude
operators (the packaged supply vessel and user CSV files).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from offshore_crane.errors import SeaStateError
from offshore_crane.motion.sea.arguments import DOFS, HEADING_TOL_DEG, SPACING_RTOL


#: Header of a RAO table CSV file.
RAO_COLUMNS = ("omega_rad_s", "heading_deg", "dof", "amplitude", "phase_rad")
#: Packaged vessels: name -> RAO file in ``offshore_crane/motion/data/vessels``.
VESSELS = {"supply": "supply.csv"}


# ---------------------------------------------------------------------------- RAO tables
@dataclass(frozen=True, eq=False)
class RAOTable:
    """A vessel's motion RAOs on a grid of frequencies × headings.

    Attributes:
        omega: ``(F,)`` wave frequencies [rad/s], strictly increasing, F >= 2.
        heading_deg: ``(H,)`` wave headings [deg] in [0, 360), increasing (our
            convention: 180 = head seas, 90 = waves from starboard).
        values: ``(F, H, 6)`` complex RAOs ``amplitude · e^{i phase}`` for
            :data:`DOFS` [m/m, rad/m] (phase lead, vessel axes x forward, y port, z up).
        source: Where the table came from (file path or packaged name).
    """

    omega: np.ndarray
    heading_deg: np.ndarray
    values: np.ndarray
    source: str

    @property
    def periodic(self) -> bool:
        """Whether heading interpolation wraps round 360 deg.

        True when the gap across 360 deg (``h_0 + 360 − h_last``) is no wider than the
        widest gap between consecutive headings inside the table: a table that goes
        round the circle (0:10:350) wraps, a half-circle table (0:10:180) does not.
        """
        h = self.heading_deg
        if h.size < 2:
            return False
        wrap = h[0] + 360.0 - h[-1]
        # equal spacings computed as 360 - 350 and 20 - 10 differ by round-off only
        return bool(wrap <= np.diff(h).max() * (1.0 + SPACING_RTOL))

    def _heading_weights(self, heading_deg: np.ndarray):
        """Bracketing indices and weights for headings [deg]; raise if one is not covered."""
        h_tab = self.heading_deg
        h = np.mod(heading_deg, 360.0)
        diff = np.abs(np.mod(h[:, None] - h_tab[None, :] + 180.0, 360.0) - 180.0)
        nearest = diff.argmin(axis=1)
        exact = diff[np.arange(h.size), nearest] <= HEADING_TOL_DEG
        idx = np.searchsorted(h_tab, h)
        i0 = np.where(exact, nearest, idx - 1)
        i1 = np.where(exact, nearest, idx)
        wrap = ~exact & ((idx == 0) | (idx == h_tab.size))
        if wrap.any() and not self.periodic:
            k = int(np.argmax(wrap))
            raise SeaStateError(
                f"{self.source}: heading {h[k]:g} deg is not covered by the RAO table "
                f"(headings {h_tab[0]:g}..{h_tab[-1]:g} deg, which do not go round the "
                "circle): use a heading inside that range, or a table with more headings",
                name="heading", path=self.source)
        i0 = np.where(wrap, h_tab.size - 1, i0)
        i1 = np.where(wrap, 0, i1)
        gap = np.mod(h_tab[i1] - h_tab[i0], 360.0)
        offset = np.mod(h - h_tab[i0], 360.0)
        w = np.where(exact, 0.0, offset / np.where(gap > 0.0, gap, 1.0))
        return i0, i1, w

    def __call__(self, omega, heading_deg) -> np.ndarray:
        """Complex RAOs interpolated at frequencies × headings.

        Real and imaginary parts are interpolated linearly in ω and in heading (heading
        periodic when :attr:`periodic`); outside ``[omega[0], omega[-1]]`` the response
        is 0.

        Args:
            omega: ``(M,)`` [rad/s].
            heading_deg: ``(K,)`` [deg], any real (taken modulo 360).

        Returns:
            ``(M, K, 6)`` complex [m/m, rad/m].

        Raises:
            SeaStateError: a heading outside a non-periodic table's range.
        """
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        h = np.atleast_1d(np.asarray(heading_deg, dtype=float))
        i0, i1, wh = self._heading_weights(h)
        v = self.values
        vh = v[:, i0, :] * (1.0 - wh)[None, :, None] + v[:, i1, :] * wh[None, :, None]
        grid = self.omega
        j = np.clip(np.searchsorted(grid, w, side="right") - 1, 0, grid.size - 2)
        s = ((w - grid[j]) / (grid[j + 1] - grid[j]))[:, None, None]
        out = vh[j] * (1.0 - s) + vh[j + 1] * s
        out[(w < grid[0]) | (w > grid[-1])] = 0.0
        return out


def _file_error(source, line, column, text, name=None):
    where = f"{source}, line {line}" + (f", column {column}" if column else "")
    return SeaStateError(f"{where}: {text}", name=name or column, path=source, line=line,
                         column=column)


def _decode(data: bytes, source: str) -> str:
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        start = data.rfind(b"\n", 0, exc.start) + 1
        line = data.count(b"\n", 0, exc.start) + 1
        col = data.count(b",", start, exc.start)
        column = RAO_COLUMNS[col] if col < len(RAO_COLUMNS) else f"{col + 1}"
        raise _file_error(source, line, column,
                          f"byte 0x{data[exc.start]:02x} is not UTF-8 text: save the file "
                          "as UTF-8 (plain ASCII numbers and DOF names)") from None


def _parse_raos(data: bytes, source: str) -> RAOTable:
    """Parse and validate a RAO CSV (see :func:`load_raos`)."""
    import csv

    lines = _decode(data, source).splitlines()
    rows = [(n + 1, cells) for n, cells in enumerate(csv.reader(lines)) if
            any(c.strip() for c in cells)]
    if not rows:
        raise _file_error(source, 1, None, "the file is empty: write the header "
                          f"{','.join(RAO_COLUMNS)} and one row per omega, heading, dof")
    line0, header = rows[0]
    if tuple(c.strip() for c in header) != RAO_COLUMNS:
        raise _file_error(source, line0, None, f"header {','.join(header)!r} must be "
                          f"{','.join(RAO_COLUMNS)}")
    if len(rows) == 1:
        raise _file_error(source, line0, None, "the header has no data rows under it: "
                          "write one row per omega, heading and dof")
    numeric = (0, 1, 3, 4)
    values = np.empty((len(rows) - 1, 4))
    dof = np.empty(len(rows) - 1, dtype=int)
    line_of = np.empty(len(rows) - 1, dtype=int)
    for r, (line, cells) in enumerate(rows[1:]):
        line_of[r] = line
        if len(cells) != len(RAO_COLUMNS):
            raise _file_error(source, line, None, f"{len(cells)} cells, expected "
                              f"{len(RAO_COLUMNS)} ({','.join(RAO_COLUMNS)})")
        for k, j in enumerate(numeric):
            cell = cells[j].strip()
            try:
                x = float(cell)
            except ValueError:
                raise _file_error(source, line, RAO_COLUMNS[j], f"{cell!r} is not a number: "
                                  "write a decimal number") from None
            if not math.isfinite(x):
                raise _file_error(source, line, RAO_COLUMNS[j], f"{cell!r} is not finite: "
                                  "give a finite number")
            values[r, k] = x
        name = cells[2].strip().lower()
        if name not in DOFS:
            raise _file_error(source, line, "dof", f"unknown dof {cells[2].strip()!r}: use "
                              f"one of {', '.join(DOFS)}")
        dof[r] = DOFS.index(name)
    omega, heading, amplitude, phase = values.T
    checks = ((omega, "omega_rad_s", "must be >= 0 [rad/s]"),
              (amplitude, "amplitude", "is negative: amplitudes are magnitudes (>= 0); put "
               "the sign in the phase (+pi)"))
    for column_values, column, text in checks:
        bad = column_values < 0.0
        if bad.any():
            r = int(np.argmax(bad))
            raise _file_error(source, int(line_of[r]), column,
                              f"{float(column_values[r])!r} {text}")
    heading = np.mod(heading, 360.0)
    seen: dict = {}
    last: dict = {}
    for r in range(len(dof)):
        key = (omega[r], heading[r], dof[r])
        if key in seen:
            raise _file_error(source, int(line_of[r]), None,
                              f"duplicate row: omega {omega[r]:g} rad/s, heading "
                              f"{heading[r]:g} deg, dof {DOFS[dof[r]]} is already on line "
                              f"{seen[key]} (headings are taken modulo 360): remove one")
        seen[key] = int(line_of[r])
        block = (heading[r], dof[r])
        if block in last and omega[r] < last[block][0]:
            raise _file_error(source, int(line_of[r]), "omega_rad_s",
                              f"omega {omega[r]:g} rad/s does not increase after "
                              f"{last[block][0]:g} on line {last[block][1]} (heading "
                              f"{heading[r]:g} deg, dof {DOFS[dof[r]]}): sort the rows by "
                              "omega within each heading and dof")
        last[block] = (omega[r], int(line_of[r]))
    w_grid = np.unique(omega)
    h_grid = np.unique(heading)
    present = np.zeros((w_grid.size, h_grid.size, 6), dtype=bool)
    iw = np.searchsorted(w_grid, omega)
    ih = np.searchsorted(h_grid, heading)
    present[iw, ih, dof] = True
    missing_dof = [d for d in range(6) if not present[:, :, d].any()]
    if missing_dof:
        raise _file_error(source, int(line_of[-1]), "dof",
                          f"no rows for dof {', '.join(DOFS[d] for d in missing_dof)}: the "
                          f"table needs all six ({', '.join(DOFS)}), zero amplitude where "
                          "there is no response")
    if not present.all():
        a, b, d = (int(x) for x in np.argwhere(~present)[0])
        group = present[a, b].any()
        lines = sorted(int(line_of[r]) for r in np.flatnonzero((iw == a) & (ih == b)))
        if group:
            raise _file_error(source, lines[-1], "dof",
                              f"missing dof {DOFS[d]} for omega {w_grid[a]:g} rad/s, heading "
                              f"{h_grid[b]:g} deg (rows on lines "
                              f"{', '.join(map(str, lines))}): every omega and heading needs "
                              "all six dofs")
        raise _file_error(source, int(line_of[-1]), None,
                          f"no rows for omega {w_grid[a]:g} rad/s at heading {h_grid[b]:g} "
                          "deg: the table must be a full grid of omega x heading x dof")
    if w_grid.size < 2:
        raise _file_error(source, int(line_of[-1]), "omega_rad_s",
                          f"only one frequency ({w_grid[0]:g} rad/s): give at least two to "
                          "interpolate between")
    table = np.zeros((w_grid.size, h_grid.size, 6), dtype=complex)
    table[iw, ih, dof] = amplitude * np.exp(1j * phase)
    for array in (w_grid, h_grid, table):
        array.setflags(write=False)          # packaged tables are shared (cached)
    return RAOTable(w_grid, h_grid, table, source)


def load_raos(path) -> RAOTable:
    """Read a vessel's RAO table from a long-form CSV file.

    Format: UTF-8 text, header ``omega_rad_s,heading_deg,dof,amplitude,phase_rad``, one
    row per (frequency [rad/s], heading [deg], dof); ``dof`` one of :data:`DOFS`;
    ``amplitude`` >= 0 in m/m (surge, sway, heave) or rad/m (roll, pitch, yaw);
    ``phase_rad`` the phase lead (response ``amplitude · a cos(ωt + ε + phase)`` to the
    wave ``a cos(ωt + ε)`` at the table's reference point). Vessel axes x forward, y
    port, z up; roll positive starboard down, pitch bow down, yaw bow to port; heading
    180 = head seas, 90 = waves from starboard (taken modulo 360). The rows must form a
    full grid of frequencies × headings × the six dofs, with frequencies increasing (in
    file order) within each heading and dof, no duplicate; blank lines are ignored.

    Args:
        path: The CSV file (str or path-like).

    Returns:
        :class:`RAOTable`.

    Raises:
        SeaStateError: unreadable file, non-UTF-8 bytes, bad header, a non-numeric or
            non-finite cell, an unknown dof, a negative frequency or amplitude, a
            duplicate row, frequencies not increasing, a missing dof or grid point; the
            message starts with ``file, line N, column C``.
    """
    try:
        p = Path(os.fspath(path))
    except TypeError:
        raise SeaStateError(f"RAO table path must be a file name, got {path!r}",
                            name="vessel") from None
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise SeaStateError(f"{p}: cannot read the RAO table ({exc.strerror}): give an "
                            f"existing CSV file or one of {', '.join(VESSELS)}",
                            name="vessel", path=str(p)) from None
    return _parse_raos(data, str(p))


@lru_cache(maxsize=len(VESSELS))
@lru_cache(maxsize=None)
def _packaged(name: str) -> RAOTable:
    from importlib import resources

    ref = resources.files("offshore_crane.motion").joinpath("data", "vessels", VESSELS[name])
    return _parse_raos(ref.read_bytes(), f"offshore_crane/motion/data/vessels/{VESSELS[name]}")


def vessel_raos(vessel="supply") -> RAOTable:
    """The RAO table of a packaged vessel (:data:`VESSELS`), a CSV path, or a table.

    Raises:
        SeaStateError: an unknown name that is not a file, or any :func:`load_raos` error.
    """
    if isinstance(vessel, RAOTable):
        return vessel
    if isinstance(vessel, str) and vessel in VESSELS:
        return _packaged(vessel)
    try:
        is_file = Path(os.fspath(vessel)).is_file()
    except TypeError:
        is_file = False
    if not is_file:
        raise SeaStateError(f"unknown vessel {vessel!r}: use one of {', '.join(VESSELS)} or "
                            "the path of a RAO CSV file", name="vessel")
    return load_raos(vessel)
