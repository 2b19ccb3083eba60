"""A sampled trajectory (:class:`Trajectory`), Hermite interpolation between its samples, and
:func:`load`, which builds one from Table 1 or a CSV file.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from offshore_crane.errors import TrajectoryError
from offshore_crane.motion.trajectories.differences import FD_ORDERS, finite_difference
from offshore_crane.motion.trajectories.files import read_csv
from offshore_crane.motion.trajectories.paper import DEFAULT_RATE, TABLE1_PERIOD, table1, time_grid


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

    def reference(self, t, threads: int = 1) -> tuple:
        """The motion at any times ``t`` ``(n,)`` within the record: ``(q, qd, qdd)``
        ``(n, 9)`` each. Analytic where the trajectory has a source; otherwise the cubic
        Hermite interpolant of the samples' positions and rates (C¹; its acceleration is
        the interpolant's second derivative, linear between samples), which a simulator
        evaluates at its integration stages. ``threads`` go to a source whose call takes
        them (a sea motion's FFT); the same numbers in any count."""
        if self.source is not None:
            t = np.asarray(t, dtype=float)
            if threads != 1 and _takes_threads(self.source):
                return self.source(t, threads=threads)
            return self.source(t)
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


def _takes_threads(source) -> bool:
    """Whether ``source``'s call takes a ``threads`` keyword."""
    import inspect

    try:
        return "threads" in inspect.signature(source).parameters
    except (TypeError, ValueError):       # no signature to read (a builtin): it does not
        return False


def hermite(tk, qk, qdk, t) -> tuple:
    """Cubic Hermite interpolation of samples ``(tk (N,), qk (N, m), qdk (N, m))`` at
    times ``t`` ``(n,)`` (within ``[tk[0], tk[-1]]``): ``(q, qd, qdd)`` ``(n, m)``.

    Compiled (:func:`_cubic_rows`, one pass over the rows): a simulation's reference at
    its 2 n + 1 stage times took 22 ms in NumPy for 20 s at 1 ms (some 30 passes over
    arrays of (n, 9), most of the elastic lift's set-up), 1.6 ms compiled (measured,
    2026-11-28); each number the NumPy expression's bit for bit (the same operations in
    the same order, no fast-math flag).

    Raises:
        TrajectoryError: a time outside the samples' span.
    """
    t = np.ascontiguousarray(t, dtype=float).reshape(-1)
    if t.size and (t.min() < tk[0] - 1e-12 * max(1.0, abs(tk[0]))
                   or t.max() > tk[-1] + 1e-12 * max(1.0, abs(tk[-1]))):
        raise TrajectoryError(f"times {t.min():.6g}..{t.max():.6g} s reach outside the "
                              f"trajectory's {tk[0]:.6g}..{tk[-1]:.6g} s", name="t")
    tk = np.ascontiguousarray(tk, dtype=float)
    qk, qdk = (np.ascontiguousarray(x, dtype=float) for x in (qk, qdk))
    i = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 2).astype(np.int64)
    out = tuple(np.empty((t.shape[0], qk.shape[1])) for _ in range(3))
    _compiled_cubic()(tk, qk, qdk, t, i, *out)
    return out


def _cubic_rows(tk, qk, qdk, t, i, q, dq, ddq):
    """:func:`hermite`'s rows: at ``t[k]`` in interval ``i[k]``, ``q, dq, ddq`` ``(n, m)``
    (filled) from the end samples' positions and rates scaled by the interval ``h``."""
    for k in range(t.shape[0]):
        j = i[k]
        h = tk[j + 1] - tk[j]
        s = (t[k] - tk[j]) / h
        s2, s3 = s * s, s * s * s
        for c in range(qk.shape[1]):
            p0, p1, m0, m1 = qk[j, c], qk[j + 1, c], qdk[j, c] * h, qdk[j + 1, c] * h
            q[k, c] = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + \
                (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1
            dq[k, c] = ((6 * s2 - 6 * s) * p0 + (3 * s2 - 4 * s + 1) * m0
                        + (-6 * s2 + 6 * s) * p1 + (3 * s2 - 2 * s) * m1) / h
            ddq[k, c] = ((12 * s - 6) * p0 + (6 * s - 4) * m0 + (-12 * s + 6) * p1
                         + (6 * s - 2) * m1) / (h * h)


_CUBIC: list = []


def _compiled_cubic():
    """:func:`_cubic_rows` compiled (on first use; cached on disk)."""
    if not _CUBIC:
        from offshore_crane.kernel_cache import JIT, njit

        _CUBIC.append(njit(**JIT)(_cubic_rows))
    return _CUBIC[0]


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
    if fd_order not in FD_ORDERS:
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
