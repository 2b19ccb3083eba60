"""Compiled helpers of the RNEA path: tree states that close the loops, and ``Gᵀ τ``.

Same kinematics as :mod:`offshore_crane.kinematics.legs` (closed-form U-P-S legs), per
sample, written straight into the Fortran-ordered ``(nv, N)`` arrays that
``pin.rneaInParallel`` reads; and the projection ``B = Gᵀ τ`` on the independent speeds
followed by the leg-force solve. Used by :mod:`.rnea` when Numba is installed; the NumPy
path there is the fallback (both tested against each other).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .fused_numba import _cross, _dot, _leg_geometry, _leg_motion, _platform_state, _solve6


@njit(cache=True, error_model="numpy")
def tree_kernel(q, qd, qdd, leg_s, leg_P, leg_X, leg_Y, leg_Z, idx_plat, idx_arm, idx_legs,
                Q, V, A, G, diag):
    """Fill ``Q, V, A`` ``(nv, N)``, the leg rows of ``G`` ``(N, 6, 3, 6)`` and the leg
    diagnostics ``diag`` ``(5, N, 6)`` (as :data:`.fused.DIAGNOSTICS`).

    ``G[k, i, j, r]`` is ∂(rate of joint j of leg i)/∂u_r (j: u1, u2, slide; r ≤ 6);
    ``idx_plat`` maps q1..q6 to tree velocity indices, ``idx_arm`` q7..q9, ``idx_legs``
    ``(6, 3)`` the legs' joints.
    """
    N = q.shape[0]
    R = np.empty((3, 3))
    W = np.empty((3, 3))     # rows: w4, w5, w6 (partial angular velocities)
    w = np.empty(3)
    al = np.empty(3)
    rS = np.empty(3)
    d = np.empty(3)
    u = np.empty(3)
    n_ = np.empty(3)
    a2 = np.empty(3)
    vS = np.empty(3)
    aS = np.empty(3)
    wl = np.empty(3)
    wxu = np.empty(3)
    e = np.empty(3)
    alp = np.empty(3)
    t1 = np.empty(3)
    t2 = np.empty(3)
    t3 = np.empty(3)
    vr = np.empty(3)
    na = idx_arm.shape[0]
    for k in range(N):
        for j in range(6):
            Q[idx_plat[j], k] = q[k, j]
            V[idx_plat[j], k] = qd[k, j]
            A[idx_plat[j], k] = qdd[k, j]
        for j in range(na):
            Q[idx_arm[j], k] = q[k, 6 + j]
            V[idx_arm[j], k] = qd[k, 6 + j]
            A[idx_arm[j], k] = qdd[k, 6 + j]
        _platform_state(q, qd, qdd, k, R, W, w, al)
        for l in range(6):
            length, il, dlx, dly, dlz, h = _leg_geometry(q, k, l, R, leg_s, leg_P, leg_X,
                                                         leg_Y, leg_Z, rS, d, u)
            l_h = length / h
            rate, accel, th1d, th2d = _leg_motion(
                l, w, al, qd[k, :3], qdd[k, :3], rS, u, length, il, dlx, dlz, h,
                leg_X, leg_Y, leg_Z, True, n_, a2, vS, aS, wl, wxu, e, alp, t1, t2, t3)
            j1, j2, j3 = idx_legs[l, 0], idx_legs[l, 1], idx_legs[l, 2]
            Q[j1, k] = np.arctan2(dlx, dlz)
            Q[j2, k] = np.arctan2(-dly, h)
            Q[j3, k] = length
            diag[0, k, l] = length
            diag[1, k, l] = Q[j1, k]
            diag[2, k, l] = Q[j2, k]
            diag[3, k, l] = h * il
            diag[4, k, l] = d[2]
            V[j1, k] = th1d
            V[j2, k] = th2d
            V[j3, k] = rate
            A[j1, k] = _dot(alp, leg_Y[l])
            A[j2, k] = _dot(alp, a2)
            A[j3, k] = accel
            # G rows: v_S,r = e_r (r < 3), w_r × rS (r = 4..6); ω_r from v_S,r
            for r in range(6):
                if r < 3:
                    for i in range(3):
                        vr[i] = 1.0 if i == r else 0.0
                else:
                    _cross(W[r - 3], rS, vr)
                _cross(u, vr, t1)
                for i in range(3):
                    t1[i] *= il
                sp = _dot(t1, n_) * l_h
                for i in range(3):
                    t1[i] += sp * u[i]
                G[k, l, 0, r] = _dot(t1, leg_Y[l])
                G[k, l, 1, r] = _dot(t1, a2)
                G[k, l, 2, r] = _dot(u, vr)


@njit(cache=True, error_model="numpy")
def project_solve(tau, G, idx_plat, idx_arm, idx_legs, L, X, cond):
    """``B = Gᵀ τ`` and the solve of ``A X = B`` (``A = [[0, Jᵀ], [I, 0]]``) per sample.

    ``tau`` is ``(nv, N)``; ``X`` ``(N, 9)`` is filled (NaN arm columns when the robot has
    fewer than 3 arm joints) and ``cond`` ``(N,)`` with the 1-norm condition number of
    ``Jᵀ``, its angular rows divided by the length ``L`` [m] to make it dimensionless.
    """
    N = tau.shape[1]
    na = idx_arm.shape[0]
    B = np.empty(6)
    J = np.empty((6, 6))
    x = np.empty(6)
    Ainv = np.empty((6, 6))
    for k in range(N):
        for j in range(3):
            X[k, j] = tau[idx_arm[j], k] if j < na else np.nan
        for r in range(6):
            B[r] = tau[idx_plat[r], k]
        for l in range(6):
            t1, t2, t3 = tau[idx_legs[l, 0], k], tau[idx_legs[l, 1], k], tau[idx_legs[l, 2], k]
            for r in range(6):
                B[r] += t1 * G[k, l, 0, r] + t2 * G[k, l, 1, r] + t3 * G[k, l, 2, r]
                J[r, l] = G[k, l, 2, r]          # Jᵀ: column l is leg l's row of J
        for r in range(3, 6):
            B[r] /= L
            for l in range(6):
                J[r, l] /= L
        cond[k] = _solve6(J, B, x, Ainv, True)
        for l in range(6):
            X[k, 3 + l] = x[l]


def rnea_numba(robot, q, qd, qdd, gravity, threads: int = 1):
    """Actuator forces by the RNEA path, tree states and projection compiled.

    Returns:
        ``(X (N, 9), cond (N,), diag)``: forces, condition number of the solved ``Jᵀ``
        (see :func:`project_solve`) and the leg diagnostics (dict of ``(N, 6)``).

    Args:
        robot: The robot (its ``pinocchio_model`` is built on first use).
        q, qd, qdd: ``(N, 9)`` float64 [m, rad], rates, accelerations.
        gravity: ``(3,)`` [m/s²].
        threads: Threads of ``pin.rneaInParallel``.
    """
    import pinocchio as pin

    model = robot.pinocchio_model
    idx = _indices(robot)
    N = q.shape[0]
    Q = np.empty((model.nv, N), order="F")
    V = np.empty((model.nv, N), order="F")
    A = np.empty((model.nv, N), order="F")
    G = np.empty((N, 6, 3, 6))
    diag = np.empty((5, N, 6))
    a = robot.fused.arrays
    tree_kernel(np.ascontiguousarray(q), np.ascontiguousarray(qd), np.ascontiguousarray(qdd),
                a["leg_s"], a["leg_P"], a["leg_X"], a["leg_Y"], a["leg_Z"],
                idx["platform"], idx["arm"], idx["legs"], Q, V, A, G, diag)
    tau = np.empty((model.nv, N), order="F")
    pin.rneaInParallel(threads, _pool(robot, gravity, threads), Q, V, A, tau)
    X = np.empty((N, 9))
    cond = np.empty(N)
    project_solve(tau, G, idx["platform"], idx["arm"], idx["legs"], a["L"], X, cond)
    from .fused import DIAGNOSTICS

    return X, cond, dict(zip(DIAGNOSTICS, diag))


def _indices(robot) -> dict:
    cache = robot.__dict__.setdefault("_tree_indices", {})
    if not cache:
        from .rnea import tree_indices

        cache.update({k: np.ascontiguousarray(v, dtype=np.int64)
                      for k, v in tree_indices(robot.pinocchio_model).items()})
    return cache


def _pool(robot, gravity, threads):
    """A ``pin.ModelPool`` with this gravity, reused across calls."""
    import pinocchio as pin

    pools = robot.__dict__.setdefault("_pin_pools", {})
    key = (tuple(float(x) for x in gravity), threads)
    if key not in pools:
        model = robot.pinocchio_model.copy()
        model.gravity.linear = np.asarray(gravity, dtype=float)
        pools[key] = pin.ModelPool(model, threads)
    return pools[key]
