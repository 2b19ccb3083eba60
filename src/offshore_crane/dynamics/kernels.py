"""Drivers of the Kane formulas without compilation: NumPy chunks and Python floats.

:func:`run_numpy` evaluates :func:`.formulas.kane_sample` on chunks of samples (every
scalar of the text an ``(n,)`` array), then solves the chunk's 6x6 Stewart systems with
LAPACK and records what the checks find in a health record
(:mod:`offshore_crane.robot.kinematics.workspace`). :func:`run_python` evaluates the same text
on Python floats, one sample at a time: for a handful of samples it avoids NumPy's cost
per call (about 1 µs, and the text makes ~1,300 calls). Both fill the same arrays as the
compiled driver (:mod:`.compiled`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.robot.kinematics.formulas import FULL
from offshore_crane.dynamics import backends
from offshore_crane.dynamics.formulas import COS_THETA2, DIAG_ROWS, DX, DY, DZ, HEIGHT, LENGTH, STORE_WIDTH, H

#: Samples per chunk of the NumPy driver: each of the text's (n,) temporaries stays in
#: the L2 cache (4096 doubles = 32 kB).
CHUNK = 4096


@dataclass(frozen=True)
class Options:
    """What a kernel computes and checks.

    Attributes:
        leg_model: FULL, THIN_ROD or MASSLESS (:mod:`offshore_crane.robot.kinematics.formulas`).
        legs: Compute the leg forces (False: only T1, T2, Fs; legs and platform skipped).
        static: The platform is at rest (its velocity/acceleration terms skipped).
        conditioning: Measure the three condition numbers (``kappa`` arrays, the policy's
            first samples above ``warn`` and ``error``).
        limits: Check the workspace limits.
        warn, error: Thresholds of the singularity policy.
    """

    leg_model: int = FULL
    legs: bool = True
    static: bool = False
    conditioning: bool = False
    limits: bool = False
    warn: float = np.inf
    error: float = np.inf


def allocate(N: int, opts: Options):
    """Output arrays: X ``(N, 9)`` and, with conditioning, κ ``(3, N)``."""
    X = np.empty((N, 9))
    kappa = np.empty((3, N)) if opts.conditioning else None
    return X, kappa


def _solve(A: np.ndarray, rhs: np.ndarray, conditioning: bool):
    """Leg forces of the stacked systems ``A Fl = rhs`` ``(n, 6, 6)``, and their 1-norm
    condition numbers (inf for an exactly singular matrix) when asked."""
    finite = np.isfinite(A).all(axis=(1, 2))
    if not finite.all():              # U-joint at gimbal lock: κ inf, reported by policy
        A = np.where(finite[:, None, None], A, np.eye(6))
    try:
        inv = np.linalg.inv(A)
    except np.linalg.LinAlgError:     # an exactly singular sample: pseudo-inverse, κ = inf
        inv = np.linalg.pinv(A)
        finite &= np.linalg.matrix_rank(A) == 6
    X = np.einsum("nij,nj->ni", inv, rhs)
    X[~finite] = np.nan
    if not conditioning:
        return X, None
    kappa = np.abs(A).sum(axis=1).max(axis=1) * np.abs(inv).sum(axis=1).max(axis=1)
    kappa[~finite] = np.inf
    return X, kappa


def ujoint_angles(diag) -> np.ndarray:
    """``(n, 6, 2)`` U-joint angles θ1, θ2 [rad] from the diagnostics ``(DIAG_ROWS, n, 6)``
    (:func:`~offshore_crane.robot.kinematics.formulas.ujoint_angles`)."""
    return np.stack(backends.NUMPY.ujoint_angles(diag[DX], diag[DY], diag[DZ], diag[H]), -1)


def finish_chunk(X, A, rhs, length, cos2, height, theta, q, offset, opts, limits, kappa,
                 health):
    """Solve the legs of a chunk and check it.

    Args:
        X: ``(n, 9)`` view of the output with the arm columns filled.
        A, rhs: ``(n, 6, 6)``, ``(n, 6)`` leg-force systems (ignored without legs); or, for
            a caller that solved them, ``A`` the ``(n,)`` condition numbers and ``rhs``
            None (the leg columns of X filled).
        length, cos2, height: ``(n, 6)`` leg lengths [m], cos θ2, heights of S above P [m].
        theta: ``(n, 6, 2)`` U-joint angles [rad] (read with ``opts.limits``), or None.
        q: ``(n, 9)`` the chunk's coordinates; ``offset``: index of its first sample.
        kappa: ``(3, n)`` view of the output condition numbers, or None.
    """
    na = limits.arm.shape[0]
    X[:, na:3] = np.nan
    cond = None
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if opts.legs and rhs is None:
            cond = A
        elif opts.legs:
            X[:, 3:], cond = _solve(A, rhs, opts.conditioning)
        else:
            X[:, 3:] = np.nan
    ws.record_chunk(X, cond, length, cos2, height, theta, q, offset, opts, limits, kappa,
                    health)


def _finish_diag(X, A, rhs, diag, q, offset, opts, limits, kappa, health):
    """:func:`finish_chunk` from the Kane formulas' diagnostics ``(DIAG_ROWS, n, 6)``."""
    with np.errstate(divide="ignore", invalid="ignore"):
        theta = ujoint_angles(diag) if opts.limits else None
    finish_chunk(X, A, rhs, diag[LENGTH], diag[COS_THETA2], diag[HEIGHT], theta, q, offset,
                 opts, limits, kappa, health)


def run_numpy(arrays, q, qd, qdd, g, opts: Options, X, kappa, health, chunk: int = CHUNK):
    """The text on NumPy arrays, chunk by chunk (see module docstring).

    Args:
        arrays: :class:`~.constants.RobotArrays`.
        q, qd, qdd: ``(N, 9)`` float64 [m, rad], rates, accelerations.
        g: ``(3,)`` gravity [m/s²].
        X, kappa: outputs of :func:`allocate`; health: a record (:func:`ws.new_health`).
    """
    C, limits = arrays.kane, arrays.limits
    gt = tuple(float(x) for x in g)
    N = q.shape[0]
    rows = np.empty(3, dtype=object)
    Aw = np.empty((6, 6), dtype=object)
    rw = np.empty(6, dtype=object)
    dw = np.empty((DIAG_ROWS, 6), dtype=object)
    store = np.empty((C.n_arm, STORE_WIDTH), dtype=object)
    for start in range(0, N, chunk):
        sl = slice(start, min(start + chunk, N))
        qc, qdc, qddc = q[sl], qd[sl], qdd[sl]
        n = len(qc)
        ws.check_finite((qc, qdc, qddc), start, health)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            backends.NUMPY.kane_sample(C, qc.T, qdc.T, qddc.T, gt, opts.static, opts.leg_model,
                                       opts.legs, rows, Aw, rw, dw, store)
        Xc = X[sl]
        for b in range(C.n_arm):
            Xc[:, b] = rows[b]
        A = rhs = None
        diag = np.zeros((DIAG_ROWS, n, 6))
        if opts.legs:
            A = np.empty((n, 6, 6))
            rhs = np.empty((n, 6))
            for i in range(6):
                rhs[:, i] = rw[i]
                for j in range(6):
                    A[:, i, j] = Aw[i, j]
            for r in range(DIAG_ROWS):
                for j in range(6):
                    diag[r, :, j] = dw[r, j]
        _finish_diag(Xc, A, rhs, diag, qc, start, opts, limits,
                     None if kappa is None else kappa[:, sl], health)


def run_python(arrays, q, qd, qdd, g, opts: Options, X, kappa, health) -> bool:
    """The text on Python floats, one sample at a time; False if a sample raised an
    arithmetic exception (e.g. a U-joint exactly at gimbal lock): the caller then uses
    :func:`run_numpy`, whose arrays give inf/NaN there for the policy to report."""
    C, limits = arrays.kane, arrays.limits
    gt = tuple(float(x) for x in g)
    N = q.shape[0]
    A = np.zeros((N, 6, 6))
    rhs = np.zeros((N, 6))
    diag = np.zeros((DIAG_ROWS, N, 6))
    rows = [0.0, 0.0, 0.0]
    store = np.empty((C.n_arm, STORE_WIDTH))
    ws.check_finite((q, qd, qdd), 0, health)
    if health[ws.BAD_INPUT] >= 0:
        return True
    try:
        for k, (qk, qdk, qddk) in enumerate(zip(q.tolist(), qd.tolist(), qdd.tolist())):
            backends.PYTHON.kane_sample(C, qk, qdk, qddk, gt, opts.static, opts.leg_model,
                                        opts.legs, rows, A[k], rhs[k], diag[:, k], store)
            X[k, :C.n_arm] = rows[:C.n_arm]
    except (ZeroDivisionError, ValueError, OverflowError):
        return False
    _finish_diag(X, A, rhs, diag, q, 0, opts, limits, kappa, health)
    return True


def run_explicit_numpy(arrays, q, qd, qdd, g, opts: Options, X, kappa, health,
                       chunk: int = CHUNK):
    """:func:`.formulas.explicit_sample` on NumPy arrays, chunk by chunk: ``(T1, T2, Fs)
    = B[6:9]`` and ``Jᵀ Fl = B[0:6]`` (rotation rows scaled by 1/L)."""
    C, limits = arrays.kane, arrays.limits
    gt = tuple(float(x) for x in g)
    N = q.shape[0]
    iL = 1.0 / C.L
    for start in range(0, N, chunk):
        sl = slice(start, min(start + chunk, N))
        qc, qdc, qddc = q[sl], qd[sl], qdd[sl]
        n = len(qc)
        ws.check_finite((qc, qdc, qddc), start, health)
        B = np.zeros(9, dtype=object)
        Jw = np.empty((6, 6), dtype=object)
        Vw, Ww, Vs = (np.empty((9, 3), dtype=object) for _ in range(3))
        dw = np.empty((DIAG_ROWS, 6), dtype=object)
        store = np.empty((C.n_arm, STORE_WIDTH), dtype=object)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            backends.NUMPY.explicit_sample(C, qc.T, qdc.T, qddc.T, gt, False, B, Jw, None,
                                           store, Vw, Ww, Vs, dw, np.empty((1, 3), object))
        Xc = X[sl]
        for b in range(C.n_arm):
            Xc[:, b] = B[6 + b]
        A = np.empty((n, 6, 6))
        rhs = np.empty((n, 6))
        diag = np.empty((DIAG_ROWS, n, 6))
        for r in range(6):
            f = iL if r >= 3 else 1.0
            rhs[:, r] = B[r] * f
            for j in range(6):
                A[:, r, j] = Jw[j, r] * f
        for r in range(DIAG_ROWS):
            for j in range(6):
                diag[r, :, j] = dw[r, j]
        _finish_diag(Xc, A, rhs, diag, qc, start, opts, limits,
                     None if kappa is None else kappa[:, sl], health)
