"""Identification from a record: the base parameters by weighted least squares.

``X_k = Y_b,k β + e_k`` per actuator k; ordinary least squares first, each actuator's
noise variance from its residuals ``σ_k² = |e_k|² / (N − r/9)`` (the degrees of freedom
shared across the 9 equations), then weighted least squares with weights ``1/σ_k``; the
covariance of β̂ is ``(W_bᵀ Σ⁻¹ W_b)⁻¹``, its standard deviations the square roots of its
diagonal (Gautier & Poignet, "Extended Kalman filtering and weighted least squares
dynamic identification of robot", Control Engineering Practice 9(12), 2001).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class Fit(NamedTuple):
    """Identified base parameters.

    Attributes:
        beta: ``(r,)`` the estimates. sigma: ``(r,)`` their standard deviations.
        noise: ``(9,)`` each actuator's estimated noise standard deviation [N, N·m].
        residual: ``(N, 9)`` X minus the fitted forces [N, N·m].
        condition: The weighted base regressor's condition number (columns unscaled).
        covariance: ``(r, r)`` of β̂.
    """

    beta: np.ndarray
    sigma: np.ndarray
    noise: np.ndarray
    residual: np.ndarray
    condition: float
    covariance: np.ndarray


def fit_base(Yb: np.ndarray, X: np.ndarray) -> Fit:
    """Weighted least squares of ``X (N, 9)`` on the base regressor ``Yb (N, 9, r)``.

    Raises:
        InputError: shapes that do not agree; fewer equations than parameters; a record
            that does not excite every base parameter (the column-scaled regressor's
            numerical rank below ``r`` at :data:`~._base.RANK_TOLERANCE`, the base
            parameters' own threshold).
    """
    from offshore_crane.errors import InputError
    from offshore_crane.studies.identification._base import RANK_TOLERANCE

    N, m, r = Yb.shape
    if X.shape != (N, m):
        raise InputError(f"fit: X has shape {X.shape}; the regressor {Yb.shape} wants "
                         f"({N}, {m})", name="X")
    if N * m <= r:
        raise InputError(f"fit: {N * m} equations for {r} base parameters: give a longer "
                         "record", name="X")
    W, y = Yb.reshape(-1, r), X.reshape(-1)
    scale = np.linalg.norm(W, axis=0)
    sv = np.linalg.svd(W / np.where(scale > 0.0, scale, 1.0), compute_uv=False)
    rank = int(np.sum(sv > RANK_TOLERANCE * sv[0])) if sv[0] > 0.0 else 0
    if rank < r:
        raise InputError(f"fit: the record excites {rank} of the {r} base parameters (the "
                         "motion does not identify the robot): log an excitation "
                         "trajectory (offshore-crane excite)", name="X")
    beta = np.linalg.lstsq(W, y, rcond=None)[0]
    e = (y - W @ beta).reshape(N, m)
    dof = max(N - r / m, 1.0)
    noise = np.sqrt((e * e).sum(axis=0) / dof)
    floor = max(float(noise.max()), 1e-300) * 1e-12        # an exact actuator: weight 1
    wts = 1.0 / np.maximum(noise, floor)
    Ww = (Yb * wts[None, :, None]).reshape(-1, r)
    beta = np.linalg.lstsq(Ww, (X * wts).reshape(-1), rcond=None)[0]
    residual = X - Yb @ beta
    cov = np.linalg.pinv(Ww.T @ Ww)
    return Fit(beta, np.sqrt(np.clip(np.diag(cov), 0.0, None)), noise, residual,
               float(np.linalg.cond(Ww)), cov)


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
    Butterworth of :data:`FILTER_ORDER`, ``cutoff`` [Hz]) and differentiated twice
    (second-order central differences): ``(keep, q, q̇, q̈)``, ``keep`` the slice of the
    samples away from the ends, where the filter's transients last
    (:data:`EDGE_TIME_CONSTANTS` time constants ``1 / (2π cutoff)``).

    Raises:
        InputError: non-uniform times, a cut-off not below the Nyquist frequency, a log
            shorter than the filter needs.
    """
    import math

    from scipy.signal import butter, filtfilt

    from offshore_crane.errors import InputError

    t, q = np.asarray(t, dtype=float), np.asarray(q, dtype=float)
    dt = np.diff(t)
    if len(t) < 3 or not np.allclose(dt, dt[0], rtol=1e-9, atol=0.0):
        raise InputError("log: the times must be uniform (at least 3 samples)", name="t")
    rate = 1.0 / float(dt[0])
    if not (0.0 < cutoff < rate / 2.0):
        raise InputError(f"cutoff = {cutoff!r} Hz: give a frequency in (0, {rate / 2:g}) "
                         f"Hz, below the log's Nyquist frequency", name="cutoff")
    b, a = butter(FILTER_ORDER, cutoff / (rate / 2.0))
    edge = int(math.ceil(EDGE_TIME_CONSTANTS * rate / (2.0 * math.pi * cutoff))) + 1
    if len(t) <= 2 * edge + 9:
        raise InputError(f"log: {len(t)} samples; the filter's ends take {edge} at each "
                         "end: give a longer log or a higher cut-off", name="t")
    qf = filtfilt(b, a, q, axis=0, padlen=len(t) - 1)
    qd = np.gradient(qf, float(dt[0]), axis=0)
    qdd = np.gradient(qd, float(dt[0]), axis=0)
    return slice(edge, len(t) - edge), qf, qd, qdd
