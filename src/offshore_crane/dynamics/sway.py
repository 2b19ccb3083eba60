"""The hanging load's formulas: the tip's motion, the pendulum on its cable (fixed or
hoisted by a winch) and the cable's pull, per sample (docs/cable.md).

Written once like :mod:`offshore_crane.dynamics.formulas` (whose arm chain they continue
by the two sway joints and the payload) and run by the same backends
(:mod:`offshore_crane.dynamics.backends`: NumPy-vectorised, compiled, Python floats,
mpmath). Units SI; vectors in base axes unless said (tip axes: the ``arm_tip`` frame's).
"""

from __future__ import annotations

from numpy import cos, sin, sqrt

from offshore_crane.dynamics.formulas import F_, RC_
from offshore_crane.robot.kinematics.formulas import (add, arm_child, arm_joint, attitude, axpy,
                                                      axis_rotation, cross, dot, mat3, mm,
                                                      mtv, mv, platform_rates,
                                                      point_acceleration, row3, scale, sub,
                                                      take)


def tip_motion(C, q, qd, qdd):
    """The first sway joint's frame (``arm_tip``): ``(R_base_tip, ω [rad/s], α [rad/s²],
    a [m/s²])``, its attitude, angular velocity and acceleration, and its origin's
    acceleration, under the robot's motion ``q, q̇, q̈`` (the arm chain ``C`` continued
    by the two sway joints)."""
    R, w4, w5, w6 = attitude(q)
    omega, alpha = platform_rates(w4, w5, qd, qdd)
    a = (qdd[0], qdd[1], qdd[2])
    nb = C.n_arm - 2
    for b in range(nb):
        axis = row3(C.arm_axis, b)
        r, Rj, z = arm_joint(R, mat3(C.arm_Ro, b), row3(C.arm_t, b), axis)
        R, off, omega, alpha, a = arm_child(Rj, z, axis, omega, alpha,
                                            point_acceleration(a, omega, alpha, r),
                                            C.arm_prism[b], q[6 + b], qd[6 + b], qdd[6 + b])
    r, Rj, z = arm_joint(R, mat3(C.arm_Ro, nb), row3(C.arm_t, nb), row3(C.arm_axis, nb))
    return Rj, omega, alpha, point_acceleration(a, omega, alpha, r)


def sway_direction(p1, p2):
    """The cable's direction from the tip to the payload in tip axes,
    ``e = Rx(φ1) Ry(φ2) (0, 0, −1)``, and its partials ``∂e/∂φ1``, ``∂e/∂φ2``."""
    s1, k1, s2, k2 = sin(p1), cos(p1), sin(p2), cos(p2)
    return (-s2, s1 * k2, -k1 * k2), (0.0 * s1, k1 * k2, s1 * k2), (-k2, -s1 * s2, k1 * s2)


def pendulum(C, Rt, omega, alpha, a_t, g, p1, p2, r1, r2, c1, c2, f):
    """Kane's equations of the sway speeds: ``(φ̈1, φ̈2)`` [rad/s²] and ``cos²φ2``.

    A point mass m on a cable of length L (``C``'s last body, at ``(0, 0, −L)`` below the
    sway joints) from the origin of a frame of attitude ``Rt`` (R_base_tip), angular
    velocity ``omega``, acceleration ``alpha``, origin acceleration ``a_t``; sway angles
    ``p1, p2`` about x then the rotated y of that frame, rates ``r1, r2``, viscous damping
    ``c1, c2`` [N·m·s/rad]; ``f`` a force on the payload [N] (base axes: the air's drag,
    :func:`drag_force`). With ``e = Rx(φ1) Ry(φ2) (0, 0, −1)`` (tip axes) the partial
    velocities are ``v_r = L Rt ∂e/∂φ_r`` and ``v_r · (m (a_p − g) − f) + c_r φ̇_r = 0``,
    where ``∂e/∂φ1 · ∂e/∂φ1 = cos²φ2``, ``∂e/∂φ2 · ∂e/∂φ2 = 1``,
    ``∂e/∂φ1 · ∂e/∂φ2 = 0``.
    """
    b = C.n_arm - 1
    m = C.arm_m[b]
    L = -C.arm_c[b, 2]
    e, e1, e2, acc, cos2 = sway_terms(Rt, omega, alpha, a_t, g, p1, p2, r1, r2, L, 0.0)
    mL = m * L
    ft = mtv(Rt, f)
    return (-(mL * dot(e1, acc) - L * dot(e1, ft) + c1 * r1) / (mL * L * cos2),
            -(mL * dot(e2, acc) - L * dot(e2, ft) + c2 * r2) / (mL * L), cos2)


def sway_terms(Rt, omega, alpha, a_t, g, p1, p2, r1, r2, L, Ld):
    """The pendulum's kinematics on a cable of length ``L`` [m] hoisted at ``Ld`` [m/s]:
    ``(e, ∂e/∂φ1, ∂e/∂φ2, acc, cos²φ2)`` with ``acc`` the payload's acceleration minus g,
    in tip axes, but for its φ̈ and L̈ terms.

    With ``ρ = L e`` in the tip frame (attitude ``Rt``, angular velocity ω), its rates in
    that frame ``ρ' = L̇ e + L ė`` and ``ρ'' = L̈ e + 2 L̇ ė + L ë``, the payload's
    acceleration is ``a_t + α × ρ + ω × (ω × ρ) + 2 ω × ρ' + ρ''``: the hoisting adds
    ``2 L̇ (ω × e + ė) + L̈ e`` to the fixed-length pendulum's."""
    s1, k1, s2, k2 = sin(p1), cos(p1), sin(p2), cos(p2)
    e, e1, e2 = sway_direction(p1, p2)
    quad = axpy(r2 * r2, (s2, -s1 * k2, k1 * k2),
                axpy(2.0 * r1 * r2, (0.0 * s1, -k1 * s2, -s1 * s2),
                     scale((0.0 * s1, -s1 * k2, k1 * k2), r1 * r1)))
    w = mtv(Rt, omega)
    rho = scale(e, L)
    edot = axpy(r2, e2, scale(e1, r1))
    acc = add(point_acceleration(mtv(Rt, sub(a_t, g)), w, mtv(Rt, alpha), rho),
              add(scale(cross(w, edot), 2.0 * L), scale(quad, L)))
    acc = add(acc, scale(add(cross(w, e), edot), 2.0 * Ld))
    return e, e1, e2, acc, k2 * k2


def hoisted_pendulum(C, Rt, omega, alpha, a_t, g, p1, p2, r1, r2, c1, c2, f, L, Ld, Ldd):
    """Kane's equations of the sway speeds on a cable of length ``L(t)`` (a winch):
    ``(φ̈1, φ̈2, cos²φ2, pull, tension)``.

    As :func:`pendulum` with the length ``L`` [m], its rate ``Ld`` [m/s] and acceleration
    ``Ldd`` [m/s²] given (the payload mass m is ``C``'s last body's). The partial
    velocities of the sway speeds are ``v_r = L Rt ∂e/∂φ_r``, orthogonal to e, so ``L̈``
    does not enter the sway; it enters the pull: ``pull = m (g − a_p) + f`` [N, base
    axes], the cable's force on the robot, acting at the payload's point (the sway
    damping's moment makes it leave the cable's line), and ``tension = pull · e`` [N]
    (> 0 taut), the line pull the winch holds.
    """
    m = C.arm_m[C.n_arm - 1]
    e, e1, e2, acc, cos2 = sway_terms(Rt, omega, alpha, a_t, g, p1, p2, r1, r2, L, Ld)
    mL = m * L
    ft = mtv(Rt, f)
    a1 = -(mL * dot(e1, acc) - L * dot(e1, ft) + c1 * r1) / (mL * L * cos2)
    a2 = -(mL * dot(e2, acc) - L * dot(e2, ft) + c2 * r2) / (mL * L)
    full = add(acc, axpy(Ldd, e, scale(axpy(a2, e2, scale(e1, a1)), L)))
    return a1, a2, cos2, add(scale(mv(Rt, full), -m), f), -m * dot(full, e) + dot(ft, e)


def drag_force(v, k):
    """The air's drag on the payload, ``−k |v| v`` [N], at its velocity ``v`` [m/s]
    relative to still air (base axes); ``k = ½ ρ C_d A`` [kg/m] (0: none)."""
    return scale(v, -k * sqrt(dot(v, v)))


def hanging_velocity(Rt, omega, v_tip, p1, p2, r1, r2, L, Ld):
    """The payload's velocity [m/s] (base axes) on a cable of length ``L`` [m] paid out at
    ``Ld`` [m/s] at the sway ``p1, p2`` [rad], ``r1, r2`` [rad/s], below a tip of attitude
    ``Rt``, angular velocity ``omega`` [rad/s] and velocity ``v_tip`` [m/s]:
    ``v_tip + ω × ρ + Rt (L ė + L̇ e)``, ``ρ = L Rt e``."""
    e, e1, e2 = sway_direction(p1, p2)
    rel = axpy(Ld, e, scale(axpy(r2, e2, scale(e1, r1)), L))
    return add(v_tip, add(cross(omega, mv(Rt, scale(e, L))), mv(Rt, rel)))


#: The largest ``1/cos²φ2`` the elastic cable's sway damping follows
#: (:func:`sway_damping_force`): the cable 5.7° from the tip's x axis. Nearer, the rigid
#: cable's damping of φ1 grows without bound (``c φ̇1`` with ``φ̇1 ~ 1/cos φ2`` for a given
#: payload speed): a free payload there would get a damping rate ``c / (m L² cos²φ2)``
#: that makes RK4 unstable once it exceeds 2.8 / step; capped, RK4 stays stable while
#: ``c / (m L²)`` < 0.028 / step (20 /s at a 1.4 ms step: ζ ≈ 3 on a 1 m cable).
SWAY_DAMPING_CONDITION = 100.0
#: Added to ``cos²φ2`` where it divides, so that the cable exactly along the tip's x axis
#: (``cos φ2 = 0``, φ1 undefined) gives a finite force (the term it weighs is then 0).
_TINY = 1e-300


def sway_damping_force(Rt, omega, rho, rhod, c1, c2):
    """The rigid cable's sway damping as a force on a free payload [N] (base axes): the
    elastic cable's, for which ``φ`` are the angles of the cable's direction in the tip
    frame (:func:`sway_direction`) and ``c1, c2`` [N·m·s/rad] their dampings.

    The payload at ``rho`` [m] from the tip, moving at ``rhod`` [m/s] (the rate of
    ``rho``, base axes), under a tip of attitude ``Rt`` and angular velocity ``omega``
    [rad/s]: with ``r = Rtᵀ ρ``, ``w = Rtᵀ (ρ̇ − ω × ρ)`` (its velocity relative to the tip
    frame, tip axes), ``u = r/|r|``, ``e1 = x × u`` (``= ∂e/∂φ1``, ``|e1|² = cos²φ2``,
    ê1 = e1/|e1|) the force ``F = −Σ_r c_r φ̇_r ∇φ_r`` does the work of the rigid cable's
    ``−c_r φ̇_r`` on the two angles (``v_r · F = −c_r φ̇_r``, ``F ⟂ u``):

    ``F = −(c2 w⊥ + (c1 / cos²φ2 − c2) (w · ê1) ê1) / |r|²``;

    with ``c1 = c2 = c``, ``−c (w⊥ + tan²φ2 (w · ê1) ê1) / |r|²``: isotropic transverse
    damping ``c / |r|²`` of the payload's motion across the cable, plus the part the
    angles' parametrisation adds along ê1 (the rigid cable's per-angle damping also acts
    on the cable link's spin about its own axis, ``φ̇1 sin φ2``). So the elastic cable
    tends to the damped rigid cable as EA → ∞. ``1/cos²φ2`` is capped at
    :data:`SWAY_DAMPING_CONDITION`.
    """
    r = mtv(Rt, rho)
    w = mtv(Rt, sub(rhod, cross(omega, rho)))
    d2 = dot(r, r)
    u = scale(r, 1.0 / sqrt(d2))
    e1 = (0.0 * u[0], -u[2], u[1])
    cos2 = u[1] * u[1] + u[2] * u[2] + _TINY
    tan2 = u[0] * u[0] / cos2
    cap = SWAY_DAMPING_CONDITION - 1.0
    extra = c1 * (1.0 + 0.5 * (tan2 + cap - abs(tan2 - cap))) - c2    # min(tan²φ2, cap)
    across = axpy(-dot(w, u), u, w)
    return mv(Rt, scale(axpy(extra * dot(w, e1) / cos2, e1, scale(across, c2)), -1.0 / d2))


def cable_force(C, store):
    """The cable's pull on the arm tip ``f_tip`` (3,) [N] (base axes) and its tension [N]
    (> 0 taut), from an arm pass at the true accelerations: the payload's
    ``m (a − g)`` reversed, and its component along the cable (tip → payload)."""
    b = C.n_arm - 1
    f = scale(take(store, b, F_), -1.0)
    rho = take(store, b, RC_)
    return f, dot(f, rho) / sqrt(dot(rho, rho))


def tip_state(C, q, qd):
    """The tip's (``arm_tip`` origin's) position [m] and velocity [m/s] in the base frame,
    under the robot's ``q, q̇`` (the arm chain ``C`` continued by the two sway joints)."""
    p, v, _, _ = tip_frame(C, q, qd)
    return p, v


def tip_frame(C, q, qd):
    """:func:`tip_state` and the tip's frame: ``(p [m], v [m/s], R_base_tip, ω
    [rad/s])``, the attitude and angular velocity being :func:`tip_motion`'s (the same
    operations: one call where both are wanted)."""
    R, w4, w5, w6 = attitude(q)
    omega = platform_rates(w4, w5, qd, qd)[0]          # ω needs no acceleration
    p = (q[0], q[1], q[2])
    v = (qd[0], qd[1], qd[2])
    nb = C.n_arm - 2
    for b in range(nb):
        axis = row3(C.arm_axis, b)
        r, Rj, z = arm_joint(R, mat3(C.arm_Ro, b), row3(C.arm_t, b), axis)
        p = add(p, r)
        v = add(v, cross(omega, r))
        if C.arm_prism[b]:
            off = scale(z, q[6 + b])
            p = add(p, off)
            v = axpy(qd[6 + b], z, add(v, cross(omega, off)))
            R = Rj
        else:
            R = mm(Rj, axis_rotation(axis, cos(q[6 + b]), sin(q[6 + b])))
            omega = axpy(qd[6 + b], z, omega)
    r, Rt, _ = arm_joint(R, mat3(C.arm_Ro, nb), row3(C.arm_t, nb), row3(C.arm_axis, nb))
    return add(p, r), add(v, cross(omega, r)), Rt, omega


def cable_tension(rho, rhod, L, Ld, EA, c):
    """An elastic cable's law, before the clamp: ``(T, s, u)``.

    The payload at ``rho`` [m] from the tip, moving at ``rhod`` [m/s] relative to it
    (base axes); unstretched length ``L`` [m] paid out at ``Ld`` [m/s]; axial stiffness
    ``EA`` [N] (spring ``EA / L`` [N/m]) and damping ``c`` [N·s/m]. ``s = |ρ| − L`` the
    stretch [m], ``u = ρ / |ρ|`` the cable's direction (tip → payload) and
    ``T = EA s / L + c ṡ`` with ``ṡ = u · ρ̇ − L̇``. The cable pulls only when taut and
    pulling (``s > 0`` and ``T > 0``; else the tension is zero: the caller clamps)."""
    d = sqrt(dot(rho, rho))
    u = scale(rho, 1.0 / d)
    s = d - L
    return EA / L * s + c * (dot(u, rhod) - Ld), s, u


def tip_jacobian(C, q):
    """The tip's position [m] (base frame) and its partial derivatives with respect to
    the arm's coordinates q7, q8, … (one 3-vector each: ``z × (p_tip − o_j)`` for a
    revolute joint of axis z through o_j [m/rad], ``z`` for a slider [m/m]), for the
    robot's ``q`` (the arm chain ``C`` continued by the two sway joints)."""
    R = attitude(q)[0]
    p = (q[0], q[1], q[2])
    nb = C.n_arm - 2
    joints = []
    for b in range(nb):
        axis = row3(C.arm_axis, b)
        r, Rj, z = arm_joint(R, mat3(C.arm_Ro, b), row3(C.arm_t, b), axis)
        p = add(p, r)
        joints.append((p, z, C.arm_prism[b]))
        if C.arm_prism[b]:
            p = add(p, scale(z, q[6 + b]))
            R = Rj
        else:
            R = mm(Rj, axis_rotation(axis, cos(q[6 + b]), sin(q[6 + b])))
    tip = add(p, arm_joint(R, mat3(C.arm_Ro, nb), row3(C.arm_t, nb),
                           row3(C.arm_axis, nb))[0])
    return tip, [z if prism else cross(z, sub(tip, o)) for o, z, prism in joints]
