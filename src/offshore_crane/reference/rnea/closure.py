"""The RNEA reference's loop closure: tree states that put each leg's tip on its anchor.

For each leg, the passive U-joint angles and the leg length that put frame ``leg{i}_tip``
on frame ``platform_anchor{i}``, by Newton's method on the tip position of the leg's
serial chain; their rates and accelerations from the chain's 3x3 Jacobian:
``J θ̇ = v_S``, ``J θ̈ = a_S − (J̇ θ̇)``, where ``v_S``, ``a_S`` follow from the platform's
chain of virtual joints. Both chains' kinematics are a generic forward recursion over
1-DOF joints read from Pinocchio's model (:mod:`.tree`), compiled with Numba; Pinocchio's
own forward kinematics checks them (``tests/robot/test_kinematics.py``), and a plain
per-sample Pinocchio closure checks the whole path
(``tests/dynamics/test_kane_vs_rnea.py``).

Frames: the base frame is Pinocchio's world (the URDF root ``base``); units SI.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from offshore_crane.kernel_cache import njit

from offshore_crane.conventions import N_LEGS
from offshore_crane.errors import NumericalError
from offshore_crane.reference.rnea.tree import read_tree

#: Newton on a leg's tip position stops when the residual is below this, relative to
#: 1 m + |S| (a few ulps of the positions: the reference closes the loops to round-off);
#: from the previous samples' extrapolation it takes 2 evaluations, from zero angles
#: 5-8; at most MAX_NEWTON. Revolute steps are limited to MAX_TURN [rad].
RESIDUAL_TOL = 4e-16
MAX_NEWTON = 60
MAX_TURN = 0.5


# --------------------------------------------------------------------------- compiled
# Numba is imported with this module (which the dynamics package imports lazily, when the
# reference runs). Every compiled helper of the closure lives here: Numba's cache does not
# follow a change of a function inlined from another file.
jit = njit(cache=True, nogil=True, error_model="numpy")

# Small vectors and matrices are tuples here (kept in registers by the compiler).
@jit
def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0])

@jit
def lin(a, s, b, t):
    """``s a + t b``."""
    return (s * a[0] + t * b[0], s * a[1] + t * b[1], s * a[2] + t * b[2])

@jit
def rot(R, v):
    """``R v`` for R a tuple of rows."""
    return (R[0][0] * v[0] + R[0][1] * v[1] + R[0][2] * v[2],
            R[1][0] * v[0] + R[1][1] * v[1] + R[1][2] * v[2],
            R[2][0] * v[0] + R[2][1] * v[1] + R[2][2] * v[2])


@jit
def vec(a, c, j):
    """``a[c, j]`` of a (m, n, 3) array as a tuple."""
    return (a[c, j, 0], a[c, j, 1], a[c, j, 2])


@jit
def compose(R, P, c, j):
    """``R P[c, j]`` (R a tuple of rows, P a (m, n, 3, 3) array) as a tuple of rows."""
    return ((R[0][0] * P[c, j, 0, 0] + R[0][1] * P[c, j, 1, 0] + R[0][2] * P[c, j, 2, 0],
             R[0][0] * P[c, j, 0, 1] + R[0][1] * P[c, j, 1, 1] + R[0][2] * P[c, j, 2, 1],
             R[0][0] * P[c, j, 0, 2] + R[0][1] * P[c, j, 1, 2] + R[0][2] * P[c, j, 2, 2]),
            (R[1][0] * P[c, j, 0, 0] + R[1][1] * P[c, j, 1, 0] + R[1][2] * P[c, j, 2, 0],
             R[1][0] * P[c, j, 0, 1] + R[1][1] * P[c, j, 1, 1] + R[1][2] * P[c, j, 2, 1],
             R[1][0] * P[c, j, 0, 2] + R[1][1] * P[c, j, 1, 2] + R[1][2] * P[c, j, 2, 2]),
            (R[2][0] * P[c, j, 0, 0] + R[2][1] * P[c, j, 1, 0] + R[2][2] * P[c, j, 2, 0],
             R[2][0] * P[c, j, 0, 1] + R[2][1] * P[c, j, 1, 1] + R[2][2] * P[c, j, 2, 1],
             R[2][0] * P[c, j, 0, 2] + R[2][1] * P[c, j, 1, 2] + R[2][2] * P[c, j, 2, 2]))


@jit
def turn(R, k, q):
    """``R exp([k]× q)``: R's rows turned about the unit axis k (joint frame)."""
    c, s = np.cos(q), np.sin(q)
    t = 1.0 - c
    e0 = (c + t * k[0] * k[0], t * k[0] * k[1] - s * k[2], t * k[0] * k[2] + s * k[1])
    e1 = (t * k[0] * k[1] + s * k[2], c + t * k[1] * k[1], t * k[1] * k[2] - s * k[0])
    e2 = (t * k[0] * k[2] - s * k[1], t * k[1] * k[2] + s * k[0], c + t * k[2] * k[2])
    return ((R[0][0] * e0[0] + R[0][1] * e1[0] + R[0][2] * e2[0],
             R[0][0] * e0[1] + R[0][1] * e1[1] + R[0][2] * e2[1],
             R[0][0] * e0[2] + R[0][1] * e1[2] + R[0][2] * e2[2]),
            (R[1][0] * e0[0] + R[1][1] * e1[0] + R[1][2] * e2[0],
             R[1][0] * e0[1] + R[1][1] * e1[1] + R[1][2] * e2[1],
             R[1][0] * e0[2] + R[1][1] * e1[2] + R[1][2] * e2[2]),
            (R[2][0] * e0[0] + R[2][1] * e1[0] + R[2][2] * e2[0],
             R[2][0] * e0[1] + R[2][1] * e1[1] + R[2][2] * e2[1],
             R[2][0] * e0[2] + R[2][1] * e1[2] + R[2][2] * e2[2]))

@jit
def solve3(M, b):
    """``M⁻¹ b`` for a 3x3 array ``M`` and a 3-tuple ``b`` (adjugate / determinant)."""
    c0 = cross((M[0, 1], M[1, 1], M[2, 1]), (M[0, 2], M[1, 2], M[2, 2]))
    c1 = cross((M[0, 2], M[1, 2], M[2, 2]), (M[0, 0], M[1, 0], M[2, 0]))
    c2 = cross((M[0, 0], M[1, 0], M[2, 0]), (M[0, 1], M[1, 1], M[2, 1]))
    det = M[0, 0] * c0[0] + M[1, 0] * c0[1] + M[2, 0] * c0[2]
    return ((c0[0] * b[0] + c0[1] * b[1] + c0[2] * b[2]) / det,
            (c1[0] * b[0] + c1[1] * b[1] + c1[2] * b[2]) / det,
            (c2[0] * b[0] + c2[1] * b[1] + c2[2] * b[2]) / det)

@jit
def chain_frame(R_, p_, axis_, prism_, c, qj, vj, aj, org, zs):
    """Forward recursion over one chain's 1-DOF joints (placements ``R_, p_`` in the
    parent joint frame, axes, types) at positions ``qj``, rates ``vj``, accelerations
    ``aj``, from a world frame at rest: the last joint frame's attitude, origin,
    angular velocity and acceleration, origin velocity and acceleration (world);
    ``org``, ``zs`` (n, 3) receive each joint's origin and axis."""
    R = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    p = (0.0, 0.0, 0.0)
    w = p
    al = p
    v = p
    a = p
    for j in range(qj.shape[0]):
        r = rot(R, vec(p_, c, j))
        t = cross(w, r)
        p = lin(p, 1.0, r, 1.0)
        v = lin(v, 1.0, t, 1.0)
        a = lin(lin(a, 1.0, cross(al, r), 1.0), 1.0, cross(w, t), 1.0)
        Rj = compose(R, R_, c, j)
        k = vec(axis_, c, j)
        z = rot(Rj, k)
        for i in range(3):
            org[j, i] = p[i]
            zs[j, i] = z[i]
        if prism_[c, j]:
            d = lin(z, qj[j], z, 0.0)
            wd = cross(w, d)
            a = lin(lin(lin(a, 1.0, cross(al, d), 1.0), 1.0, cross(w, wd), 1.0), 1.0,
                    lin(cross(w, z), 2.0 * vj[j], z, aj[j]), 1.0)
            v = lin(lin(v, 1.0, wd, 1.0), 1.0, z, vj[j])
            p = lin(p, 1.0, d, 1.0)
            R = Rj
        else:
            R = turn(Rj, k, qj[j])
            al = lin(al, 1.0, lin(z, aj[j], cross(w, z), vj[j]), 1.0)
            w = lin(w, 1.0, z, vj[j])
    return R, p, w, al, v, a

@jit
def end_point(frame, pend, prism_, c, org, zs, Jc):
    """The point ``pend`` (in the last joint frame) of a chain in state ``frame``
    (:func:`chain_frame`): position, velocity, acceleration (world), and its Jacobian
    ``Jc[:, j] = ∂X/∂q_j``."""
    R, p, w, al, v, a = frame
    r = rot(R, (pend[c, 0], pend[c, 1], pend[c, 2]))
    X = lin(p, 1.0, r, 1.0)
    t = cross(w, r)
    V = lin(v, 1.0, t, 1.0)
    A = lin(lin(a, 1.0, cross(al, r), 1.0), 1.0, cross(w, t), 1.0)
    for j in range(prism_.shape[1]):
        zj = (zs[j, 0], zs[j, 1], zs[j, 2])
        col = zj
        if not prism_[c, j]:
            col = cross(zj, (X[0] - org[j, 0], X[1] - org[j, 1], X[2] - org[j, 2]))
        for i in range(3):
            Jc[i, j] = col[i]
    return X, V, A

@jit
def tip_position(R_, p_, axis_, prism_, pend, c, qj, Jc, org, zs):
    """Position of chain ``c``'s end point at joint positions ``qj`` (world), its Jacobian
    ``Jc[:, j] = ∂X/∂q_j``, and each joint's origin ``org[j]`` and axis ``zs[j]``."""
    R = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    p = (0.0, 0.0, 0.0)
    n = qj.shape[0]
    for j in range(n):
        p = lin(p, 1.0, rot(R, vec(p_, c, j)), 1.0)
        Rj = compose(R, R_, c, j)
        k = vec(axis_, c, j)
        z = rot(Rj, k)
        for i in range(3):
            org[j, i] = p[i]
            zs[j, i] = z[i]
        if prism_[c, j]:
            p = lin(p, 1.0, z, qj[j])
            R = Rj
        else:
            R = turn(Rj, k, qj[j])
    X = lin(p, 1.0, rot(R, (pend[c, 0], pend[c, 1], pend[c, 2])), 1.0)
    for j in range(n):
        z = (zs[j, 0], zs[j, 1], zs[j, 2])
        col = z if prism_[c, j] else cross(z, (X[0] - org[j, 0], X[1] - org[j, 1],
                                               X[2] - org[j, 2]))
        for i in range(3):
            Jc[i, j] = col[i]
    return X


@jit
def bias_acceleration(prism_, c, X, Jc, org, zs, qd):
    """``J̇ q̇``: the end point's acceleration at rates ``qd`` and zero joint accelerations,
    from the joints' origins and axes of :func:`tip_position` (base at rest).

    Column j of J is ``z_j × (X − o_j)`` (revolute) or ``z_j`` (prismatic), with ``z_j``
    and ``o_j`` fixed in the body before joint j, which turns at
    ``ω_{j−1} = Σ_{k<j, revolute} z_k q̇_k``: ``ż_j = ω_{j−1} × z_j``,
    ``ȯ_j = Σ_{k<j} J_k(o_j) q̇_k``, ``Ẋ = J q̇``, and
    ``d/dt J_j = ż_j × (X − o_j) + z_j × (Ẋ − ȯ_j)`` (revolute), ``ż_j`` (prismatic).
    """
    n = qd.shape[0]
    Xd = (0.0, 0.0, 0.0)
    for j in range(n):
        Xd = lin(Xd, 1.0, (Jc[0, j], Jc[1, j], Jc[2, j]), qd[j])
    w = (0.0, 0.0, 0.0)
    acc = (0.0, 0.0, 0.0)
    for j in range(n):
        z = (zs[j, 0], zs[j, 1], zs[j, 2])
        o = (org[j, 0], org[j, 1], org[j, 2])
        zd = cross(w, z)
        if prism_[c, j]:
            acc = lin(acc, 1.0, zd, qd[j])
        else:
            od = (0.0, 0.0, 0.0)
            for k in range(j):
                zk = (zs[k, 0], zs[k, 1], zs[k, 2])
                if prism_[c, k]:
                    od = lin(od, 1.0, zk, qd[k])
                else:
                    od = lin(od, 1.0, cross(zk, lin(o, 1.0, (org[k, 0], org[k, 1], org[k, 2]),
                                                    -1.0)), qd[k])
            djc = lin(cross(zd, lin(X, 1.0, o, -1.0)), 1.0, cross(z, lin(Xd, 1.0, od, -1.0)),
                      1.0)
            acc = lin(acc, 1.0, djc, qd[j])
            w = lin(w, 1.0, z, qd[j])
    return acc


@jit
def det3(M):
    """Determinant of a 3x3 array."""
    return (M[0, 0] * (M[1, 1] * M[2, 2] - M[1, 2] * M[2, 1])
            - M[0, 1] * (M[1, 0] * M[2, 2] - M[1, 2] * M[2, 0])
            + M[0, 2] * (M[1, 0] * M[2, 1] - M[1, 1] * M[2, 0]))


@jit
def newton(lR, lp, lax, lpr, lpe, l, S, th, iters, Jl, branch, org, zs):
    """Leg joint positions ``th`` (updated in place) putting the tip on ``S``.

    Iterates ``θ += J⁻¹ (S − tip(θ))`` (revolute steps limited to MAX_TURN rad, so that a
    far guess does not jump to another solution), until the residual is below
    RESIDUAL_TOL (relative to the chain's size); revolute angles are wrapped into
    (−π, π]. The solution must lie on the leg's own branch: the U-joint and slider reach
    each tip position twice (the second with the U-joint flipped through its gimbal
    singularity), and the flip reverses the sign of ``det J``; ``branch`` is that sign at
    the zero angles. On return ``Jl``, ``org``, ``zs`` are those of :func:`tip_position`
    at ``th``. True on success.
    """
    scale = 1.0 + abs(S[0]) + abs(S[1]) + abs(S[2])
    for _ in range(iters):
        tip = tip_position(lR, lp, lax, lpr, lpe, l, th, Jl, org, zs)
        r = (S[0] - tip[0], S[1] - tip[1], S[2] - tip[2])
        if max(abs(r[0]), abs(r[1]), abs(r[2])) <= RESIDUAL_TOL * scale:
            return th[2] > 0.0 and det3(Jl) * branch > 0.0
        step = solve3(Jl, r)
        big = 0.0
        for i in range(3):
            if not lpr[l, i]:
                big = max(big, abs(step[i]))
        f = MAX_TURN / big if big > MAX_TURN else 1.0
        for i in range(3):
            th[i] += f * step[i]
            if not lpr[l, i]:
                th[i] = np.arctan2(np.sin(th[i]), np.cos(th[i]))
    return False


@jit
def closure(pR, pp, pax, ppr, ppe, pco, pvi, lR, lp, lax, lpr, lpe, lvi,
            q, qd, qdd, Q, Vt, At, G, diag, status):
    """Tree states closing the loops for samples of q, qd, qdd (N, 9); fills Q, Vt, At
    (N, nv) (a sample a row: the transposes of :func:`tree_state`'s Fortran (nv, N)
    arrays, C-ordered for any N, so that one compiled signature serves every call; with
    those arrays as given, an (nv, 1) one, C- and F-contiguous, was typed apart: a
    second 2.5 s compile), G (N, 6, 3, 6) = ∂(leg joint rates)/∂(q̇1..q̇6) and diag
    (5, N, 6) (length, cos θ2, height of S above P, θ1, θ2). ``status[0]`` is the first
    sample whose Newton iteration failed (-1 if none)."""
    N = q.shape[0]
    qp = np.empty(6)
    vp = np.empty(6)
    ap = np.empty(6)
    JS = np.empty((3, 6))
    Jl = np.empty((3, 3))
    org = np.empty((3, 3))
    zs = np.empty((3, 3))
    porg = np.empty((6, 3))
    pzs = np.empty((6, 3))
    th = np.zeros((6, 3))
    branch = np.empty(6)
    for l in range(6):                   # sign of det J at zero angles: the leg's branch
        th[l, 2] = 1.0
        tip_position(lR, lp, lax, lpr, lpe, l, th[l], Jl, org, zs)
        branch[l] = np.sign(det3(Jl))
    prev = np.zeros((6, 3))
    guess = np.zeros(3)
    zero = np.zeros(3)
    thd = np.empty(3)
    for k in range(N):
        for c in range(6):
            qp[c] = q[k, pco[0, c]]
            vp[c] = qd[k, pco[0, c]]
            ap[c] = qdd[k, pco[0, c]]
            Q[k, pvi[0, c]] = qp[c]
            Vt[k, pvi[0, c]] = vp[c]
            At[k, pvi[0, c]] = ap[c]
        frame = chain_frame(pR, pp, pax, ppr, 0, qp, vp, ap, porg, pzs)
        for l in range(6):
            S, vS, aS = end_point(frame, ppe, ppr, l, porg, pzs, JS)
            if k >= 2:                   # warm start: linear extrapolation of the path
                for j in range(3):
                    guess[j] = 2.0 * th[l, j] - prev[l, j]
            else:
                for j in range(3):
                    guess[j] = th[l, j]
            for j in range(3):
                prev[l, j] = th[l, j]
                th[l, j] = guess[j]
            ok = k > 0 and newton(lR, lp, lax, lpr, lpe, l, S, th[l], 10, Jl, branch[l], org, zs)
            if not ok:                   # from zero angles and the straight length
                th[l, 0] = 0.0
                th[l, 1] = 0.0
                th[l, 2] = np.sqrt((S[0] - lp[l, 0, 0]) ** 2 + (S[1] - lp[l, 0, 1]) ** 2
                                   + (S[2] - lp[l, 0, 2]) ** 2)
                ok = newton(lR, lp, lax, lpr, lpe, l, S, th[l], MAX_NEWTON, Jl, branch[l],
                            org, zs)
            if not ok and status[0] < 0:
                status[0] = k
            td = solve3(Jl, vS)
            for j in range(3):
                thd[j] = td[j]
            at = bias_acceleration(lpr, l, S, Jl, org, zs, thd)
            tdd = solve3(Jl, (aS[0] - at[0], aS[1] - at[1], aS[2] - at[2]))
            for j in range(3):
                vi = lvi[l, j]
                Q[k, vi] = th[l, j]
                Vt[k, vi] = thd[j]
                At[k, vi] = tdd[j]
            for c in range(6):
                g = solve3(Jl, (JS[0, c], JS[1, c], JS[2, c]))
                for j in range(3):
                    G[k, l, j, pco[0, c]] = g[j]
            diag[0, k, l] = th[l, 2]
            diag[1, k, l] = abs(np.cos(th[l, 1]))
            diag[2, k, l] = S[2] - lp[l, 0, 2]
            diag[3, k, l] = th[l, 0]
            diag[4, k, l] = th[l, 1]


def tree_state(robot: Any, q: np.ndarray, qd: np.ndarray,
               qdd: np.ndarray) -> tuple[np.ndarray, ...]:
    """Tree positions, rates and accelerations that close the loops (compiled closure).

    Args:
        q, qd, qdd: ``(N, 9)`` [m, rad], rates, accelerations.

    Returns:
        ``(Q, V, A, G, diag)``: ``(nv, N)`` Fortran-ordered tree states (Pinocchio's
        velocity index order), ``G`` ``(N, 6, 3, 6)`` the legs' joint-rate partials on
        q̇1..q̇6, ``diag`` ``(5, N, 6)`` leg length [m], cos θ2, height of S_i above P_i
        [m], θ1, θ2 [rad].

    Raises:
        NumericalError: Newton's method did not close a loop (naming the sample).
    """
    T = read_tree(robot)
    N = q.shape[0]
    Q, V, A = (np.zeros((T.nv, N), order="F") for _ in range(3))
    for x, src in ((Q, q), (V, qd), (A, qdd)):
        x[T.arm_v] = src[:, 6:6 + len(T.arm_v)].T
    G = np.empty((N, N_LEGS, 3, 6))
    diag = np.empty((5, N, N_LEGS))
    status = np.array([-1], dtype=np.int64)
    p, l = T.platform, T.legs
    closure(p.R, p.p, p.axis, p.prismatic, p.p_end, p.coordinate, p.v_index,
            l.R, l.p, l.axis, l.prismatic, l.p_end, l.v_index,
            np.ascontiguousarray(q), np.ascontiguousarray(qd), np.ascontiguousarray(qdd),
            Q.T, V.T, A.T, G, diag, status)
    if status[0] >= 0:
        raise NumericalError(f"the RNEA reference could not close the legs' loops at sample "
                             f"{status[0]} (Newton's method did not converge): is the pose "
                             "inside the workspace?", index=int(status[0]))
    return Q, V, A, G, diag


def tree_states(robot: Any, q: np.ndarray, qd: np.ndarray,
                qdd: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`tree_state` as ``(N, nv)`` arrays ``(q_tree, v_tree, a_tree)`` (Pinocchio's
    joint order), for analysis and tests."""
    Q, V, A, _, _ = tree_state(robot, np.atleast_2d(q), np.atleast_2d(qd), np.atleast_2d(qdd))
    return Q.T.copy(), V.T.copy(), A.T.copy()
