"""Joint-space trajectories of the 9-DOF crane: the paper's Table 1, CSV files, finite differences.

A trajectory is sampled on a time axis ``t`` ``(N,)`` [s] and gives the generalized
coordinates ``q`` ``(N, 9)`` with their first and second time derivatives ``qd`` and
``qdd``. Units are SI: ``q1, q2, q3, q9`` in [m] (``qd`` [m/s], ``qdd`` [m/s²]) and
``q4 .. q8`` in [rad] (``qd`` [rad/s], ``qdd`` [rad/s²]).

Sources:

* :func:`table1` evaluates the paper's Table 1 (sums of cosines) with analytic derivatives.
* :func:`read_csv` / :func:`write_csv` read and write ``t_s,q1,...,q9`` CSV files; the
  derivatives of a CSV trajectory come from :func:`finite_difference`.
* :func:`load` builds a :class:`Trajectory` from either.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from offshore_crane.errors import TrajectoryError
from offshore_crane.validation import uniform_step

__all__ = [
    "TABLE1_PERIOD",
    "DEFAULT_RATE",
    "CSV_COLUMNS",
    "time_grid",
    "table1",
    "finite_difference",
    "read_csv",
    "write_csv",
    "Trajectory",
    "load",
]

#: Period of the slowest Table 1 components (q4, q5, q6, q9 at 0.2 rad/s) [s]. Over it
#: q1..q3 make two cycles but q7, q8 (0.5 rad/s) make 2.5 and end with the opposite sign;
#: the whole table repeats only after 2 * TABLE1_PERIOD = 20 pi s.
TABLE1_PERIOD = 10.0 * math.pi
#: Default sampling rate of :func:`time_grid` [Hz].
DEFAULT_RATE = 100.0
#: Header of a trajectory CSV file: time [s] then q1..q9 [m or rad].
CSV_COLUMNS = ("t_s",) + tuple(f"q{i}" for i in range(1, 10))
#: The same with the rates and accelerations (written by ``offshore-crane motion``):
#: ``qd1..qd9`` [m/s or rad/s] and ``qdd1..qdd9`` [m/s² or rad/s²], used instead of finite
#: differences when present.
CSV_COLUMNS_DERIVATIVES = CSV_COLUMNS + tuple(f"qd{i}" for i in range(1, 10)) + tuple(
    f"qdd{i}" for i in range(1, 10))
#: Largest number of samples :func:`time_grid` accepts (about 7 GB for t, q, qd, qdd).
MAX_SAMPLES = 10**8

# Table 1 as q_j(t) = offset_j + amplitude_j * cos(omega_j * t + phase_j), j = 1..9.
_TABLE1_OFFSET = np.array([0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])  # [m or rad]
_TABLE1_AMPLITUDE = np.array([0.03, 0.02, 0.035, math.pi / 9, math.pi / 9, math.pi / 9,
                              math.pi, math.pi / 3, 0.15])  # [m or rad]
_TABLE1_OMEGA = np.array([0.4, 0.4, 0.4, 0.2, 0.2, 0.2, 0.5, 0.5, 0.2])  # [rad/s]
_TABLE1_PHASE = np.array([0.0, 0.5, 0.0, 0.2, 0.3, 0.4, 0.0, 0.0, math.pi / 2])  # [rad]

_FD_ORDERS = (2, 4, 6)


def _positive_finite(value, name: str, unit: str, hint: str) -> float:
    """Return ``value`` as a float, or raise TrajectoryError if it is not finite and > 0."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise TrajectoryError(
            f"{name} must be a positive number [{unit}], got {value!r}: {hint}.", name=name
        ) from None
    if not (math.isfinite(x) and x > 0.0):
        raise TrajectoryError(
            f"{name} must be positive and finite [{unit}], got {x!r}: {hint}.", name=name)
    return x


def time_grid(duration: float = TABLE1_PERIOD, rate: float = DEFAULT_RATE) -> np.ndarray:
    """Uniform time axis ``t = arange(N) / rate`` starting at 0.

    ``N = floor(duration * rate + 1e-9) + 1``, so both ends are included when
    ``duration * rate`` is an integer; otherwise the last sample is the last one before
    ``duration``. The defaults give 3142 samples from 0 to 31.41 s.

    Args:
        duration: Length of the time span [s], > 0.
        rate: Sampling rate [Hz], > 0.

    Returns:
        ``t`` ``(N,)`` [s].

    Raises:
        TrajectoryError: ``duration`` or ``rate`` not positive and finite, or more than
            ``MAX_SAMPLES`` samples.
    """
    duration = _positive_finite(duration, "duration", "s", "give the length of the trajectory")
    rate = _positive_finite(rate, "rate", "Hz", "give the sampling rate")
    steps = duration * rate + 1e-9
    if steps >= MAX_SAMPLES:
        raise TrajectoryError(
            f"duration={duration!r} s at rate={rate!r} Hz gives about {steps:.3g} samples, "
            f"more than the limit {MAX_SAMPLES}: shorten the duration or lower the rate.",
            name="rate",
        )
    n = math.floor(steps) + 1
    return np.arange(n) / rate


def table1(t):
    """The paper's Table 1 trajectory and its analytic first and second derivatives.

    ``q_j(t) = c_j + a_j cos(w_j t + p_j)``, ``qd_j = -a_j w_j sin(w_j t + p_j)``,
    ``qdd_j = -a_j w_j² cos(w_j t + p_j)``, with (t in [s])::

        q1 = 0.03 cos(0.4t)               q6 = (pi/9) cos(0.2t + 0.4)
        q2 = 0.02 cos(0.4t + 0.5)         q7 = pi cos(0.5t)
        q3 = 0.5 + 0.035 cos(0.4t)        q8 = (pi/3) cos(0.5t)
        q4 = (pi/9) cos(0.2t + 0.2)       q9 = 0.15 cos(0.2t + pi/2)
        q5 = (pi/9) cos(0.2t + 0.3)

    Args:
        t: Time [s], scalar or ``(N,)``.

    Returns:
        ``(q, qd, qdd)``, each ``(9,)`` for a scalar ``t`` or ``(N, 9)`` for ``t`` ``(N,)``,
        in [m or rad], [m/s or rad/s], [m/s² or rad/s²].

    Raises:
        TrajectoryError: ``t`` is not numeric, has more than one axis, or holds a NaN or
            infinity (``index`` is the first such sample, None for a scalar).
    """
    try:
        t = np.asarray(t, dtype=float)
    except (TypeError, ValueError):
        raise TrajectoryError(
            f"t must be a number or a 1-D array of times [s], got {t!r}.", name="t") from None
    if t.ndim > 1:
        raise TrajectoryError(
            f"t must be a scalar or a 1-D array of times [s], got shape {t.shape}: "
            "flatten it first.", name="t")
    finite = np.isfinite(t)
    if not finite.all():
        index = None if t.ndim == 0 else int(np.argmin(finite))
        value = float(t.item() if t.ndim == 0 else t[index])
        where = "" if index is None else f" at sample {index}"
        raise TrajectoryError(
            f"t is not finite{where} (t = {value!r}): give finite times [s].",
            name="t", index=index)
    phase = np.multiply.outer(t, _TABLE1_OMEGA) + _TABLE1_PHASE  # (..., 9) [rad]
    cos = np.cos(phase)
    q = _TABLE1_OFFSET + _TABLE1_AMPLITUDE * cos
    qd = -(_TABLE1_AMPLITUDE * _TABLE1_OMEGA) * np.sin(phase)
    qdd = -(_TABLE1_AMPLITUDE * _TABLE1_OMEGA**2) * cos
    return q, qd, qdd


@lru_cache(maxsize=64)
def _stencil_weights(offsets: tuple, deriv: int) -> tuple:
    """Finite-difference weights of the ``deriv``-th derivative on integer ``offsets``.

    Solves the Vandermonde system ``sum_j w_j s_j**k = deriv! * (k == deriv)`` for
    ``k = 0 .. M-1`` exactly in rational arithmetic (Gauss-Jordan elimination), so the
    weights are correctly rounded and annihilate constants to round-off. Divide by
    ``h**deriv`` to use them on a grid of step ``h``.

    Args:
        offsets: ``M`` distinct integer offsets, in units of the grid step.
        deriv: Order of the derivative, ``0 <= deriv < M``.

    Returns:
        ``M`` float weights, in the order of ``offsets``.
    """
    from fractions import Fraction  # imported here: only needed when differentiating

    m = len(offsets)
    rhs = [Fraction(math.factorial(deriv) if k == deriv else 0) for k in range(m)]
    a = [[Fraction(s) ** k for s in offsets] + [rhs[k]] for k in range(m)]  # augmented
    for col in range(m):
        pivot = next(r for r in range(col, m) if a[r][col] != 0)
        a[col], a[pivot] = a[pivot], a[col]
        inv = 1 / a[col][col]
        a[col] = [x * inv for x in a[col]]
        for r in range(m):
            if r != col and a[r][col] != 0:
                f = a[r][col]
                a[r] = [x - f * y for x, y in zip(a[r], a[col])]
    return tuple(float(a[r][m]) for r in range(m))


def _check_time_axis(t: np.ndarray, what: str) -> None:
    """Raise TrajectoryError unless ``t`` is finite and strictly increasing."""
    finite = np.isfinite(t)
    if not finite.all():
        k = int(np.argmin(finite))
        raise TrajectoryError(
            f"{what}: t[{k}] = {float(t[k])!r} is not finite: give finite times [s].",
            name="t", index=k)
    dt = np.diff(t)
    bad = dt <= 0.0
    if bad.any():
        k = int(np.argmax(bad)) + 1
        raise TrajectoryError(
            f"{what}: time is not strictly increasing at sample {k} "
            f"(t[{k - 1}] = {float(t[k - 1])!r} s, t[{k}] = {float(t[k])!r} s): sort the "
            "samples and remove duplicates.", name="t", index=k)


def finite_difference(t, q, order: int = 4):
    """First and second time derivatives of sampled data by finite differences.

    Interior samples use the central stencil of ``order + 1`` points (offsets
    ``-order/2 .. order/2``). The ``order/2`` samples at each end, where that stencil does
    not fit, use one-sided stencils on the first (last) ``order + 1`` samples for ``qd`` and
    ``order + 2`` samples for ``qdd``, so every sample has a truncation error of
    ``O(h**order)``. Weights come from a Vandermonde solve (as in Fornberg's method),
    computed once per stencil shape.

    Args:
        t: ``(N,)`` time [s]; strictly increasing and uniform (every step within
            ``1e-6`` of the mean step, relative).
        q: ``(N,)`` or ``(N, m)`` samples [any unit u].
        order: Order of accuracy, 2, 4 or 6.

    Returns:
        ``(qd, qdd)``, both of the shape of ``q``, in [u/s] and [u/s²].

    Raises:
        TrajectoryError: bad ``order``; ``t`` not 1-D, not finite, not strictly increasing
            or not uniform (``index`` names the first offending sample or step); ``q`` of
            the wrong shape or not finite; fewer than ``order + 2`` samples.
    """
    if isinstance(order, bool) or order not in _FD_ORDERS:
        raise TrajectoryError(
            f"finite-difference order must be one of {_FD_ORDERS}, got {order!r}.", name="order")
    t = np.asarray(t, dtype=float)
    q = np.asarray(q, dtype=float)
    if t.ndim != 1:
        raise TrajectoryError(f"t must be 1-D (N,), got shape {t.shape}.", name="t")
    n = t.shape[0]
    if q.ndim not in (1, 2) or q.shape[0] != n:
        raise TrajectoryError(
            f"q must have shape ({n},) or ({n}, m) to match t, got {q.shape}.", name="q")
    need = order + 2
    if n < need:
        raise TrajectoryError(
            f"finite differences of order {order} need at least {need} samples, got {n}: "
            "give a longer trajectory or a lower order.", name="t")
    _check_time_axis(t, "finite_difference")
    finite = np.isfinite(q)
    if not finite.all():
        k = int(np.argmin(finite.reshape(n, -1).all(axis=1)))
        raise TrajectoryError(
            f"q is not finite at sample {k}: give finite samples.", name="q", index=k)

    h = uniform_step(t, "the trajectory")  # mean step [s]

    half = order // 2
    derivatives = []
    for deriv, width in ((1, order + 1), (2, order + 2)):
        out = np.empty_like(q)
        # Interior: central stencil, one shifted slice per tap.
        central = tuple(range(-half, half + 1))
        acc = np.zeros_like(q[half:n - half])
        for s, w in zip(central, _stencil_weights(central, deriv)):
            acc += w * q[half + s:n - half + s]
        out[half:n - half] = acc
        # Ends: one-sided stencils on the first / last `width` samples, as small matrices.
        left = np.array([_stencil_weights(tuple(range(-i, width - i)), deriv)
                         for i in range(half)])  # (half, width)
        right = np.array([_stencil_weights(tuple(range(-(width - 1 - i), i + 1)), deriv)
                          for i in range(half - 1, -1, -1)])  # rows: samples n-half .. n-1
        out[:half] = np.tensordot(left, q[:width], axes=1)
        out[n - half:] = np.tensordot(right, q[n - width:], axes=1)
        derivatives.append(out / h**deriv)
    return derivatives[0], derivatives[1]


def read_csv(path, derivatives: bool = False):
    """Read a trajectory CSV file with header ``t_s,q1,q2,q3,q4,q5,q6,q7,q8,q9``, optionally
    followed by ``qd1..qd9,qdd1..qdd9``.

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

    header = [cell.strip() for cell in rows[0]]
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


@dataclass(frozen=True, eq=False)
class Trajectory:
    """A sampled joint-space trajectory.

    Attributes:
        name: Where it came from: ``"table1"`` or the CSV file's stem.
        t: ``(N,)`` time [s].
        q: ``(N, 9)`` generalized coordinates [m or rad].
        qd: ``(N, 9)`` first derivatives [m/s or rad/s].
        qdd: ``(N, 9)`` second derivatives [m/s² or rad/s²].
        source: The analytic motion it samples, ``source(t (n,)) -> (q, qd, qdd)``, when
            there is one (Table 1, sea states, crane operations), else None.
    """

    name: str
    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    source: object = None

    def reference(self, t) -> tuple:
        """The motion at any times ``t`` ``(n,)`` within the record: ``(q, qd, qdd)``
        ``(n, 9)`` each. Analytic where the trajectory has a source; otherwise the cubic
        Hermite interpolant of the samples' positions and rates (C¹; its acceleration is
        the interpolant's second derivative, linear between samples), which a simulator
        evaluates at its integration stages."""
        if self.source is not None:
            return self.source(np.asarray(t, dtype=float))
        return hermite(self.t, self.q, self.qd, t)

    def __post_init__(self):
        n = np.shape(self.t)[0] if np.ndim(self.t) == 1 else None
        if n is None:
            raise TrajectoryError(f"Trajectory.t must be 1-D (N,), got shape {np.shape(self.t)}.",
                                  name="t")
        for field in ("q", "qd", "qdd"):
            if np.shape(getattr(self, field)) != (n, 9):
                raise TrajectoryError(
                    f"Trajectory.{field} must have shape ({n}, 9), got "
                    f"{np.shape(getattr(self, field))}.", name=field)

    def __len__(self) -> int:
        """Number of time samples ``N``."""
        return int(self.t.shape[0])


def hermite(tk, qk, qdk, t) -> tuple:
    """Cubic Hermite interpolation of samples ``(tk (N,), qk (N, m), qdk (N, m))`` at
    times ``t`` ``(n,)`` (within ``[tk[0], tk[-1]]``): ``(q, qd, qdd)`` ``(n, m)``.

    Raises:
        TrajectoryError: a time outside the samples' span.
    """
    t = np.asarray(t, dtype=float)
    if t.size and (t.min() < tk[0] - 1e-12 * max(1.0, abs(tk[0]))
                   or t.max() > tk[-1] + 1e-12 * max(1.0, abs(tk[-1]))):
        raise TrajectoryError(f"times {t.min():.6g}..{t.max():.6g} s reach outside the "
                              f"trajectory's {tk[0]:.6g}..{tk[-1]:.6g} s", name="t")
    i = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 2)
    h = (tk[i + 1] - tk[i])[:, None]
    s = ((t - tk[i])[:, None]) / h
    p0, p1, m0, m1 = qk[i], qk[i + 1], qdk[i] * h, qdk[i + 1] * h
    s2, s3 = s * s, s * s * s
    q = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + \
        (s3 - s2) * m1
    dq = ((6 * s2 - 6 * s) * p0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * p1
          + (3 * s2 - 2 * s) * m1) / h
    ddq = ((12 * s - 6) * p0 + (6 * s - 4) * m0 + (-12 * s + 6) * p1 + (6 * s - 2) * m1) / h**2
    return q, dq, ddq


def load(spec="table1", duration=None, rate=None, fd_order: int = 4) -> Trajectory:
    """Build a :class:`Trajectory` from ``"table1"`` or a CSV file.

    Args:
        spec: ``"table1"`` for the paper's Table 1 (analytic derivatives), or the path of
            a CSV file ``t_s,q1..q9`` (derivatives by :func:`finite_difference`).
        duration: Table 1 only: length [s]; default :data:`TABLE1_PERIOD`.
        rate: Table 1 only: sampling rate [Hz]; default :data:`DEFAULT_RATE`.
        fd_order: CSV only: finite-difference order of accuracy (2, 4 or 6).

    Returns:
        The trajectory.

    Raises:
        TrajectoryError: unknown ``spec``; ``duration`` / ``rate`` given with a CSV file;
            any error of :func:`time_grid`, :func:`read_csv` or :func:`finite_difference`.
    """
    if fd_order not in _FD_ORDERS:
        raise TrajectoryError(f"fd_order = {fd_order!r}: use 2, 4 or 6", name="fd_order")
    if isinstance(spec, str) and spec == "table1":
        t = time_grid(TABLE1_PERIOD if duration is None else duration,
                      DEFAULT_RATE if rate is None else rate)
        q, qd, qdd = table1(t)
        return Trajectory("table1", t, q, qd, qdd, source=table1)
    try:
        path = Path(os.fspath(spec))
    except TypeError:
        path = None
    if path is None or not path.is_file():
        raise TrajectoryError(
            f"unknown trajectory '{spec}': use 'table1' or the path of a CSV file with "
            "columns t_s,q1..q9", name="spec")
    if duration is not None or rate is not None:
        raise TrajectoryError(
            f"duration and rate (--duration, --rate) apply to table1 only, not to the CSV "
            f"file '{path}', whose samples set the time axis: leave them out",
            name="duration" if duration is not None else "rate")
    t, q, qd, qdd = read_csv(path, derivatives=True)
    if qd is None:
        qd, qdd = finite_difference(t, q, order=fd_order)
    return Trajectory(path.stem, t, q, qd, qdd)
