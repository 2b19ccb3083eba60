"""Kane's method for the hybrid robot, written once, per sample (paper Eqs. 18-40).

Like :mod:`offshore_crane.robot.kinematics.formulas` (whose formulas these call), this is plain
arithmetic on 3-tuples that :mod:`.backends` runs vectorised with NumPy, compiled with
Numba, or in Python floats / mpmath. Two forms of Kane's equations live here:

**Fused** (:func:`kane_sample`, the default ``method="kane"``). Every body's partial
velocities are linear images of a few *carrier* partials, so Kane's sums
``Σ v_r · F + ω_r · T`` are taken *before* the dot product with the carrier:

- a leg reduces to an equivalent force ``f_S`` at its sphere centre S_i: with both links
  sharing ω_r = Ω v_S,r, ``Ω = (I − u nᵀ/(u·n)) [u]× / l``,
  ``v_r^{up}·F_up + v_r^{lo}·F_lo + ω_r·(T_lo + T_up) = v_S,r · f_S`` with
  ``f_S = F_up + (M' × u)/l``, ``M = ρ_lo × F_lo + ρ_up × F_up + T``,
  ``M' = M − n (u·M)/(u·n)`` (ρ: the links' centres of mass from P_i and S_i);
- the platform rows are the wrench ``(F, M_O2)`` of everything the platform carries;
- arm row j is ``z_j · (moment about o_j of the bodies below j)`` (revolute) or
  ``z_j · (their force)`` (prismatic);
- the leg forces solve the dimensionless Stewart system
  ``Σ_i Fl_i (u_i, r_i × u_i / L) = (F, M_O2 / L)``: the attitude coordinates never enter
  it (no division by cos q5).

**Explicit** (:func:`explicit_sample`, ``method="kane-explicit"``, and the mass matrix).
Every body's partial velocities ``v_r``, ``ω_r`` (r = 1..9) are formed, as the paper
writes them, and ``B_r = Σ_bodies v_r · m (a − g) + ω_r · (I α + ω × I ω)``,
``M_rs = Σ_bodies m v_r · v_s + ω_r · I ω_s``; ``A X = B`` with ``A = [[0, Jᵀ], [I3, 0]]``,
``J_ir = u_i · v_S_i,r`` the leg-length Jacobian (a leg's rate is ``l̇_i = J_i · u``).
A leg's links move as its sphere centre S does, so their partials are formed for the
three components of ``v_S`` and the leg's share of B and M (:func:`leg_share`: a force
``f_S`` and an inertia ``M_S`` seen at S, from those partials and the links' own forces,
not from the fused ``(M' × u)/l``) is carried to the speeds by ``v_S,r``
(:func:`carry`); sums only over the speeds that move a body (the platform's six for the
platform and the legs, and the joints above an arm body). It checks the fused factoring
(same kinematics, other algebra) and gives the equations of motion ``M q̈ + h = A X``.

``C`` is a :class:`KaneConstants` (arrays read once from the robot's URDF); workspaces
(``rows``, ``A``, ``rhs``, ``diag``, ``store``, …) are indexable arrays the caller
provides (float arrays compiled, object arrays vectorised). Units: SI; vectors in base
axes; ``g`` the gravity [m/s²].
"""

from __future__ import annotations

from collections import namedtuple

from offshore_crane.robot.kinematics.formulas import (FULL, MASSLESS, add, arm_child, arm_joint, attitude, axpy,
                                   cross, platform_partials, put, take, dot, leg_frame, leg_geometry, leg_motion,
                                   leg_spin, mat3, mm, mtv, mv, platform_rates,
                                   point_acceleration, point_velocity, row3, scale, sub,
                                   ujoint_axes)

#: The arrays Kane's formulas read, built by :func:`offshore_crane.dynamics.constants.build`.
#: Shapes: plat_c (3,), plat_I (3, 3) [platform frame, about the CoM]; arm_* (na, ...):
#: arm_t, arm_Ro joint origin and orientation in the parent body frame, arm_axis unit axis
#: in the joint frame, arm_prism bool, arm_m [kg], arm_c CoM in the body frame, arm_I
#: central inertia in body axes; leg_s (6, 3) S_i in the platform frame, leg_P P_i (base),
#: leg_X/Y/Z (6, 3) the U-joint frame's axes (Y = a1, Z = leg at zero angles); lo_*/up_*
#: lower/upper link mass (6,) and CoM (6, 3) in the leg frame (origins P_i and S_i);
#: leg_I (6, 3, 3) both links' central inertias summed, leg axes (they share ω, α);
#: thin_It (6,), lo_cz, up_cz (6,): the thin-rod approximation's transverse inertia and
#: CoMs on the axis; L [m] the length scale of the Stewart matrix.
KaneConstants = namedtuple("KaneConstants", (
    "plat_m", "plat_c", "plat_I", "n_arm", "arm_t", "arm_Ro", "arm_axis", "arm_prism",
    "arm_m", "arm_c", "arm_I", "leg_s", "leg_P", "leg_X", "leg_Y", "leg_Z", "lo_m", "lo_c",
    "up_m", "up_c", "leg_I", "thin_It", "lo_cz", "up_cz", "L"))

#: Columns of the arm's per-body workspace ``store`` (n_arm, STORE_WIDTH).
Z_, R_, OFF_, RC_, F_, T_, ATT_ = 0, 3, 6, 9, 12, 15, 18
STORE_WIDTH = 27
#: Rows of the legs' diagnostics workspace ``diag`` (DIAG_ROWS, 6).
#: LENGTH l [m], COS_THETA2 = h / l, HEIGHT of S above P [m], and S − P in the U-joint
#: frame (DX, DY, DZ) with H = |(DX, DZ)| [m], from which the U-joint angles follow
#: (:func:`~offshore_crane.robot.kinematics.formulas.ujoint_angles`, only where checked).
LENGTH, COS_THETA2, HEIGHT, DX, DY, DZ, H = 0, 1, 2, 3, 4, 5, 6
DIAG_ROWS = 7


def body_torque(R, I, omega, alpha):
    """``I_w α + ω × I_w ω`` [N·m] with ``I_w = R I Rᵀ`` (computed in body axes)."""
    wb = mtv(R, omega)
    tb = add(mv(I, mtv(R, alpha)), cross(wb, mv(I, wb)))
    return mv(R, tb)


def rigid_force(m, a_com, g):
    """``m (a − g)`` [N]: minus the inertia and gravity forces of a body."""
    return scale(sub(a_com, g), m)


# --------------------------------------------------------------------------- fused
def platform_wrench(C, R, omega, alpha, a, g):
    """The platform body's ``(F, M about O2)``: ``m (a_c − g)`` and ``T + ρ × F``."""
    rho = mv(R, C.plat_c)
    F = rigid_force(C.plat_m, point_acceleration(a, omega, alpha, rho), g)
    return F, add(body_torque(R, C.plat_I, omega, alpha), cross(rho, F))


def arm_forward(C, R, omega, alpha, a, q, qd, qdd, first, g, store, keep_attitude):
    """Forward recursion over the arm bodies on a base of attitude ``R``, angular velocity
    ``omega``, acceleration ``alpha``, origin acceleration ``a``: fills ``store`` (see the
    ``*_`` columns; the bodies' attitudes only with ``keep_attitude``). Joint b's
    coordinate is ``q[first + b]`` (6 for the hybrid robot)."""
    for b in range(C.n_arm):
        axis = row3(C.arm_axis, b)
        r, Rj, z = arm_joint(R, mat3(C.arm_Ro, b), row3(C.arm_t, b), axis)
        a_j = point_acceleration(a, omega, alpha, r)
        R, off, omega, alpha, a = arm_child(Rj, z, axis, omega, alpha, a_j, C.arm_prism[b],
                                            q[first + b], qd[first + b], qdd[first + b])
        rc = mv(R, row3(C.arm_c, b))
        put(store, b, Z_, z)
        put(store, b, R_, r)
        put(store, b, OFF_, off)
        put(store, b, RC_, rc)
        put(store, b, F_, rigid_force(C.arm_m[b], point_acceleration(a, omega, alpha, rc), g))
        put(store, b, T_, body_torque(R, mat3(C.arm_I, b), omega, alpha))
        if keep_attitude:
            put(store, b, ATT_, R[0])
            put(store, b, ATT_ + 3, R[1])
            put(store, b, ATT_ + 6, R[2])


def arm_backward(C, store, rows):
    """Arm rows ``rows[b]`` [N·m or N] and the arm's wrench ``(F, M about the base
    body's origin)`` by backward accumulation of the bodies' wrenches in ``store``."""
    F = (0.0, 0.0, 0.0)
    M = (0.0, 0.0, 0.0)
    for b in range(C.n_arm - 1, -1, -1):
        off = take(store, b, OFF_)
        if b < C.n_arm - 1:        # shift the moment of bodies > b from o_{b+1} to o_b
            M = add(M, cross(add(off, take(store, b + 1, R_)), F))
        Fb = take(store, b, F_)
        M = add(add(M, take(store, b, T_)), cross(add(off, take(store, b, RC_)), Fb))
        F = add(F, Fb)
        rows[b] = dot(take(store, b, Z_), F) if C.arm_prism[b] else dot(take(store, b, Z_), M)
    if C.n_arm > 0:
        M = add(M, cross(take(store, 0, R_), F))
    return F, M


def leg_constants(C, l):
    """Leg ``l``'s constants as a tuple (what :func:`leg_force` reads): S_l in the
    platform frame, P_l, the U-joint frame's axes X, Y = a1, Z, the links' masses and
    CoMs, their summed central inertia (leg frame), and the thin-rod values.

    (The formulas that run per leg take this tuple rather than the whole constants:
    compiled, a function reading array fields of ``C`` pays for all of them on each call.)
    """
    return (row3(C.leg_s, l), row3(C.leg_P, l), row3(C.leg_X, l), row3(C.leg_Y, l),
            row3(C.leg_Z, l), C.lo_m[l], row3(C.lo_c, l), C.up_m[l], row3(C.up_c, l),
            mat3(C.leg_I, l), C.thin_It[l], C.lo_cz[l], C.up_cz[l])


def leg_force(K, R, p, v, a, omega, alpha, g, static, leg_model):
    """A leg's geometry and its equivalent force ``f_S`` [N] at S (module docstring).

    Args:
        K: :func:`leg_constants` of the leg.

    Returns:
        ``(r, u, l, dx, dy, dz, h, d_z, f_S)``: O2 → S, the unit leg vector, its length
        [m], ``S − P`` in the U-joint frame, ``h = l cos θ2``, the height of S above P [m]
        and ``f_S`` (zero for massless legs).
    """
    s, P, X, Y, Z, lo_m, lo_c, up_m, up_c, I, It, lo_cz, up_cz = K
    r, d, length, il, u, dx, dy, dz, h = leg_geometry(p, R, s, P, X, Y, Z)
    f_S = (0.0 * length, 0.0 * length, 0.0 * length)
    if leg_model != MASSLESS:
        neg_g = scale(g, -1.0)
        l_h = 0.0 * length
        if leg_model == FULL:
            a2, n = ujoint_axes(X, Z, dx, dz, h)
            l_h = length / h
            Rl = leg_frame(u, a2)
            rho_lo = mv(Rl, lo_c)
            rho_up = mv(Rl, up_c)
        else:
            a2 = n = f_S
            Rl = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))   # unused
            rho_lo = scale(u, lo_cz)
            rho_up = scale(u, up_cz)
        if static:                      # the legs are at rest: weight only
            F_lo = scale(neg_g, lo_m)
            F_up = scale(neg_g, up_m)
            T = f_S
        else:
            v_S = point_velocity(v, omega, r)
            a_S = point_acceleration(a, omega, alpha, r)
            rate, accel, w, al, wxu, e, th1d, th2d = leg_motion(
                v_S, a_S, u, length, il, Y, a2, n, l_h, leg_model == FULL)
            F_lo = scale(add(point_acceleration(f_S, w, al, rho_lo), neg_g), lo_m)
            F_up = scale(add(point_acceleration(a_S, w, al, rho_up), neg_g), up_m)
            if leg_model == FULL:
                T = body_torque(Rl, I, w, al)
            else:                       # thin rods: ω ⟂ u, I = It (1 − u uᵀ)
                T = scale(al, It)
        M = add(add(cross(rho_lo, F_lo), cross(rho_up, F_up)), T)
        if leg_model == FULL:
            M = axpy(dot(u, M) * l_h, n, M)         # M' = M − n (u·M)/(u·n)
        f_S = add(F_up, scale(cross(M, u), il))
    return r, u, length, dx, dy, dz, h, d[2], f_S


def leg_diagnostics(diag, l, length, h, height, dx, dy, dz):
    """Write leg l's diagnostics (rows LENGTH .. H) into ``diag``."""
    diag[LENGTH, l] = length
    diag[COS_THETA2, l] = h / length
    diag[HEIGHT, l] = height
    diag[DX, l] = dx
    diag[DY, l] = dy
    diag[DZ, l] = dz
    diag[H, l] = h


def kane_sample(C, q, qd, qdd, g, static, leg_model, want_legs, rows, A, rhs, diag, store):
    """The fused Kane equations of one sample (or of n samples, vectorised).

    Fills ``rows[0:n_arm]`` with the arm actuators ``T1, T2, Fs``; with ``want_legs``, the
    dimensionless 6x6 Stewart matrix ``A`` (column l: ``(u_l, r_l × u_l / L)``), its
    right-hand side ``rhs = (F, M_O2 / L)`` (the leg forces solve ``A Fl = rhs``) and the
    legs' diagnostics ``diag`` (rows LENGTH .. H).

    Args:
        static: the platform is at rest (q̇ = q̈ = 0 for q1..q6): its velocity and
            acceleration terms are skipped (exact; the caller checks the premise).
        leg_model: FULL, THIN_ROD or MASSLESS.
        want_legs: False when no leg force is wanted: legs and platform are skipped.
    """
    R, p, omega, alpha, v, a = base_motion(q, qd, qdd, static)
    arm_forward(C, R, omega, alpha, a, q, qd, qdd, 6, g, store, False)
    F, M = arm_backward(C, store, rows)
    if want_legs:
        legs_and_platform(C, R, p, v, a, omega, alpha, g, static, leg_model, F, M, A, rhs,
                          diag)


def kane_sample_pull(C, q, qd, qdd, g, pull, at, rows, A, rhs, diag, store):
    """:func:`kane_sample` (all legs, full leg model) of the robot whose last arm body is
    replaced by a force ``pull`` [N] (base axes) acting on the robot at the point ``at``
    [m] from that body's joint origin (base axes), a point moving with the tip: the
    cable's pull on the tip (a massless cable whose payload moves as it will, e.g.
    hoisted by a winch, or on an elastic cable), at the payload's place when a moment
    about the tip (the sway damping's) makes it leave the cable's line. The arm rows of
    the bodies past the tip (the sway joints) are not X's."""
    R, p, omega, alpha, v, a = base_motion(q, qd, qdd, False)
    arm_forward(C, R, omega, alpha, a, q, qd, qdd, 6, g, store, False)
    b = C.n_arm - 1
    put(store, b, F_, scale(pull, -1.0))      # the body's m (a − g): minus the force on it
    put(store, b, T_, scale(pull, 0.0))
    put(store, b, RC_, at)
    F, M = arm_backward(C, store, rows)
    legs_and_platform(C, R, p, v, a, omega, alpha, g, False, FULL, F, M, A, rhs, diag)


def base_motion(q, qd, qdd, static):
    """The platform's attitude R, position p [m], ω [rad/s], α [rad/s²], velocity v [m/s]
    and acceleration a [m/s²] (zero rates when ``static``)."""
    R, w4, w5, w6 = attitude(q)
    p = (q[0], q[1], q[2])
    if static:
        zero = scale(p, 0.0)
        return R, p, zero, zero, zero, zero
    omega, alpha = platform_rates(w4, w5, qd, qdd)
    return R, p, omega, alpha, (qd[0], qd[1], qd[2]), (qdd[0], qdd[1], qdd[2])


def legs_and_platform(C, R, p, v, a, omega, alpha, g, static, leg_model, F, M, A, rhs,
                      diag):
    """The Stewart system of :func:`kane_sample`: ``A``, ``rhs`` and ``diag`` from the
    wrench ``(F, M about O2)`` the arm puts on the platform, the platform's and the legs'."""
    Fp, Mp = platform_wrench(C, R, omega, alpha, a, g)
    F = add(F, Fp)
    M = add(M, Mp)
    iL = 1.0 / C.L
    for l in range(6):
        f_S, m_S = stewart_leg(C, l, R, p, v, a, omega, alpha, g, static, leg_model, iL, A,
                               diag)
        F = add(F, f_S)
        M = add(M, m_S)
    for i in range(3):
        rhs[i] = F[i]
        rhs[3 + i] = M[i] * iL


def stewart_leg(C, l, R, p, v, a, omega, alpha, g, static, leg_model, iL, A, diag):
    """Leg ``l``'s part of :func:`legs_and_platform`, which depends on no other leg: its
    column of ``A`` (``iL`` = 1 / L [1/m]) and of ``diag``; returns its force on the
    platform at S, ``f_S`` [N], and that force's moment about O2, ``r × f_S`` [N·m]."""
    r, u, length, dx, dy, dz, h, height, f_S = leg_force(
        leg_constants(C, l), R, p, v, a, omega, alpha, g, static, leg_model)
    rxu = cross(r, u)
    for i in range(3):
        A[i, l] = u[i]
        A[3 + i, l] = rxu[i] * iL
    leg_diagnostics(diag, l, length, h, height, dx, dy, dz)
    return f_S, cross(r, f_S)


# --------------------------------------------------------------------------- explicit
def accumulate(B, Mm, Vw, Ww, m, Iw, F, T, want_mass, nr):
    """Add one body's share to ``B_r += v_r·F + ω_r·T`` and, with ``want_mass``,
    ``M_rs += m v_r·v_s + ω_r·(I_w ω_s)`` for r, s < ``nr``; ``Vw, Ww`` (n, 3) hold its
    partials (n = 9, or 11 with the hanging load's sway speeds), of which rows ``nr..n−1``
    are zero for this body (the speeds of joints beyond it: their share, exact zeros,
    is not added)."""
    for r in range(nr):
        vr, wr = take(Vw, r, 0), take(Ww, r, 0)
        B[r] = B[r] + dot(vr, F) + dot(wr, T)
        if want_mass:
            Iwr = mv(Iw, wr)
            for s in range(r + 1):
                Mm[r, s] = Mm[r, s] + m * dot(vr, take(Vw, s, 0)) + dot(Iwr, take(Ww, s, 0))


def _link_partials(W, rho_lo, rho_up, e):
    """A leg's links' partial velocities for the sphere centre's ``v_S = e`` and the
    leg's ω = ``W``: ``(W × ρ_lo, e + W × ρ_up)``."""
    return cross(W, rho_lo), add(e, cross(W, rho_up))


def _pair(m_lo, m_up, IW_i, W_j, lo_i, lo_j, up_i, up_j):
    """``m_lo v_i·v_j + ω_i·I ω_j + m_up v_i·v_j`` for a leg's partials i, j."""
    return m_lo * dot(lo_i, lo_j) + dot(IW_i, W_j) + m_up * dot(up_i, up_j)


def leg_share(m_lo, m_up, Iw, u, il, n, l_h, rho_lo, rho_up, F_lo, T_lo, F_up, want_mass):
    """A leg's Kane terms in its sphere centre's velocity ``v_S``, on which its motion
    depends alone: with the partials of ``v_S = e_x, e_y, e_z`` (ω_i = Ω e_i by
    :func:`~offshore_crane.robot.kinematics.formulas.leg_spin`, the lower link's centre
    ``ω_i × ρ_lo``, the upper's ``e_i + ω_i × ρ_up``; the two links share ω and their
    inertia ``Iw`` [kg·m², base axes] is counted once), ``f_S,i = Σ v_i · F + ω_i · T``
    [N] and the leg's inertia seen at S, ``M_S,ij = Σ m v_i · v_j + ω_i · Iw ω_j`` [kg]
    (zeros without ``want_mass``). A generalized speed r moving S by ``v_S,r`` gets
    ``v_S,r · f_S`` and ``v_S,r · M_S v_S,s`` (:func:`carry`): the same sums as each
    link's partials in the nine speeds, in 3 partials instead of 6 a link."""
    z0 = 0.0 * il
    one = 1.0 + z0
    Wx = leg_spin(scale((z0, u[2], -u[1]), il), u, n, l_h)        # Ω e_x: ω⊥ = u × e_x / l
    Wy = leg_spin(scale((-u[2], z0, u[0]), il), u, n, l_h)
    Wz = leg_spin(scale((u[1], -u[0], z0), il), u, n, l_h)
    lo_x, up_x = _link_partials(Wx, rho_lo, rho_up, (one, z0, z0))
    lo_y, up_y = _link_partials(Wy, rho_lo, rho_up, (z0, one, z0))
    lo_z, up_z = _link_partials(Wz, rho_lo, rho_up, (z0, z0, one))
    f_S = (dot(lo_x, F_lo) + dot(Wx, T_lo) + dot(up_x, F_up),
           dot(lo_y, F_lo) + dot(Wy, T_lo) + dot(up_y, F_up),
           dot(lo_z, F_lo) + dot(Wz, T_lo) + dot(up_z, F_up))
    if not want_mass:
        zt = (z0, z0, z0)
        return f_S, (zt, zt, zt)
    IWx, IWy, IWz = mv(Iw, Wx), mv(Iw, Wy), mv(Iw, Wz)
    xx = _pair(m_lo, m_up, IWx, Wx, lo_x, lo_x, up_x, up_x)
    yx = _pair(m_lo, m_up, IWy, Wx, lo_y, lo_x, up_y, up_x)
    yy = _pair(m_lo, m_up, IWy, Wy, lo_y, lo_y, up_y, up_y)
    zx = _pair(m_lo, m_up, IWz, Wx, lo_z, lo_x, up_z, up_x)
    zy = _pair(m_lo, m_up, IWz, Wy, lo_z, lo_y, up_z, up_y)
    zz = _pair(m_lo, m_up, IWz, Wz, lo_z, lo_z, up_z, up_z)
    return f_S, ((xx, yx, zx), (yx, yy, zy), (zx, zy, zz))


def carry(B, Mm, Vs, f_S, M_S, want_mass):
    """Add a leg's :func:`leg_share` to the platform's speeds r, s < 6 through its sphere
    centre's partials ``Vs`` (r, 3): ``B_r += v_S,r · f_S``, ``M_rs += v_S,r · M_S v_S,s``
    (the arm's speeds do not move a leg)."""
    for r in range(6):
        vr = take(Vs, r, 0)
        B[r] = B[r] + dot(vr, f_S)
        if want_mass:
            Mvr = mv(M_S, vr)
            for s in range(r + 1):
                Mm[r, s] = Mm[r, s] + dot(Mvr, take(Vs, s, 0))


def world_inertia(R, I):
    """``R I Rᵀ`` [kg·m²]."""
    RI = mm(R, I)
    return ((dot(RI[0], R[0]), dot(RI[0], R[1]), dot(RI[0], R[2])),
            (dot(RI[1], R[0]), dot(RI[1], R[1]), dot(RI[1], R[2])),
            (dot(RI[2], R[0]), dot(RI[2], R[1]), dot(RI[2], R[2])))


def explicit_sample(C, q, qd, qdd, g, want_mass, B, J, Mm, store, Vw, Ww, Vs, diag, mc):
    """Kane's equations with every body's partial velocities formed (module docstring).

    Fills ``B`` (9,) [N or N·m per generalized speed], the leg-length Jacobian ``J``
    (6, 6) [l̇_i per u_r, r ≤ 6] and, with ``want_mass``, the lower triangle of the mass
    matrix ``Mm`` (9, 9) [kg, kg·m, kg·m²] (the caller zeroes ``B`` and ``Mm``).
    ``store`` is the arm workspace, ``Vw, Ww`` (9, 3) a body's partials, ``Vs`` (9, 3)
    the sphere centre's; ``diag`` receives the legs' diagnostics (as
    :func:`kane_sample`'s); ``mc`` (3,) the first moment ``Σ m c`` [kg·m] of all bodies
    about the base origin (the potential energy is ``−g · Σ m c``).
    """
    R, w4, w5, w6 = attitude(q)
    p = (q[0], q[1], q[2])
    omega, alpha = platform_rates(w4, w5, qd, qdd)
    v = (qd[0], qd[1], qd[2])
    a = (qdd[0], qdd[1], qdd[2])
    # platform body
    rho = mv(R, C.plat_c)
    first = scale(add(p, rho), C.plat_m)
    platform_partials(w4, w5, w6, rho, Vw, Ww)
    accumulate(B, Mm, Vw, Ww, C.plat_m, world_inertia(R, C.plat_I),
               rigid_force(C.plat_m, point_acceleration(a, omega, alpha, rho), g),
               body_torque(R, C.plat_I, omega, alpha), want_mass, 6)
    # legs
    for l in range(6):
        first_l, f_S, M_S = explicit_leg(C, l, p, R, v, a, omega, alpha, w4, w5, w6, g,
                                         want_mass, J, Vs, Ww, diag)
        first = add(first, first_l)
        carry(B, Mm, Vs, f_S, M_S, want_mass)
    # arm: positions from O2 of the joint origins o_j and the bodies' CoMs c_b
    arm_forward(C, R, omega, alpha, a, q, qd, qdd, 6, g, store, True)
    origin = scale(p, 0.0)
    for b in range(C.n_arm):
        o_b = add(origin, take(store, b, R_))
        origin = add(o_b, take(store, b, OFF_))
        c_b = add(origin, take(store, b, RC_))
        first = add(first, scale(add(p, c_b), C.arm_m[b]))
        platform_partials(w4, w5, w6, c_b, Vw, Ww)
        o_j = scale(p, 0.0)
        orig_j = scale(p, 0.0)
        for j in range(b + 1):
            o_j = add(orig_j, take(store, j, R_))
            orig_j = add(o_j, take(store, j, OFF_))
            z = take(store, j, Z_)
            if C.arm_prism[j]:
                put(Vw, 6 + j, 0, z)
            else:
                put(Vw, 6 + j, 0, cross(z, sub(c_b, o_j)))
                put(Ww, 6 + j, 0, z)
        Rb = (take(store, b, ATT_), take(store, b, ATT_ + 3), take(store, b, ATT_ + 6))
        accumulate(B, Mm, Vw, Ww, C.arm_m[b], world_inertia(Rb, mat3(C.arm_I, b)),
                   take(store, b, F_), take(store, b, T_), want_mass, 7 + b)
    put(mc, 0, 0, first)


def explicit_leg(C, l, p, R, v, a, omega, alpha, w4, w5, w6, g, want_mass, J, Vs, Ww,
                 diag):
    """Leg ``l``'s part of :func:`explicit_sample`, which depends on no other leg: its
    row of the leg Jacobian ``J``, its sphere centre's partials ``Vs`` (Ww: scratch), its
    diagnostics (column l of ``diag``); returns its links' first moment ``Σ m c`` [kg·m]
    about the base origin and its share ``f_S``, ``M_S`` (:func:`leg_share`), which
    :func:`carry` adds to the platform's speeds."""
    X, Y, Z = row3(C.leg_X, l), row3(C.leg_Y, l), row3(C.leg_Z, l)
    r, d, length, il, u, dx, dy, dz, h = leg_geometry(p, R, row3(C.leg_s, l),
                                                      row3(C.leg_P, l), X, Y, Z)
    a2, n = ujoint_axes(X, Z, dx, dz, h)
    l_h = length / h
    Rl = leg_frame(u, a2)
    rho_lo = mv(Rl, row3(C.lo_c, l))
    rho_up = mv(Rl, row3(C.up_c, l))
    leg_diagnostics(diag, l, length, h, d[2], dx, dy, dz)
    v_S = point_velocity(v, omega, r)
    a_S = point_acceleration(a, omega, alpha, r)
    w, al = leg_motion(v_S, a_S, u, length, il, Y, a2, n, l_h, True)[2:4]
    zero = scale(r, 0.0)
    first = add(scale(add(row3(C.leg_P, l), rho_lo), C.lo_m[l]),
                scale(add(add(p, r), rho_up), C.up_m[l]))
    F_lo = rigid_force(C.lo_m[l], point_acceleration(zero, w, al, rho_lo), g)
    F_up = rigid_force(C.up_m[l], point_acceleration(a_S, w, al, rho_up), g)
    platform_partials(w4, w5, w6, r, Vs, Ww)           # v_S,r; Ww: scratch
    for k in range(6):
        J[l, k] = dot(u, take(Vs, k, 0))
    f_S, M_S = leg_share(C.lo_m[l], C.up_m[l], world_inertia(Rl, mat3(C.leg_I, l)), u, il, n,
                         l_h, rho_lo, rho_up, F_lo, body_torque(Rl, mat3(C.leg_I, l), w, al),
                         F_up, want_mass)
    return first, f_S, M_S


def actuator_coordinates(C, q, qd, pos, rate):
    """The actuated joints' positions ``pos`` (9,) and rates ``rate`` (9,): the arm joints
    q7..q9 [rad, m] (NaN-free zeros without arm) and the leg lengths [m], ``l̇ = u · v_S``
    [m/s], in the order of X."""
    R, w4, w5, w6 = attitude(q)
    p = (q[0], q[1], q[2])
    omega = platform_rates(w4, w5, qd, qd)[0]          # (the acceleration is not used)
    v = (qd[0], qd[1], qd[2])
    for b in range(3):
        pos[b] = q[6 + b] if b < C.n_arm else 0.0 * q[0]
        rate[b] = qd[6 + b] if b < C.n_arm else 0.0 * q[0]
    for l in range(6):
        s, P, X, Y, Z = row3(C.leg_s, l), row3(C.leg_P, l), row3(C.leg_X, l), row3(C.leg_Y, l), \
            row3(C.leg_Z, l)
        r, d, length, il, u, dx, dy, dz, h = leg_geometry(p, R, s, P, X, Y, Z)
        pos[3 + l] = length
        rate[3 + l] = dot(u, point_velocity(v, omega, r))


# --------------------------------------------------------------------------- hanging load
# With a payload on a cable the arm chain ``C`` continues by the two sway joints (φ1 about
# x of arm_tip, φ2 about the rotated y, one origin) and the payload, a point mass L below
# them (``C.n_arm = 5``; q, q̇, q̈ have 11 entries: q1..q9, φ1, φ2). The sway's equations
# come from :func:`pendulum` on the tip's motion (:func:`tip_motion`); the actuator forces
# from :func:`kane_sample` on the whole chain, whose rows of the sway speeds must then
# vanish (``rows[3:5] + c φ̇ = 0``): a check between the two.
