"""Identification from a record: the base parameters by weighted least squares, computed
from an orthogonal factorisation of the weighted regressor (never from normal equations).

``X_k = Y_b,k β + e_k`` per actuator k; ordinary least squares first, each actuator's
noise variance from its residuals ``σ_k² = |e_k|² / (N − n/9)`` (n the parameters the
record excites, the degrees of freedom shared across the 9 equations), then weighted
least squares with weights ``1/σ_k`` (Gautier & Poignet, "Extended Kalman filtering and
weighted least squares dynamic identification of robot", Control Engineering Practice
9(12), 2001).

The record enters as each actuator's triangle, the R of a QR of ``[Y_b,k | X_k]``
updated block by block (:class:`Triangles`: memory is a block's, whatever the record's
length). Each solve stacks the triangles weighted, scales the columns to unit norm
(``D``: the column norms are the triangles'), takes the R of a QR of that ``[W D⁻¹ | y]``
up to an orthogonal factor (its last column gives ``Qᵀ y`` without forming Q), then the
SVD of the small triangle ``R = U S Vᵀ``. The record excites the directions whose
singular values exceed :data:`~._base.RANK_TOLERANCE` times the largest; along them
``β̂ = D⁻¹ V S⁻¹ Uᵀ Qᵀ y`` (none along the others), the information matrix's square root
is ``S Vᵀ D`` and the covariance of β̂ ``D⁻¹ V S⁻² Vᵀ D⁻¹``: positive semi-definite by
construction, and nothing is ever squared, so a record with condition number 10⁸ loses
8 digits, not 16.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from offshore_crane.dynamics.runtime import one_blas_thread

#: The weights' noise is at least this share of the largest actuator's RMS force: below
#: it a residual is round-off (an exact log's is ~1e-13), and weights that differ by more
#: would only make the consistent lift's problem needlessly stiff. The σ of an exact log
#: are therefore upper bounds.
NOISE_FLOOR = 1e-9
#: And at least this [N, N·m] (a log of zero forces: no sensor resolves less).
FLOOR = 1e-12
#: A regressor column whose norm is below this share of the largest is round-off (e.g.
#: an inertia's column in a log standing still, its filtered rates ~1e-17): set to 0,
#: not scaled up to unit norm like the others.
NEGLIGIBLE = 1e-10
#: A base parameter is determined by a record when its unit vector lies in the span the
#: record excites to this (the norm of what is left, in column-scaled coordinates).
DETERMINED = 1e-6


class Fit(NamedTuple):
    """Identified base parameters.

    Attributes:
        beta: ``(r,)`` the estimates (0 along the directions the record does not excite).
        sigma: ``(r,)`` their standard deviations (``inf`` where the record does not
            determine the parameter: it has a share in an unexcited direction).
        noise: ``(m,)`` each actuator's estimated noise standard deviation [N, N·m].
        residual: ``(N, m)`` X minus the fitted forces [N, N·m] (:func:`fit_base`), or
            None when the record was fitted block by block (:class:`Triangles`: only
            ``rms`` is kept).
        condition: The weighted base regressor's condition number, columns scaled to
            unit norm (``inf`` when the record does not excite every base parameter).
        covariance: ``(r, r)`` of β̂ along the excited directions (the pseudo-inverse of
            the information matrix: 0 along the others, where ``sigma`` is ``inf``).
        root: ``(n, r)`` the information matrix's square root: ``rootᵀ root = W_wᵀ W_w``
            (the weighted regressor's), so ``|root (β − β̂)|`` is the misfit of any β in
            standard deviations, with no covariance to invert.
        excited: n, the number of independent directions the record excites (≤ r).
        determined: ``(r,)`` bool: the record determines this base parameter (its
            ``sigma`` is finite).
        rms: ``(m,)`` each actuator's residual RMS [N, N·m].
    """

    beta: np.ndarray
    sigma: np.ndarray
    noise: np.ndarray
    residual: np.ndarray | None
    condition: float
    covariance: np.ndarray
    root: np.ndarray
    excited: int
    determined: np.ndarray
    rms: np.ndarray


class Triangles:
    """A record's least-squares data, accumulated block by block: per actuator k the
    triangle ``T_k`` of a QR of ``[Y_b,k | X_k]`` over every sample added so far (a QR
    of stacked blocks is updated as the R of ``[T_k; block]``), so that memory is one
    block's whatever the record's length. Weighting an actuator's rows by ``w_k``
    weights its triangle alike, and column norms and residual norms are the triangles'
    (``[Y_b,k | X_k] = Q_k T_k``, Q_k orthonormal): the weighted fit needs nothing else.

    Args:
        r: base parameters (the regressor's columns). m: actuators (rows a sample).
    """

    def __init__(self, r: int, m: int = 9):
        self.r, self.m = int(r), int(m)
        self.T = [np.zeros((0, self.r + 1)) for _ in range(self.m)]
        self.samples = 0
        self.forces = False

    def add(self, Yb: np.ndarray, X: np.ndarray) -> None:
        """Add ``n`` samples: ``Yb (n, m, r)`` and ``X (n, m)`` [N·m, N].

        Raises:
            InputError: shapes that do not agree; non-finite values (naming the sample,
                counted from the first block).
        """
        from offshore_crane.errors import InputError

        n = len(Yb)
        if Yb.shape[1:] != (self.m, self.r) or X.shape != (n, self.m):
            raise InputError(f"fit: X has shape {X.shape}; the regressor {Yb.shape} wants "
                             f"({n}, {self.m})", name="X")
        for name, a in (("X", X), ("regressor", Yb)):
            bad = np.argwhere(~np.isfinite(a))
            if len(bad):
                raise InputError(f"fit: {name} at sample {self.samples + bad[0][0]} is not "
                                 "finite: give a record of finite numbers", name=name)
        for k in range(self.m):
            block = np.column_stack([Yb[:, k, :], X[:, k]])
            self.T[k] = np.linalg.qr(np.vstack([self.T[k], block]), mode="r")
        self.samples += n
        self.forces = self.forces or bool(np.any(X))

    def residual_norms(self, beta: np.ndarray) -> np.ndarray:
        """``(m,)`` ``|X_k − Y_b,k β|`` [N·m, N] over every sample added."""
        v = np.append(beta, -1.0)
        return np.array([np.linalg.norm(T @ v) for T in self.T])

    @one_blas_thread()
    def fit(self) -> Fit:
        """Weighted least squares on what was added (see :func:`fit_base`); the
        :class:`Fit`'s ``residual`` is None (``rms`` has each actuator's).

        Raises:
            InputError: fewer equations than parameters; forces all zero; a record that
                excites no base parameter at all.
        """
        from offshore_crane.errors import InputError

        N, m, r = self.samples, self.m, self.r
        if N * m <= r:
            raise InputError(f"fit: {N * m} equations for {r} base parameters: give a "
                             "longer record", name="X")
        if not self.forces:
            raise InputError("fit: every force of the record is 0 (under gravity the "
                             "actuators always carry the robot): check the log's force "
                             "columns", name="X")
        first = _solve(self.T, np.ones(m))
        if first.rank == 0:
            raise InputError("fit: the record excites none of the base parameters (no "
                             "force depends on them): log a moving robot, e.g. an "
                             "excitation trajectory (offshore-crane excite)", name="X")
        noise = self.residual_norms(first.beta) / np.sqrt(max(N - first.rank / m, 1.0))
        rms_x = np.array([np.linalg.norm(T[:, r]) for T in self.T]) / np.sqrt(N)
        floor = max(NOISE_FLOOR * float(rms_x.max()), FLOOR)
        fit = _solve(self.T, 1.0 / np.maximum(noise, floor))
        return Fit(fit.beta, fit.sigma, noise, None, fit.condition, fit.covariance,
                   fit.root, fit.rank, np.isfinite(fit.sigma),
                   self.residual_norms(fit.beta) / np.sqrt(N))


@one_blas_thread()
def fit_base(Yb: np.ndarray, X: np.ndarray) -> Fit:
    """Weighted least squares of ``X (N, m)`` [N·m, N] on the base regressor ``Yb (N, m,
    r)`` (through :class:`Triangles`). A record that excites only some base parameters
    is fitted along what it excites (:attr:`Fit.determined` says which; ``sigma`` is
    ``inf`` for the others).

    Raises:
        InputError: shapes that do not agree; non-finite values; fewer equations than
            parameters; forces all zero; a record that excites no base parameter at all.
    """
    from offshore_crane.errors import InputError

    if Yb.ndim != 3 or X.shape != Yb.shape[:2]:
        raise InputError(f"fit: X has shape {X.shape}; the regressor {Yb.shape} wants "
                         f"{Yb.shape[:2]}", name="X")
    tri = Triangles(Yb.shape[2], Yb.shape[1])
    tri.add(Yb, X)
    fit = tri.fit()
    return fit._replace(residual=X - Yb @ fit.beta)


class _Solution(NamedTuple):
    beta: np.ndarray
    sigma: np.ndarray
    covariance: np.ndarray
    root: np.ndarray
    rank: int
    condition: float


def _solve(T: list, weights: np.ndarray) -> _Solution:
    """Least squares of ``X * weights`` on ``Yb * weights`` (per actuator) along the
    directions the record excites (see the module docstring), from the actuators'
    triangles ``T`` (:class:`Triangles`): stacked and weighted, they are the weighted
    record's ``[W | y]`` up to an orthogonal factor."""
    from offshore_crane.studies.identification._base import RANK_TOLERANCE

    S = np.vstack([w * Tk for w, Tk in zip(weights, T)])
    r = S.shape[1] - 1
    scale = np.linalg.norm(S[:, :r], axis=0)
    negligible = scale <= NEGLIGIBLE * scale.max()
    S[:, :r][:, negligible] = 0.0                          # round-off: the motion lacks it
    scale = np.where(negligible, 1.0, scale)
    S[:, :r] /= scale
    Ra = np.linalg.qr(S, mode="r")
    U, s, Vt = np.linalg.svd(Ra[:r, :r])
    k = int(np.sum(s > RANK_TOLERANCE * s[0])) if s[0] > 0.0 else 0
    Vk = Vt[:k].T                                              # (r, k), scaled coordinates
    beta = Vk @ ((U[:, :k].T @ Ra[:r, r]) / s[:k]) / scale
    left = 1.0 - np.sum(Vk * Vk, axis=1)                       # |e_j| outside the span, ²
    cov = (Vk / s[:k]) @ (Vk / s[:k]).T / np.outer(scale, scale)
    sigma = np.where(left <= DETERMINED ** 2, np.sqrt(np.clip(np.diag(cov), 0.0, None)),
                     np.inf)
    return _Solution(beta, sigma, cov, s[:k, None] * Vt[:k] * scale[None, :], k,
                     float(s[0] / s[-1]) if k == r else float("inf"))


#: Order of the zero-phase Butterworth filter on a log's positions (applied forward and
#: backward: twice the order, no phase lag).
FILTER_ORDER = 4
#: Samples dropped at each end of a filtered log, in time constants ``1 / (2π cutoff)``
#: of the cut-off (the filter's transients; the log is padded by its odd extension over
#: its whole length). Measured on sines of 0.1-0.8 Hz, cut-offs 2-20 Hz, at 1 kHz: the
#: twice-differentiated filtered position's error, relative to the sine's q̈, is 0.13
#: at 3 time constants, 1.1e-2 at 10, 1.1e-3 at 15 (scipy's default padding: 0.3-16
#: at 3, 2.6e-2-0.12 at 15).
EDGE_TIME_CONSTANTS = 15.0


def log_derivatives(t: np.ndarray, q: np.ndarray, cutoff: float):
    """A log's positions ``q (N, 9)`` at uniform times ``t`` [s] low-passed (zero-phase
    Butterworth of :data:`FILTER_ORDER`, ``cutoff`` [Hz], in second-order sections: the
    transfer function's polynomials lose every digit near the Nyquist frequency, and a
    cut-off of 499.999 Hz at 1 kHz gave positions 30× off) and differentiated twice
    (second-order central differences): ``(keep, q, q̇, q̈)``, ``keep`` the slice of the
    samples away from the ends, where the filter's transients last
    (:data:`EDGE_TIME_CONSTANTS` time constants ``1 / (2π cutoff)``).

    Raises:
        InputError: non-uniform times, a cut-off not below the Nyquist frequency, a log
            shorter than the filter needs.
    """
    import math

    from scipy.signal import butter, sosfiltfilt

    from offshore_crane.errors import InputError

    t, q = np.asarray(t, dtype=float), np.asarray(q, dtype=float)
    dt = np.diff(t)
    if len(t) < 3 or not np.allclose(dt, dt[0], rtol=1e-9, atol=0.0):
        raise InputError("log: the times must be uniform (at least 3 samples)", name="t")
    rate = 1.0 / float(dt[0])
    if not (0.0 < cutoff < rate / 2.0):
        raise InputError(f"cutoff = {cutoff!r} Hz: give a frequency in (0, {rate / 2:g}) "
                         f"Hz, below the log's Nyquist frequency", name="cutoff")
    sos = butter(FILTER_ORDER, cutoff / (rate / 2.0), output="sos")
    edge = int(math.ceil(EDGE_TIME_CONSTANTS * rate / (2.0 * math.pi * cutoff))) + 1
    if len(t) <= 2 * edge + 9:
        raise InputError(f"log: {len(t)} samples; the filter's ends take {edge} at each "
                         "end: give a longer log or a higher cut-off", name="t")
    qf, qd, qdd = (np.empty(q.shape) for _ in range(3))
    for j in range(q.shape[1]):             # a column at a time: its padding is 3 N doubles
        qf[:, j] = sosfiltfilt(sos, q[:, j], padlen=len(t) - 1)
        qd[:, j] = np.gradient(qf[:, j], float(dt[0]))
        qdd[:, j] = np.gradient(qd[:, j], float(dt[0]))
    return slice(edge, len(t) - edge), qf, qd, qdd
