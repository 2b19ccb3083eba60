"""The kinematics of the hybrid robot, written once, per sample.

Every formula of the platform, the legs and the arm recursion lives here and nowhere
else. It is plain arithmetic on *3-tuples* (vectors) and *3-tuples of row 3-tuples*
(matrices), with the math functions ``sqrt``, ``sin``, ``cos``, ``arctan2`` taken from
this module's globals, so that one text serves every backend
(:mod:`offshore_crane.dynamics.backends`):

- **NumPy** (vectorised): each scalar is an ``(n,)`` array of n samples; the functions
  below are called as they are;
- **Numba** (compiled): the same code objects, bound to a namespace in which every
  function of this module is a ``numba.njit`` dispatcher; scalars are floats;
- **Python floats** and **mpmath** (extended precision): the same code objects bound to
  ``math`` or ``mpmath`` functions.

So the text must stay *branch-free on values* (a ``numpy`` array has no truth value);
branches on *options* (a static platform, the leg model) are allowed: they are Python
booleans or integers, compile-time-like switches that skip what a scene does not need.

Frames and coordinates (``docs/conventions.md``): ``R`` maps platform (or body)
coordinates to base coordinates; vectors are in base axes unless named otherwise;
``q`` is indexable by 0..8 (q1..q9). Units: m, rad, s.
"""

from __future__ import annotations

from numpy import arctan2, cos, sin, sqrt

# Leg models (what the kernel computes for the legs; docs/conventions.md "Leg models").
FULL = 0        #: exact: U-joint spin, the links' full inertia
THIN_ROD = 1    #: approximation: no spin, no axial inertia, transverse inertia kept
MASSLESS = 2    #: approximation: the legs carry no inertia and no weight
LEG_MODEL_CODES = {"full": FULL, "thin-rod": THIN_ROD, "massless": MASSLESS}


# --------------------------------------------------------------------------- algebra
def add(a, b):
    """``a + b``."""
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    """``a − b``."""
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a, s):
    """``s a``."""
    return (a[0] * s, a[1] * s, a[2] * s)


def axpy(s, a, b):
    """``s a + b``."""
    return (a[0] * s + b[0], a[1] * s + b[1], a[2] * s + b[2])


def dot(a, b):
    """``a · b``."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    """``a × b``."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def mv(R, v):
    """``R v`` (``R`` by rows)."""
    return (R[0][0] * v[0] + R[0][1] * v[1] + R[0][2] * v[2],
            R[1][0] * v[0] + R[1][1] * v[1] + R[1][2] * v[2],
            R[2][0] * v[0] + R[2][1] * v[1] + R[2][2] * v[2])


def mtv(R, v):
    """``Rᵀ v``."""
    return (R[0][0] * v[0] + R[1][0] * v[1] + R[2][0] * v[2],
            R[0][1] * v[0] + R[1][1] * v[1] + R[2][1] * v[2],
            R[0][2] * v[0] + R[1][2] * v[1] + R[2][2] * v[2])


def mm(A, B):
    """``A B`` (both by rows)."""
    return ((A[0][0] * B[0][0] + A[0][1] * B[1][0] + A[0][2] * B[2][0],
             A[0][0] * B[0][1] + A[0][1] * B[1][1] + A[0][2] * B[2][1],
             A[0][0] * B[0][2] + A[0][1] * B[1][2] + A[0][2] * B[2][2]),
            (A[1][0] * B[0][0] + A[1][1] * B[1][0] + A[1][2] * B[2][0],
             A[1][0] * B[0][1] + A[1][1] * B[1][1] + A[1][2] * B[2][1],
             A[1][0] * B[0][2] + A[1][1] * B[1][2] + A[1][2] * B[2][2]),
            (A[2][0] * B[0][0] + A[2][1] * B[1][0] + A[2][2] * B[2][0],
             A[2][0] * B[0][1] + A[2][1] * B[1][1] + A[2][2] * B[2][1],
             A[2][0] * B[0][2] + A[2][1] * B[1][2] + A[2][2] * B[2][2]))


def row3(a, i):
    """Row ``i`` of a constant ``(m, 3)`` array as a vector."""
    return (a[i, 0], a[i, 1], a[i, 2])


def mat3(a, i):
    """Matrix ``i`` of a constant ``(m, 3, 3)`` array, by rows."""
    return ((a[i, 0, 0], a[i, 0, 1], a[i, 0, 2]),
            (a[i, 1, 0], a[i, 1, 1], a[i, 1, 2]),
            (a[i, 2, 0], a[i, 2, 1], a[i, 2, 2]))


def column(R, j):
    """Column ``j`` of ``R`` (by rows) as a vector."""
    return (R[0][j], R[1][j], R[2][j])


def point_velocity(v, omega, r):
    """Velocity of the point at ``r`` from a body's origin: ``v + ω × r`` [m/s]."""
    return add(v, cross(omega, r))


def point_acceleration(a, omega, alpha, r):
    """Acceleration of the point at ``r``: ``a + α × r + ω × (ω × r)`` [m/s²]."""
    return add(add(a, cross(alpha, r)), cross(omega, cross(omega, r)))


def axis_rotation(k, c, s):
    """Rotation ``exp(K θ)`` about the unit axis ``k`` with ``c = cos θ``, ``s = sin θ``
    (Rodrigues: ``I + s K + (1 − c) K²``), by rows."""
    t = 1.0 - c
    return ((1.0 - t * (k[1] * k[1] + k[2] * k[2]), t * k[0] * k[1] - s * k[2],
             t * k[0] * k[2] + s * k[1]),
            (t * k[0] * k[1] + s * k[2], 1.0 - t * (k[0] * k[0] + k[2] * k[2]),
             t * k[1] * k[2] - s * k[0]),
            (t * k[0] * k[2] - s * k[1], t * k[1] * k[2] + s * k[0],
             1.0 - t * (k[0] * k[0] + k[1] * k[1])))


def put(store, b, k, v):
    """``store[b, k:k+3] = v``."""
    store[b, k] = v[0]
    store[b, k + 1] = v[1]
    store[b, k + 2] = v[2]


def take(store, b, k):
    """``store[b, k:k+3]`` as a vector."""
    return (store[b, k], store[b, k + 1], store[b, k + 2])



# --------------------------------------------------------------------------- platform
def attitude(q):
    """``R_base_platform = Rz(q6) Ry(q5) Rx(q4)`` and the partial angular velocities
    ``w4 = Rz(q6) Ry(q5) x``, ``w5 = Rz(q6) y``, ``w6 = z`` (paper Eq. 24; erratum 1: the
    rotation is that of the coordinates, not ``exp(Ω̂ t)``)."""
    c4, s4 = cos(q[3]), sin(q[3])
    c5, s5 = cos(q[4]), sin(q[4])
    c6, s6 = cos(q[5]), sin(q[5])
    R = ((c6 * c5, c6 * s5 * s4 - s6 * c4, c6 * s5 * c4 + s6 * s4),
         (s6 * c5, s6 * s5 * s4 + c6 * c4, s6 * s5 * c4 - c6 * s4),
         (-s5, c5 * s4, c5 * c4))
    w4 = (c6 * c5, s6 * c5, -s5)
    w5 = (-s6, c6, 0.0)
    w6 = (0.0, 0.0, 1.0)
    return R, w4, w5, w6


def platform_rates(w4, w5, qd, qdd):
    """Angular velocity ``ω = Σ w_r q̇_r`` [rad/s] and acceleration [rad/s²] of the
    platform: ``α = Σ w_r q̈_r + q̇4 (q̇6 z + q̇5 w5) × w4 + q̇5 q̇6 (z × w5)``."""
    omega = (w4[0] * qd[3] + w5[0] * qd[4], w4[1] * qd[3] + w5[1] * qd[4],
             w4[2] * qd[3] + qd[5])
    turn = scale(cross((w5[0] * qd[4], w5[1] * qd[4], qd[5]), w4), qd[3])
    q56 = qd[4] * qd[5]
    alpha = (w4[0] * qdd[3] + w5[0] * qdd[4] + turn[0] - w5[1] * q56,
             w4[1] * qdd[3] + w5[1] * qdd[4] + turn[1] + w5[0] * q56,
             w4[2] * qdd[3] + qdd[5] + turn[2])
    return omega, alpha


def platform_partials(w4, w5, w6, rho, Vw, Ww):
    """Partials of a point at ``rho`` from O2 on the platform: ``v_r = e_r`` (r ≤ 3),
    ``ω_r × ρ`` (r = 4..6 with ω_r = w4, w5, w6), zero for the arm speeds."""
    W = (w4, w5, w6)
    for r in range(Vw.shape[0]):
        put(Ww, r, 0, scale(rho, 0.0))
        put(Vw, r, 0, scale(rho, 0.0))
    for r in range(3):
        Vw[r, r] = 1.0 + 0.0 * rho[0]
        put(Ww, 3 + r, 0, W[r])
        put(Vw, 3 + r, 0, cross(W[r], rho))



# --------------------------------------------------------------------------- legs
def leg_geometry(p, R, s, P, X, Y, Z):
    """Where leg i is: the U-joint frame's axes ``X, Y, Z`` (base), ``Y = a1``.

    Args:
        p: O2 [m]; ``R``: attitude; ``s``: S_i in the platform frame [m]; ``P``: P_i [m].

    Returns:
        ``(r, d, l, 1/l, u, dx, dy, dz, h)``: ``r = R s`` (O2 → S_i), ``d = S_i − P_i``,
        the length ``l`` [m], the unit vector ``u = d / l``, ``d``'s components in the
        U-joint frame and ``h = |(dx, dz)| = l cos θ2``.
    """
    r = mv(R, s)
    d = sub(add(p, r), P)
    length = sqrt(dot(d, d))
    il = 1.0 / length
    u = scale(d, il)
    dx, dy, dz = dot(X, d), dot(Y, d), dot(Z, d)
    return r, d, length, il, u, dx, dy, dz, sqrt(dx * dx + dz * dz)


def ujoint_axes(X, Z, dx, dz, h):
    """The U-joint's second axis ``a2`` (on the cross) and ``n = a1 × a2`` [unit].

    With θ1 = atan2(dx, dz): ``a2 = X cos θ1 − Z sin θ1``, ``n = −(X sin θ1 + Z cos θ1)``,
    and ``u · n = −h / l = −cos θ2`` (zero at the gimbal singularity).
    """
    ih = 1.0 / h
    a2 = scale(sub(scale(X, dz), scale(Z, dx)), ih)
    n = scale(add(scale(X, dx), scale(Z, dz)), -ih)
    return a2, n


def ujoint_angles(dx, dy, dz, h):
    """U-joint angles ``(θ1, θ2) = (atan2(dx, dz), atan2(−dy, h))`` [rad]: θ1 about
    a1, θ2 about a2; the leg direction in the U-joint frame is ``(cos θ2 sin θ1,
    −sin θ2, cos θ2 cos θ1)``."""
    return arctan2(dx, dz), arctan2(-dy, h)


def leg_spin(w, u, n, l_h):
    """Add the spin the U-joint imposes (erratum 3): ``ω = ω⊥ − (ω⊥·n)/(u·n) u`` with
    ``l_h = l / h = −1/(u·n)``, so that ``ω · n = 0`` (ω in span{a1, a2}).

    Linear in ``w``: maps the sphere centre's velocity (or a partial velocity) through
    ``ω⊥ = u × v_S / l`` to the leg's angular velocity (or partial angular velocity).
    """
    return axpy(dot(w, n) * l_h, u, w)


def leg_frame(u, a2):
    """``R_base_leg = R_base_U Ry(θ1) Rx(θ2)``: columns ``[a2, u × a2, u]`` (both leg
    links' frames; z along the leg), by rows."""
    b = cross(u, a2)
    return ((a2[0], b[0], u[0]), (a2[1], b[1], u[1]), (a2[2], b[2], u[2]))


def leg_motion(v_S, a_S, u, length, il, a1, a2, n, l_h, spin):
    """Leg rates from the sphere centre's velocity ``v_S`` and acceleration ``a_S``.

    ``ω⊥ = u × v_S / l`` (paper Eq. 12) plus the U-joint spin when ``spin``;
    accelerations derived (erratum 4): ``l̈ = a_S·u + l |ω×u|²``,
    ``e = α×u + ω×(ω×u) = (a_S − l̈ u − 2 l̇ ω×u)/l``, ``α⊥ = u × (e − ω × (ω×u))`` and,
    with the spin, ``α·n = θ̇1 θ̇2`` (``α = θ̈1 a1 + θ̈2 a2 + θ̇1 θ̇2 a1×a2``).

    Returns:
        ``(l̇ [m/s], l̈ [m/s²], ω [rad/s], α [rad/s²], ω×u, e, θ̇1, θ̇2 [rad/s])``;
        θ̇ are zero without ``spin``.
    """
    rate = dot(u, v_S)
    w = scale(cross(u, v_S), il)
    th1d = th2d = 0.0 * rate
    if spin:
        w = leg_spin(w, u, n, l_h)
        th1d, th2d = dot(w, a1), dot(w, a2)
    wxu = cross(w, u)
    accel = dot(a_S, u) + length * dot(wxu, wxu)
    e = scale(sub(a_S, add(scale(u, accel), scale(wxu, 2.0 * rate))), il)
    alpha = cross(u, sub(e, cross(w, wxu)))
    if spin:
        alpha = axpy((dot(alpha, n) - th1d * th2d) * l_h, u, alpha)
    return rate, accel, w, alpha, wxu, e, th1d, th2d


# --------------------------------------------------------------------------- arm
def arm_joint(R, Ro, t, axis):
    """Joint frame of an arm joint on a body at attitude ``R``: the offset ``r = R t``
    [m] from the body's origin to the joint's, ``R_j = R Ro`` and the axis ``z = R_j k``."""
    Rj = mm(R, Ro)
    return mv(R, t), Rj, mv(Rj, axis)


def arm_child(Rj, z, axis, omega, alpha, a_j, prismatic, q, qd, qdd):
    """The child body of a joint (paper Eqs. 27-30, recursive form).

    Args:
        Rj, z: joint frame and axis (base); ``axis``: the unit axis in the joint frame.
        omega, alpha: parent's angular velocity [rad/s] and acceleration [rad/s²].
        a_j: acceleration of the joint origin [m/s²].
        prismatic: joint type; ``q, qd, qdd``: its position [rad or m] and derivatives.

    Returns:
        ``(R_c, off, ω_c, α_c, a_c)``: the child's attitude, the offset ``off`` [m]
        from the joint origin to the child's origin (``z q`` for a slider, else zero),
        its angular velocity, acceleration and its origin's acceleration.
    """
    if prismatic:
        off = scale(z, q)
        a_c = axpy(qdd, z, axpy(2.0 * qd, cross(omega, z),
                                point_acceleration(a_j, omega, alpha, off)))
        return Rj, off, omega, alpha, a_c
    Rc = mm(Rj, axis_rotation(axis, cos(q), sin(q)))
    omega_c = axpy(qd, z, omega)
    alpha_c = axpy(qd, cross(omega, z), axpy(qdd, z, alpha))
    return Rc, (0.0 * q, 0.0 * q, 0.0 * q), omega_c, alpha_c, a_j
