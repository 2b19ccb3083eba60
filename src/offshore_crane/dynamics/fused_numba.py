"""The fused Kane kernel compiled with Numba: same formulas as :mod:`.fused`, per sample.

Why it exists: NumPy pays about 1 µs per call, and the fused formulas need about 900
calls per chunk, so the vectorised kernel is bound by memory traffic of its temporaries
(≈2 µs per sample) and a single sample costs ≈150 µs of interpreter time. Compiled, the
same arithmetic runs in registers: a few tenths of a µs per sample, conditioning and
diagnostics included. Numba is optional (``pip install offshore-crane[fast]``); without
it, or for float32, the NumPy kernel runs. Both are tested against each other.

The formulas are those of :mod:`.fused` (see its docstring); the 6x6 leg-force system
``A Fl = rhs`` is solved by Gauss–Jordan elimination with partial pivoting, which also
yields ``A⁻¹`` for the 1-norm condition number.
"""

from __future__ import annotations

import numpy as np
from numba import njit

# leg models, as codes for the compiled kernel
FULL, THIN_ROD, MASSLESS = 0, 1, 2
LEG_MODEL_CODES = {"full": FULL, "thin-rod": THIN_ROD, "massless": MASSLESS}


@njit(cache=True, inline="always", error_model="numpy")
def _cross(a, b, out):
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@njit(cache=True, inline="always", error_model="numpy")
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True, inline="always", error_model="numpy")
def _matvec(R, v, out):
    for i in range(3):
        out[i] = R[i, 0] * v[0] + R[i, 1] * v[1] + R[i, 2] * v[2]


@njit(cache=True, inline="always", error_model="numpy")
def _matvec_t(R, v, out):
    for i in range(3):
        out[i] = R[0, i] * v[0] + R[1, i] * v[1] + R[2, i] * v[2]


@njit(cache=True, inline="always", error_model="numpy")
def _accel_point(a, w, al, r, out, tmp, tmp2):
    """out = a + al × r + w × (w × r)."""
    _cross(w, r, tmp)
    _cross(w, tmp, tmp2)
    _cross(al, r, tmp)
    for i in range(3):
        out[i] = a[i] + tmp[i] + tmp2[i]


@njit(cache=True, inline="always", error_model="numpy")
def _body_torque(R, I, w, al, out, wb, ab, t1, t2):
    """out = I_w al + w × I_w w with I_w = R I Rᵀ (in body axes)."""
    _matvec_t(R, w, wb)
    _matvec_t(R, al, ab)
    _matvec(I, wb, t1)
    _cross(wb, t1, t2)
    _matvec(I, ab, t1)
    for i in range(3):
        t1[i] += t2[i]
    _matvec(R, t1, out)


@njit(cache=True, inline="always", error_model="numpy")
def _platform_state(q, qd, qdd, k, R, W, w, al):
    """Sample k's platform attitude ``R`` (3, 3), attitude partials ``W`` (rows w4, w5,
    w6), angular velocity ``w`` and acceleration ``al`` (see :mod:`.platform`)."""
    c4, s4 = np.cos(q[k, 3]), np.sin(q[k, 3])
    c5, s5 = np.cos(q[k, 4]), np.sin(q[k, 4])
    c6, s6 = np.cos(q[k, 5]), np.sin(q[k, 5])
    R[0, 0] = c6 * c5
    R[0, 1] = c6 * s5 * s4 - s6 * c4
    R[0, 2] = c6 * s5 * c4 + s6 * s4
    R[1, 0] = s6 * c5
    R[1, 1] = s6 * s5 * s4 + c6 * c4
    R[1, 2] = s6 * s5 * c4 - c6 * s4
    R[2, 0] = -s5
    R[2, 1] = c5 * s4
    R[2, 2] = c5 * c4
    W[0, 0], W[0, 1], W[0, 2] = c6 * c5, s6 * c5, -s5
    W[1, 0], W[1, 1], W[1, 2] = -s6, c6, 0.0
    W[2, 0], W[2, 1], W[2, 2] = 0.0, 0.0, 1.0
    for i in range(3):
        w[i] = W[0, i] * qd[k, 3] + W[1, i] * qd[k, 4] + W[2, i] * qd[k, 5]
    # α = W q̈ + q̇4 (q̇6 z + q̇5 w5) × w4 + q̇5 q̇6 (z × w5)
    sx, sy, sz = W[1, 0] * qd[k, 4], W[1, 1] * qd[k, 4], qd[k, 5]
    cx = (sy * W[0, 2] - sz * W[0, 1]) * qd[k, 3]
    cy = (sz * W[0, 0] - sx * W[0, 2]) * qd[k, 3]
    cz = (sx * W[0, 1] - sy * W[0, 0]) * qd[k, 3]
    q56 = qd[k, 4] * qd[k, 5]
    al[0] = W[0, 0] * qdd[k, 3] + W[1, 0] * qdd[k, 4] + cx - c6 * q56
    al[1] = W[0, 1] * qdd[k, 3] + W[1, 1] * qdd[k, 4] + cy - s6 * q56
    al[2] = W[0, 2] * qdd[k, 3] + qdd[k, 5] + cz


@njit(cache=True, inline="always", error_model="numpy")
def _leg_geometry(q, k, l, R, leg_s, leg_P, leg_X, leg_Y, leg_Z, rS, d, u):
    """Leg l of sample k: fills ``rS = R s_l`` (O2 → S), ``d = S − P`` and ``u = d/l``;
    returns ``(l, 1/l, X·d, Y·d, Z·d, h = |(X·d, Z·d)|)`` (U-joint frame axes X, Y, Z)."""
    _matvec(R, leg_s[l], rS)
    for i in range(3):
        d[i] = q[k, i] + rS[i] - leg_P[l, i]
    length = np.sqrt(_dot(d, d))
    il = 1.0 / length
    for i in range(3):
        u[i] = d[i] * il
    dlx, dly, dlz = _dot(leg_X[l], d), _dot(leg_Y[l], d), _dot(leg_Z[l], d)
    return length, il, dlx, dly, dlz, np.sqrt(dlx * dlx + dlz * dlz)


@njit(cache=True, inline="always", error_model="numpy")
def _leg_motion(l, w, al, v, a, rS, u, length, il, dlx, dlz, h, leg_X, leg_Y, leg_Z, full,
                n_, a2, vS, aS, wl, wxu, e, alp, t1, t2, t3):
    """Leg l's motion (see :mod:`offshore_crane.kinematics.legs`): fills the sphere
    centre's velocity ``vS`` and acceleration ``aS``, the leg's angular velocity ``wl`` and
    acceleration ``alp``, ``wxu = wl × u``, ``e = α × u + ω × (ω × u)`` and, when ``full``
    (U-joint spin included), the U-joint normal ``n_ = a1 × a2`` and axis ``a2``. Without
    ``full`` the leg has no spin (thin rods: ω, α ⟂ u). Returns ``(l̇, l̈, θ̇1, θ̇2)``
    (θ̇ zero without ``full``)."""
    _cross(w, rS, t1)
    _cross(al, rS, t2)
    _cross(w, t1, t3)
    for i in range(3):
        vS[i] = v[i] + t1[i]
        aS[i] = a[i] + t2[i] + t3[i]
    rate = _dot(u, vS)
    _cross(u, vS, wl)
    for i in range(3):
        wl[i] *= il
    th1d = th2d = 0.0
    if full:
        ih = 1.0 / h
        for i in range(3):
            n_[i] = -(leg_X[l, i] * dlx + leg_Z[l, i] * dlz) * ih
            a2[i] = (leg_X[l, i] * dlz - leg_Z[l, i] * dlx) * ih
        sp = _dot(wl, n_) * length * ih
        for i in range(3):
            wl[i] += sp * u[i]
        th1d = _dot(wl, leg_Y[l])
        th2d = _dot(wl, a2)
    _cross(wl, u, wxu)
    accel = _dot(aS, u) + length * _dot(wxu, wxu)
    for i in range(3):
        e[i] = (aS[i] - accel * u[i] - 2.0 * rate * wxu[i]) * il
    _cross(wl, wxu, t1)
    for i in range(3):
        t2[i] = e[i] - t1[i]
    _cross(u, t2, alp)
    if full:
        mu = (_dot(alp, n_) - th1d * th2d) * length / h
        for i in range(3):
            alp[i] += mu * u[i]
    return rate, accel, th1d, th2d


@njit(cache=True, error_model="numpy")
def _solve6(A, rhs, x, Ainv, want_inverse):
    """Gauss–Jordan with partial pivoting on [A | I | rhs]; returns the 1-norm κ of A.

    Returns inf (and NaN solution) for an exactly singular matrix.
    """
    n = 6
    M = np.empty((n, 2 * n + 1))
    for i in range(n):
        for j in range(n):
            M[i, j] = A[i, j]
            M[i, n + j] = 1.0 if i == j else 0.0
        M[i, 2 * n] = rhs[i]
    width = 2 * n + 1
    for k in range(n):
        p = k
        best = abs(M[k, k])
        for r in range(k + 1, n):
            v = abs(M[r, k])
            if v > best:
                best = v
                p = r
        if best == 0.0:
            for i in range(n):
                x[i] = np.nan
            return np.inf
        if p != k:
            for j in range(width):
                tmp = M[k, j]
                M[k, j] = M[p, j]
                M[p, j] = tmp
        inv_piv = 1.0 / M[k, k]
        for j in range(width):
            M[k, j] *= inv_piv
        for r in range(n):
            if r != k:
                f = M[r, k]
                if f != 0.0:
                    for j in range(width):
                        M[r, j] -= f * M[k, j]
    for i in range(n):
        x[i] = M[i, 2 * n]
    if not want_inverse:
        return 0.0
    norm_a = 0.0
    norm_inv = 0.0
    for j in range(n):
        sa = 0.0
        si = 0.0
        for i in range(n):
            sa += abs(A[i, j])
            si += abs(M[i, n + j])
            Ainv[i, j] = M[i, n + j]
        norm_a = max(norm_a, sa)
        norm_inv = max(norm_inv, si)
    return norm_a * norm_inv


@njit(cache=True, error_model="numpy")
def kernel(q, qd, qdd, g, plat_m, plat_c, plat_I,
           arm_t, arm_Ro, arm_axis, arm_prism, arm_m, arm_c, arm_I,
           leg_s, leg_P, leg_X, leg_Y, leg_Z, m_lo, m_up, c_lo, c_up, It, Ia, L,
           leg_model, want_legs, static, want_cond, want_diag, X, cond, diag):
    """Fill ``X (N, 9)``, ``cond (N,)`` and ``diag (5, N, 6)`` (see :mod:`.fused`)."""
    N = q.shape[0]
    na = arm_t.shape[0]
    R = np.empty((3, 3))
    Wp = np.empty((3, 3))
    Rc = np.empty((3, 3))
    Rj = np.empty((3, 3))
    Rcur = np.empty((3, 3))
    w = np.zeros(3)
    al = np.zeros(3)
    a = np.zeros(3)
    v = np.zeros(3)
    wc = np.empty(3)
    alc = np.empty(3)
    ac = np.empty(3)
    aj = np.empty(3)
    r = np.empty(3)
    z = np.empty(3)
    t1 = np.empty(3)
    t2 = np.empty(3)
    t3 = np.empty(3)
    t4 = np.empty(3)
    wb = np.empty(3)
    ab = np.empty(3)
    rc = np.empty(3)
    F = np.empty(3)
    M = np.empty(3)
    neg_g = np.empty(3)
    for i in range(3):
        neg_g[i] = -g[i]
    # per arm body storage
    bz = np.empty((na, 3))
    br = np.empty((na, 3))
    boff = np.zeros((na, 3))
    brc = np.empty((na, 3))
    bF = np.empty((na, 3))
    bT = np.empty((na, 3))
    Facc = np.empty(3)
    Macc = np.empty(3)
    A = np.empty((6, 6))
    Ainv = np.empty((6, 6))
    rhs = np.empty(6)
    xs = np.empty(6)
    d = np.empty(3)
    u = np.empty(3)
    rS = np.empty(3)
    vS = np.empty(3)
    aS = np.empty(3)
    wl = np.empty(3)
    wxu = np.empty(3)
    e = np.empty(3)
    alp = np.empty(3)
    n_ = np.empty(3)
    a2 = np.empty(3)
    Flo = np.empty(3)
    Fup = np.empty(3)
    T = np.empty(3)
    fS = np.empty(3)
    lever = np.empty(3)
    for k in range(N):
        # ---------------- platform
        _platform_state(q, qd, qdd, k, R, Wp, w, al)
        if static:
            for i in range(3):
                w[i] = 0.0
                al[i] = 0.0
                a[i] = 0.0
                v[i] = 0.0
        else:
            for i in range(3):
                a[i] = qdd[k, i]
                v[i] = qd[k, i]
        # ---------------- arm (forward recursion)
        for i in range(3):
            for j in range(3):
                Rcur[i, j] = R[i, j]
            wc[i] = w[i]
            alc[i] = al[i]
            ac[i] = a[i]
        for b in range(na):
            _matvec(Rcur, arm_t[b], r)
            for i in range(3):
                for j in range(3):
                    Rj[i, j] = (Rcur[i, 0] * arm_Ro[b, 0, j] + Rcur[i, 1] * arm_Ro[b, 1, j]
                                + Rcur[i, 2] * arm_Ro[b, 2, j])
            _matvec(Rj, arm_axis[b], z)
            _accel_point(ac, wc, alc, r, aj, t1, t2)
            qb, qdb, qddb = q[k, 6 + b], qd[k, 6 + b], qdd[k, 6 + b]
            if arm_prism[b]:
                for i in range(3):
                    boff[b, i] = z[i] * qb
                _accel_point(aj, wc, alc, boff[b], t3, t1, t2)
                _cross(wc, z, t1)
                for i in range(3):
                    ac[i] = t3[i] + 2.0 * qdb * t1[i] + qddb * z[i]
                for i in range(3):
                    for j in range(3):
                        Rc[i, j] = Rj[i, j]
            else:
                for i in range(3):
                    boff[b, i] = 0.0
                # Rc = Rj (I + s K + (1 - c) K²), K = skew(axis)
                s_, c_ = np.sin(qb), 1.0 - np.cos(qb)
                kx, ky, kz = arm_axis[b, 0], arm_axis[b, 1], arm_axis[b, 2]
                Rot00 = 1.0 - c_ * (ky * ky + kz * kz)
                Rot11 = 1.0 - c_ * (kx * kx + kz * kz)
                Rot22 = 1.0 - c_ * (kx * kx + ky * ky)
                Rot01 = -s_ * kz + c_ * kx * ky
                Rot10 = s_ * kz + c_ * kx * ky
                Rot02 = s_ * ky + c_ * kx * kz
                Rot20 = -s_ * ky + c_ * kx * kz
                Rot12 = -s_ * kx + c_ * ky * kz
                Rot21 = s_ * kx + c_ * ky * kz
                for i in range(3):
                    Rc[i, 0] = Rj[i, 0] * Rot00 + Rj[i, 1] * Rot10 + Rj[i, 2] * Rot20
                    Rc[i, 1] = Rj[i, 0] * Rot01 + Rj[i, 1] * Rot11 + Rj[i, 2] * Rot21
                    Rc[i, 2] = Rj[i, 0] * Rot02 + Rj[i, 1] * Rot12 + Rj[i, 2] * Rot22
                _cross(wc, z, t1)
                for i in range(3):
                    alc[i] = alc[i] + qddb * z[i] + qdb * t1[i]
                    wc[i] = wc[i] + qdb * z[i]
                    ac[i] = aj[i]
            _matvec(Rc, arm_c[b], rc)
            _accel_point(ac, wc, alc, rc, t3, t1, t2)
            for i in range(3):
                bF[b, i] = arm_m[b] * (t3[i] + neg_g[i])
            _body_torque(Rc, arm_I[b], wc, alc, t4, wb, ab, t1, t2)
            for i in range(3):
                bT[b, i] = t4[i]
                bz[b, i] = z[i]
                br[b, i] = r[i]
                brc[b, i] = rc[i]
            for i in range(3):
                for j in range(3):
                    Rcur[i, j] = Rc[i, j]
        # ---------------- arm (backward accumulation)
        for i in range(3):
            Facc[i] = 0.0
            Macc[i] = 0.0
        for b in range(na - 1, -1, -1):
            if b < na - 1:
                for i in range(3):
                    t1[i] = boff[b, i] + br[b + 1, i]
                _cross(t1, Facc, t2)
                for i in range(3):
                    Macc[i] += t2[i]
            for i in range(3):
                t1[i] = boff[b, i] + brc[b, i]
            _cross(t1, bF[b], t2)
            for i in range(3):
                Macc[i] += bT[b, i] + t2[i]
                Facc[i] += bF[b, i]
            if arm_prism[b]:
                X[k, b] = _dot(bz[b], Facc)
            else:
                X[k, b] = _dot(bz[b], Macc)
        for b in range(na, 3):
            X[k, b] = np.nan
        if not want_legs:
            for j in range(3, 9):
                X[k, j] = np.nan
            continue
        # arm wrench about O2
        for i in range(3):
            F[i] = Facc[i]
            M[i] = Macc[i]
        if na > 0:
            _cross(br[0], Facc, t1)
            for i in range(3):
                M[i] += t1[i]
        # ---------------- platform body
        _matvec(R, plat_c, rc)
        _accel_point(a, w, al, rc, t3, t1, t2)
        for i in range(3):
            t4[i] = plat_m * (t3[i] + neg_g[i])
            F[i] += t4[i]
        _cross(rc, t4, t1)
        _body_torque(R, plat_I, w, al, t3, wb, ab, t2, t4)
        for i in range(3):
            M[i] += t1[i] + t3[i]
        # ---------------- legs
        for l in range(6):
            length, il, dlx, dly, dlz, h = _leg_geometry(q, k, l, R, leg_s, leg_P, leg_X,
                                                         leg_Y, leg_Z, rS, d, u)
            _cross(rS, u, t1)
            for i in range(3):
                A[i, l] = u[i]
                A[3 + i, l] = t1[i] / L
            if want_diag:
                diag[0, k, l] = length
                diag[1, k, l] = np.arctan2(dlx, dlz)
                diag[2, k, l] = np.arctan2(-dly, h)
                diag[3, k, l] = h / length
                diag[4, k, l] = d[2]
            if leg_model == MASSLESS:
                continue
            l_h = length / h
            _leg_motion(l, w, al, v, a, rS, u, length, il, dlx, dlz, h, leg_X, leg_Y, leg_Z,
                        leg_model == FULL, n_, a2, vS, aS, wl, wxu, e, alp, t1, t2, t3)
            for i in range(3):
                Flo[i] = m_lo[l] * (e[i] * c_lo[l] + neg_g[i])
                Fup[i] = m_up[l] * (aS[i] + e[i] * c_up[l] + neg_g[i])
            if leg_model == FULL:
                dI = Ia[l] - It[l]
                ua = _dot(u, alp) * dI
                uw = _dot(u, wl) * dI
                for i in range(3):
                    T[i] = It[l] * alp[i] + ua * u[i] + uw * wxu[i]
            else:
                for i in range(3):
                    T[i] = It[l] * alp[i]
            for i in range(3):
                lever[i] = Flo[i] * c_lo[l] + Fup[i] * c_up[l]
            _cross(u, lever, t1)
            for i in range(3):
                t1[i] += T[i]
            if leg_model == FULL:
                um = _dot(u, t1) * l_h
                for i in range(3):
                    t1[i] += n_[i] * um
            _cross(t1, u, t2)
            for i in range(3):
                fS[i] = Fup[i] + t2[i] * il
                F[i] += fS[i]
            _cross(rS, fS, t1)
            for i in range(3):
                M[i] += t1[i]
        for i in range(3):
            rhs[i] = F[i]
            rhs[3 + i] = M[i] / L
        kappa = _solve6(A, rhs, xs, Ainv, want_cond)
        for j in range(6):
            X[k, 3 + j] = xs[j]
        if want_cond:
            cond[k] = kappa
