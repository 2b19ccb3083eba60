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
    """

    beta: np.ndarray
    sigma: np.ndarray
    noise: np.ndarray
    residual: np.ndarray
    condition: float


def fit_base(Yb: np.ndarray, X: np.ndarray) -> Fit:
    """Weighted least squares of ``X (N, 9)`` on the base regressor ``Yb (N, 9, r)``.

    Raises:
        InputError: shapes that do not agree; fewer equations than parameters.
    """
    from offshore_crane.errors import InputError

    N, m, r = Yb.shape
    if X.shape != (N, m):
        raise InputError(f"fit: X has shape {X.shape}; the regressor {Yb.shape} wants "
                         f"({N}, {m})", name="X")
    if N * m <= r:
        raise InputError(f"fit: {N * m} equations for {r} base parameters: give a longer "
                         "record", name="X")
    W, y = Yb.reshape(-1, r), X.reshape(-1)
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
               float(np.linalg.cond(Ww)))
