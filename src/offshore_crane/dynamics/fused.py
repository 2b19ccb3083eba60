"""Kane's method with the partial velocities factored: the fast default path.

Every body's partial velocities are linear images of a few *carrier* partials (paper
Eqs. 20-23, 30): for a body welded to the platform, ``v_r = v_r^{O2} + ω_r × ρ``; for a
leg link, ``ω_r = M v_r^{S}`` with the 3x3 map ``M`` of the closed-form leg kinematics;
for an arm body below joint j, ``v_r = z_j × (c − o_j)``. Kane's sums
``Σ v_r · F + ω_r · T`` can therefore be taken *before* the dot product with the carrier
partial, which replaces the per-body (N, 9, 3) partial-velocity arrays of the explicit
form (:mod:`.kane_hybrid`) by one wrench per carrier:

- each leg reduces to an equivalent force ``f_S`` at its sphere centre S_i:
  ``v_r^{ls}·F_ls + v_r^{lp}·F_lp + ω_r·(T_ls + T_lp) = v_r^{S}·f_S`` for all r, with
  ``f_S = F_ls + (M' × u)/l`` and ``M' = M − n (u·M)/(u·n)``, ``M`` the legs' moment
  about P_i (the U-joint spin enters through ``n = a1 × a2``);
- the platform rows ``r = 1..6`` are the wrench ``(F, M_O2)`` of everything the platform
  carries: ``B_r = e_r·F`` (r ≤ 3), ``B_r = w_r·M_O2`` (r = 4..6);
- arm row j is ``z_j · (moment about o_j of the bodies below j)`` (revolute) or
  ``z_j · (force of the bodies below j)`` (prismatic).

The leg forces then solve ``Σ_i Fl_i (u_i, r_i × u_i / L) = (F, M_O2 / L)`` (twist form,
``L`` a length scale making the matrix dimensionless): the 6x6 matrix is the classical
Stewart Jacobian (transposed), so the attitude-coordinate singularity at q5 = ±π/2 never
enters the solve (the explicit form's ``Jᵀ`` is that matrix times the attitude partials).

Arrays are component tuples ``(x, y, z)`` of shape ``(n,)`` or ``(6, n)`` (legs), so that
every NumPy call works on contiguous memory; samples are processed in chunks that stay in
the L2 cache. ``None`` stands for an exact zero (a static platform), so pruned terms
cost nothing. The results equal the explicit form's to round-off (tested).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from ..model.hybrid import HybridModel
from ..spatial import skew

LEG_MODELS = ("full", "thin-rod", "massless")
#: Samples per chunk of the vectorised kernel: (6, CHUNK) float arrays stay in L2 cache.
CHUNK = 4096
#: Up to this many samples, the kernel runs on Python floats, one sample at a time: the
#: same code, without NumPy's per-call overhead (~1 µs per call, ~900 calls per chunk).
SCALAR_MAX = 8
#: Leg diagnostics, each (N, 6): length l [m], U-joint angles θ1, θ2 [rad], cos θ2,
#: and height S_z − P_z [m] of the sphere centre above the U-joint centre.
DIAGNOSTICS = ("length", "theta1", "theta2", "cos_theta2", "height")

# --------------------------------------------------------------------------- helpers
# Vectors are 3-tuples of arrays or floats; matrices 3-tuples of row 3-tuples; None = 0.


def _cross(a, b):
    if a is None or b is None:
        return None
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _add(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _scale(a, s):
    return None if a is None else (a[0] * s, a[1] * s, a[2] * s)


def _sparse(v) -> tuple:
    """A constant vector as its non-zero ``(index, value)`` pairs."""
    return tuple((k, float(x)) for k, x in enumerate(v) if x != 0.0)


def _sparse_rows(C) -> tuple:
    return tuple(_sparse(row) for row in np.asarray(C, dtype=float))


def _sparse_cols(C) -> tuple:
    return _sparse_rows(np.asarray(C, dtype=float).T)


def _combine(v, cs):
    """Σ v[k] c_k over the sparse constant ``cs`` (no multiply for ones)."""
    if len(cs) == 1:
        k, ck = cs[0]
        return v[k] if ck == 1.0 else v[k] * ck
    if not cs:
        return 0.0
    terms = [v[k] if ck == 1.0 else v[k] * ck for k, ck in cs]
    acc = terms[0]
    for term in terms[1:]:
        acc = acc + term
    return acc


def _lin(R, cs):
    """``R @ c`` for a constant vector given sparse (:func:`_sparse`); None if c = 0."""
    if not cs:
        return None
    return (_combine(R[0], cs), _combine(R[1], cs), _combine(R[2], cs))


def _lin_t(R, v):
    """``Rᵀ v``."""
    r0, r1, r2 = R
    return (r0[0] * v[0] + r1[0] * v[1] + r2[0] * v[2],
            r0[1] * v[0] + r1[1] * v[1] + r2[1] * v[2],
            r0[2] * v[0] + r1[2] * v[1] + r2[2] * v[2])


def _const_lin(rows, v):
    """``C @ v`` for a constant matrix given by sparse rows (:func:`_sparse_rows`)."""
    return (_combine(v, rows[0]), _combine(v, rows[1]), _combine(v, rows[2]))


def _mat_const(R, cols):
    """``R @ C`` for a constant matrix given by sparse columns (:func:`_sparse_cols`)."""
    c = [_lin(R, col) or (0.0, 0.0, 0.0) for col in cols]
    return tuple(tuple(c[j][i] for j in range(3)) for i in range(3))


def _rotate_about_axis(Rj, axis: int, c, s):
    """``Rj @ Rot(e_axis, θ)`` with ``c = cos θ``, ``s = sin θ`` for a coordinate axis."""
    i, j = ((1, 2), (2, 0), (0, 1))[axis]      # the two columns that turn
    out = []
    for row in Rj:
        new = list(row)
        new[i] = row[i] * c + row[j] * s
        new[j] = row[j] * c - row[i] * s
        out.append(new)
    return out


def _mat_vec(R, v):
    """``R v``."""
    r0, r1, r2 = R
    return (r0[0] * v[0] + r0[1] * v[1] + r0[2] * v[2],
            r1[0] * v[0] + r1[1] * v[1] + r1[2] * v[2],
            r2[0] * v[0] + r2[1] * v[1] + r2[2] * v[2])


def _body_torque(R, I, omega, alpha):
    """``I_w α + ω × I_w ω`` with ``I_w = R I Rᵀ`` (computed in body axes)."""
    if omega is None and alpha is None:
        return None
    tb = None
    if alpha is not None:
        tb = _const_lin(I, _lin_t(R, alpha))
    if omega is not None:
        wb = _lin_t(R, omega)
        tb = _add(tb, _cross(wb, _const_lin(I, wb)))
    return _mat_vec(R, tb)


def _sum_legs(v):
    return tuple(x.sum(axis=0) for x in v)


# --------------------------------------------------------------------------- data
@dataclass(frozen=True)
class LegConsts:
    """Constants of the legs: arrays of shape (6, 1) for all legs, or floats for one."""

    s: tuple             # sphere centre S_i in the platform frame [m]
    P: tuple             # U-joint centre P_i in the base frame [m]
    X: tuple             # x axis of the U-joint frame (base)
    Z: tuple             # z axis (leg direction at zero angles)
    a1: tuple            # first U-joint axis (y of the U-joint frame)
    m_lo: object         # [kg]
    m_up: object         # [kg]
    c_lo: object         # CoM of the lower link: distance from P_i along u [m]
    c_up: object         # CoM of the upper link: distance from S_i along u [m]
    It: object           # transverse inertias of both links (sum) [kg·m²]
    Ia: object           # axial inertias of both links (sum) [kg·m²]


@dataclass(frozen=True)
class FusedData:
    """Constants of the fused kernel, read once from a :class:`HybridModel`.

    Attributes:
        model: The model.
        legs: :class:`LegConsts` of the six legs as (6, 1) arrays (vectorised path).
        leg_list: Six :class:`LegConsts` of floats (single-sample path).
        length_scale: L = mean |S_i − O2| [m], makes the Stewart Jacobian dimensionless.
        arm: Per arm joint, a dict of constants.
    """

    model: HybridModel
    platform_mass: float
    platform_com: tuple
    platform_inertia: tuple
    legs: LegConsts
    leg_list: tuple
    length_scale: float
    arm: list
    arrays: dict


def _axisymmetric(com, inertia, name):
    if not (np.allclose(com[:, :2], 0.0, rtol=0.0, atol=1e-12)
            and np.allclose(inertia[:, 0, 0], inertia[:, 1, 1], rtol=1e-12, atol=0.0)
            and np.allclose(inertia[:, [0, 0, 1], [1, 2, 2]], 0.0, rtol=0.0, atol=1e-15)):
        raise ModelError(f"the fused Kane path needs {name} links symmetric about the leg "
                         "axis (CoM on the axis, ixx = iyy, no products of inertia); use "
                         "method='kane-explicit' for this robot", element=name)
    return inertia[:, 0, 0], inertia[:, 2, 2]


def _coordinate_axis(axis) -> int | None:
    """0, 1 or 2 when ``axis`` is +x, +y or +z exactly, else None."""
    for k in range(3):
        if np.array_equal(axis, np.eye(3)[k]):
            return k
    return None


def prepare(model: HybridModel, dtype=np.float64) -> FusedData:
    """Read the kernel's constants from the model.

    Args:
        model: The robot's arrays.
        dtype: Floating type of the per-leg constant arrays; with ``np.float32`` (and
            float32 inputs) the vectorised kernel runs in single precision.

    Raises:
        ModelError: leg links not symmetric about the leg axis (the fused leg formulas
            assume it; the explicit Kane path does not).
    """
    It_lo, Ia_lo = _axisymmetric(model.lower_com, model.lower_inertia, "lower leg")
    It_up, Ia_up = _axisymmetric(model.upper_com, model.upper_inertia, "upper leg")

    def col(a):
        return np.ascontiguousarray(np.asarray(a, dtype=dtype)[:, None])

    def vec(a):
        return tuple(col(a[:, k]) for k in range(3))

    ch = model.arm
    arm = []
    for k in range(ch.n):
        K = skew(ch.axis[k])
        arm.append(dict(t=_sparse(ch.p_parent_joint[k]), Ro=_sparse_cols(ch.R_parent_joint[k]),
                        axis=_sparse(ch.axis[k]), K=_sparse_cols(K), K2=_sparse_cols(K @ K),
                        identity=bool(np.array_equal(ch.R_parent_joint[k], np.eye(3))),
                        coord_axis=_coordinate_axis(ch.axis[k]),
                        prismatic=bool(ch.prismatic[k]), mass=float(ch.mass[k]),
                        com=_sparse(ch.com[k]), inertia=_sparse_rows(ch.inertia[k])))
    per_leg = dict(s=model.p_platform_S, P=model.p_base_P, X=model.R_base_U[:, :, 0],
                   Z=model.R_base_U[:, :, 2], a1=model.R_base_U[:, :, 1],
                   m_lo=model.lower_mass, m_up=model.upper_mass, c_lo=model.lower_com[:, 2],
                   c_up=model.upper_com[:, 2], It=It_lo + It_up, Ia=Ia_lo + Ia_up)
    vectors = ("s", "P", "X", "Z", "a1")
    legs = LegConsts(**{k: vec(v) if k in vectors else col(v) for k, v in per_leg.items()})
    leg_list = tuple(
        LegConsts(**{k: tuple(float(x) for x in v[i]) if k in vectors else float(v[i])
                     for k, v in per_leg.items()})
        for i in range(len(model.lower_mass)))
    ch = model.arm
    arrays = dict(
        plat_m=float(model.platform_mass), plat_c=model.platform_com.copy(),
        plat_I=model.platform_inertia.copy(),
        arm_t=ch.p_parent_joint.copy(), arm_Ro=ch.R_parent_joint.copy(),
        arm_axis=ch.axis.copy(), arm_prism=ch.prismatic.copy(), arm_m=ch.mass.copy(),
        arm_c=ch.com.copy(), arm_I=ch.inertia.copy(),
        leg_s=model.p_platform_S.copy(), leg_P=model.p_base_P.copy(),
        leg_X=np.ascontiguousarray(model.R_base_U[:, :, 0]),
        leg_Y=np.ascontiguousarray(model.R_base_U[:, :, 1]),
        leg_Z=np.ascontiguousarray(model.R_base_U[:, :, 2]),
        m_lo=model.lower_mass.copy(), m_up=model.upper_mass.copy(),
        c_lo=model.lower_com[:, 2].copy(), c_up=model.upper_com[:, 2].copy(),
        It=It_lo + It_up, Ia=Ia_lo + Ia_up,
        L=float(np.linalg.norm(model.p_platform_S, axis=1).mean()))
    return FusedData(model=model, arrays=arrays, platform_mass=float(model.platform_mass),
                     platform_com=_sparse(model.platform_com),
                     platform_inertia=_sparse_rows(model.platform_inertia),
                     legs=legs, leg_list=leg_list,
                     length_scale=float(np.linalg.norm(model.p_platform_S, axis=1).mean()),
                     arm=arm)


@dataclass(frozen=True)
class Options:
    """What the fused kernel computes.

    Attributes:
        leg_model: ``"full"`` (exact: U-joint spin, both links' full inertia),
            ``"thin-rod"`` (approximation: the legs' axial inertia is dropped and the leg
            spin ignored, the paper's Eq. 12), ``"massless"`` (approximation: the legs
            carry no inertia or weight).
        legs: Compute the leg forces. False (only arm outputs wanted) skips the leg
            kinematics, the platform's loads and the 6x6 solve: exact for T1, T2, Fs.
        platform_static: q̇ = q̈ = 0 for q1..q6: the platform's velocity and acceleration
            terms are skipped (exact; the caller checks the premise).
        conditioning: Also return the 1-norm condition number of the 6x6 solve.
        diagnostics: Also return the legs' lengths and U-joint angles (for the
            workspace and singularity checks).
    """

    leg_model: str = "full"
    legs: bool = True
    platform_static: bool = False
    conditioning: bool = False
    diagnostics: bool = False


# --------------------------------------------------------------------------- kernel
def _platform(q, qd, qdd, static, xp=np):
    c4, s4 = xp.cos(q[3]), xp.sin(q[3])
    c5, s5 = xp.cos(q[4]), xp.sin(q[4])
    c6, s6 = xp.cos(q[5]), xp.sin(q[5])
    R = ((c6 * c5, c6 * s5 * s4 - s6 * c4, c6 * s5 * c4 + s6 * s4),
         (s6 * c5, s6 * s5 * s4 + c6 * c4, s6 * s5 * c4 - c6 * s4),
         (-s5, c5 * s4, c5 * c4))
    p = (q[0], q[1], q[2])
    if static:
        return R, p, None, None, None
    w4 = (c6 * c5, s6 * c5, -s5)      # partial angular velocities (Eq. 24)
    w5 = (-s6, c6)
    omega = (w4[0] * qd[3] + w5[0] * qd[4], w4[1] * qd[3] + w5[1] * qd[4],
             w4[2] * qd[3] + qd[5])
    # α = W q̈ + q̇4 (q̇6 z + q̇5 w5) × w4 + q̇5 q̇6 (z × w5)
    sw4 = _scale(_cross((w5[0] * qd[4], w5[1] * qd[4], qd[5]), w4), qd[3])
    q56 = qd[4] * qd[5]
    alpha = (w4[0] * qdd[3] + w5[0] * qdd[4] + sw4[0] - c6 * q56,
             w4[1] * qdd[3] + w5[1] * qdd[4] + sw4[1] - s6 * q56,
             w4[2] * qdd[3] + qdd[5] + sw4[2])
    return R, p, omega, alpha, (qdd[0], qdd[1], qdd[2])


def _accel_point(a, omega, alpha, r):
    """a + α × r + ω × (ω × r), with None for zero terms."""
    return _add(_add(a, _cross(alpha, r)), _cross(omega, _cross(omega, r)))


def _arm(fd: FusedData, R, omega, alpha, a, q, qd, qdd, g, xp=np):
    """Arm rows (list of (n,) arrays) and the arm's wrench (F, M about O2)."""
    neg_g = (-g[0], -g[1], -g[2])
    bodies = []
    for k, c in enumerate(fd.arm):
        qk, qdk, qddk = q[6 + k], qd[6 + k], qdd[6 + k]
        r = _lin(R, c["t"])
        Rj = R if c["identity"] else _mat_const(R, c["Ro"])
        z = _lin(Rj, c["axis"])
        a_j = _accel_point(a, omega, alpha, r)
        if c["prismatic"]:
            off = _scale(z, qk)
            Rc, w_c, al_c = Rj, omega, alpha
            a_c = _add(_add(_accel_point(a_j, omega, alpha, off),
                            _scale(_cross(omega, z), 2.0 * qdk)), _scale(z, qddk))
        else:
            off = None
            if c["coord_axis"] is not None:
                Rc = _rotate_about_axis(Rj, c["coord_axis"], xp.cos(qk), xp.sin(qk))
            else:
                s, cm = xp.sin(qk), 1.0 - xp.cos(qk)
                RK, RK2 = _mat_const(Rj, c["K"]), _mat_const(Rj, c["K2"])
                Rc = tuple(tuple(Rj[i][j] + s * RK[i][j] + cm * RK2[i][j] for j in range(3))
                           for i in range(3))
            w_c = _add(omega, _scale(z, qdk))
            al_c = _add(_add(alpha, _scale(z, qddk)), _scale(_cross(omega, z), qdk))
            a_c = a_j
        rc = _lin(Rc, c["com"])
        a_com = _accel_point(a_c, w_c, al_c, rc)
        F = _scale(_add(a_com, neg_g), c["mass"])
        T = _body_torque(Rc, c["inertia"], w_c, al_c)
        bodies.append((z, r, off, rc, F, T, c["prismatic"]))
        R, omega, alpha, a = Rc, w_c, al_c, a_c
    rows = [None] * len(bodies)
    F_acc = M = None
    for k in range(len(bodies) - 1, -1, -1):
        z, r, off, rc, F, T, prismatic = bodies[k]
        if F_acc is not None:   # shift the moment of bodies > k from o_{k+1} to o_k
            M = _add(M, _cross(_add(off, bodies[k + 1][1]), F_acc))
        M = _add(_add(M, T), _cross(_add(off, rc), F))
        F_acc = _add(F_acc, F)
        rows[k] = _dot(z, F_acc if prismatic else M)
    if not bodies:
        return [], None, None
    return rows, F_acc, _add(M, _cross(bodies[0][1], F_acc))


def _legs(fd: LegConsts, R, p, v, omega, alpha, a, g, leg_model, xp=np):
    """Leg unit vectors u, moment arms r × u / L, and the legs' resultant (F, M about O2).

    Kinematics of leg i (see :mod:`offshore_crane.kinematics.legs`): ``l u = S − P``,
    ``ω = ω⊥ − (ω⊥·n)/(u·n) u``, ``l̈ = a_S·u + l|ω×u|²``,
    ``e = α×u + ω×(ω×u) = (a_S − l̈ u − 2 l̇ ω×u)/l``, ``α·n = θ̇1 θ̇2``; with the U-joint
    frame axes X, Z: ``n = −(X (X·d) + Z (Z·d))/h``, ``u·n = −h/l``, ``h = |(X·d, Z·d)|``.
    """
    r = tuple(R[i][0] * fd.s[0] + R[i][1] * fd.s[1] + R[i][2] * fd.s[2] for i in range(3))
    d = _sub(_add(p, r), fd.P)
    length = xp.sqrt(_dot(d, d))
    il = 1.0 / length
    u = _scale(d, il)
    rxu = _cross(r, u)
    if leg_model == "massless":
        return u, rxu, None, None, d, length
    neg_g = (-g[0], -g[1], -g[2])
    if omega is None:                   # static platform: legs at rest, no spin terms
        F_lo = _scale(neg_g, fd.m_lo)
        F_up = _scale(neg_g, fd.m_up)
        M = _cross(u, _add(_scale(F_lo, fd.c_lo), _scale(F_up, fd.c_up)))
    else:
        wxr = _cross(omega, r)
        vS = _add(v, wxr)
        aS = _add(_add(a, _cross(alpha, r)), _cross(omega, wxr))
        rate = _dot(u, vS)
        w = _scale(_cross(u, vS), il)                        # ω⊥ (Eq. 12)
        if leg_model == "full":
            dlx, dlz = _dot(fd.X, d), _dot(fd.Z, d)
            ih = 1.0 / xp.sqrt(dlx * dlx + dlz * dlz)
            n = _scale(_add(_scale(fd.X, dlx), _scale(fd.Z, dlz)), -ih)
            l_h = length * ih                                # −1/(u·n)
            w = _add(w, _scale(u, _dot(w, n) * l_h))         # + U-joint spin
            a2 = _scale(_sub(_scale(fd.X, dlz), _scale(fd.Z, dlx)), ih)
            th12 = _dot(w, fd.a1) * _dot(w, a2)              # θ̇1 θ̇2
        wxu = _cross(w, u)
        accel = _dot(aS, u) + length * _dot(wxu, wxu)
        e = _scale(_sub(aS, _add(_scale(u, accel), _scale(wxu, 2.0 * rate))), il)
        alpha_perp = _cross(u, _sub(e, _cross(w, wxu)))
        F_lo = _scale(_add(_scale(e, fd.c_lo), neg_g), fd.m_lo)
        F_up = _scale(_add(_add(aS, _scale(e, fd.c_up)), neg_g), fd.m_up)
        if leg_model == "full":
            al = _add(alpha_perp, _scale(u, (_dot(alpha_perp, n) - th12) * l_h))
            # I α + ω × I ω for I = It (1 − u uᵀ) + Ia u uᵀ
            dI = fd.Ia - fd.It
            T = _add(_scale(al, fd.It),
                     _add(_scale(u, _dot(u, al) * dI), _scale(wxu, _dot(u, w) * dI)))
        else:
            T = _scale(alpha_perp, fd.It)                    # thin rods: no axial inertia
        M = _add(_cross(u, _add(_scale(F_lo, fd.c_lo), _scale(F_up, fd.c_up))), T)
        if leg_model == "full":
            M = _add(M, _scale(n, _dot(u, M) * l_h))         # M' = M − n (u·M)/(u·n)
    f_S = _add(F_up, _scale(_cross(M, u), il))
    return u, rxu, f_S, _cross(r, f_S), d, length


def _platform_wrench(fd: FusedData, R, omega, alpha, a, g):
    """The platform body's (F, M about O2): m (a_c − g) and T + ρ × F."""
    m = fd.platform_mass
    rho = _lin(R, fd.platform_com)
    a_c = _accel_point(a, omega, alpha, rho)
    F = _scale(_add(a_c, (-g[0], -g[1], -g[2])), m)
    T = _body_torque(R, fd.platform_inertia, omega, alpha)
    return F, _add(T, _cross(rho, F))


def _chunk(fd: FusedData, q, qd, qdd, g, opts: Options, diag=None):
    """Kernel on one chunk; ``q, qd, qdd`` are ``(9, n)``. Returns X ``(n, 9)``, cond.

    ``diag``, if given, is a dict of ``(n, 6)`` output views filled with the legs'
    lengths [m], U-joint angles θ1, θ2 [rad] and cos θ2 = |u·n|.
    """
    static = opts.platform_static
    R, p, omega, alpha, a = _platform(q, qd, qdd, static)
    v = None if static else (qd[0], qd[1], qd[2])
    arm_rows, F, M = _arm(fd, R, omega, alpha, a, q, qd, qdd, g)
    n = q.shape[1]
    X = np.full((n, 9), np.nan, dtype=q.dtype)   # NaN: not computed (no arm, no legs)
    for k, row in enumerate(arm_rows):
        X[:, k] = row
    if not opts.legs:
        return X, None
    u, rxu, F_legs, M_legs, d, length = _legs(fd.legs, R, p, v, omega, alpha, a, g,
                                              opts.leg_model)
    if F_legs is not None:
        F_legs, M_legs = _sum_legs(F_legs), _sum_legs(M_legs)
    Fp, Mp = _platform_wrench(fd, R, omega, alpha, a, g)
    F = _add(_add(F, Fp), F_legs) or (0.0, 0.0, 0.0)
    M = _add(_add(M, Mp), M_legs) or (0.0, 0.0, 0.0)
    iL = 1.0 / fd.length_scale
    A = np.empty((n, 6, 6), dtype=q.dtype)
    for k in range(3):
        A[:, k, :] = np.broadcast_to(u[k], (6, n)).T
        A[:, 3 + k, :] = (rxu[k] * iL).T
    rhs = np.empty((n, 6), dtype=q.dtype)
    for k in range(3):
        rhs[:, k] = F[k]
        rhs[:, 3 + k] = M[k] * iL
    X[:, 3:], cond = _solve_legs(A, rhs, opts.conditioning)
    if diag is not None:
        L = fd.legs
        dlx, dly, dlz = _dot(L.X, d), _dot(L.a1, d), _dot(L.Z, d)
        h = np.sqrt(dlx * dlx + dlz * dlz)
        diag["length"][:] = length.T
        diag["theta1"][:] = np.arctan2(dlx, dlz).T
        diag["theta2"][:] = np.arctan2(-dly, h).T
        diag["cos_theta2"][:] = (h / length).T
        diag["height"][:] = d[2].T
    return X, cond


def _solve_legs(A, rhs, conditioning):
    """Leg forces from the dimensionless Stewart system ``A Fl = rhs`` (..., 6, 6)."""
    if conditioning:
        Ainv = np.linalg.inv(A)
        X = np.einsum("...ij,...j->...i", Ainv, rhs)
        cond = np.abs(A).sum(axis=-2).max(axis=-1) * np.abs(Ainv).sum(axis=-2).max(axis=-1)
        return X, cond
    return np.linalg.solve(A, rhs[..., None])[..., 0], None


def _sample(fd: FusedData, q, qd, qdd, g, opts: Options, diag=None, k=0):
    """The kernel on one sample of Python floats (``q, qd, qdd``: lists of 9)."""
    static = opts.platform_static
    R, p, omega, alpha, a = _platform(q, qd, qdd, static, math)
    v = None if static else (qd[0], qd[1], qd[2])
    arm_rows, F, M = _arm(fd, R, omega, alpha, a, q, qd, qdd, g, math)
    X = np.full(9, np.nan)                         # NaN: not computed (no arm, no legs)
    X[:len(arm_rows)] = arm_rows
    if not opts.legs:
        return X, None
    Fp, Mp = _platform_wrench(fd, R, omega, alpha, a, g)
    F, M = _add(F, Fp), _add(M, Mp)
    iL = 1.0 / fd.length_scale
    A = np.empty((6, 6))
    for i, lc in enumerate(fd.leg_list):
        u, rxu, f_S, m_S, d, length = _legs(lc, R, p, v, omega, alpha, a, g, opts.leg_model,
                                            math)
        A[:3, i] = u
        A[3:, i] = rxu
        F, M = _add(F, f_S), _add(M, m_S)
        if diag is not None:
            dlx, dly, dlz = _dot(lc.X, d), _dot(lc.a1, d), _dot(lc.Z, d)
            h = math.hypot(dlx, dlz)
            diag["length"][k, i] = length
            diag["theta1"][k, i] = math.atan2(dlx, dlz)
            diag["theta2"][k, i] = math.atan2(-dly, h)
            diag["cos_theta2"][k, i] = h / length
            diag["height"][k, i] = d[2]
    F, M = F or (0.0, 0.0, 0.0), M or (0.0, 0.0, 0.0)
    A[3:] *= iL
    X[3:], cond = _solve_legs(A, np.array([F[0], F[1], F[2], M[0] * iL, M[1] * iL,
                                           M[2] * iL]), opts.conditioning)
    return X, cond


BACKENDS = ("auto", "numpy", "numba")


_NUMBA: list = []          # [bool]: is Numba installed? (looked up once)
_EMPTY_COND = np.empty(1)
_EMPTY_DIAG = np.empty((len(DIAGNOSTICS), 1, 6))


def numba_available() -> bool:
    """True when Numba is installed (looked up once, without importing it)."""
    if not _NUMBA:
        import importlib.util

        _NUMBA.append(importlib.util.find_spec("numba") is not None)
    return _NUMBA[0]


def _numba(fd: FusedData, q, qd, qdd, g, opts: Options):
    """The compiled kernel (:mod:`.fused_numba`) on float64 ``(N, 9)`` inputs."""
    if not numba_available():
        from ..errors import BackendMissingError

        raise BackendMissingError("backend='numba' needs Numba: pip install "
                                  "'offshore-crane[fast]' (or pip install numba)",
                                  package="numba")
    from .fused_numba import LEG_MODEL_CODES, kernel

    N = q.shape[0]
    X = np.empty((N, 9))
    cond = np.empty(N) if opts.conditioning and opts.legs else None
    diag = np.empty((len(DIAGNOSTICS), N, 6)) if opts.diagnostics and opts.legs else None
    a = fd.arrays
    kernel(np.ascontiguousarray(q, dtype=np.float64), np.ascontiguousarray(qd, dtype=np.float64),
           np.ascontiguousarray(qdd, dtype=np.float64), np.asarray(g, dtype=np.float64),
           a["plat_m"], a["plat_c"], a["plat_I"], a["arm_t"], a["arm_Ro"], a["arm_axis"],
           a["arm_prism"], a["arm_m"], a["arm_c"], a["arm_I"], a["leg_s"], a["leg_P"],
           a["leg_X"], a["leg_Y"], a["leg_Z"], a["m_lo"], a["m_up"], a["c_lo"], a["c_up"],
           a["It"], a["Ia"], a["L"], LEG_MODEL_CODES[opts.leg_model], opts.legs,
           opts.platform_static, cond is not None, diag is not None, X,
           _EMPTY_COND if cond is None else cond, _EMPTY_DIAG if diag is None else diag)
    if diag is not None:
        diag = dict(zip(DIAGNOSTICS, diag))
    return X, cond, diag


def fused_inverse_dynamics(fd: FusedData, q, qd, qdd, g, opts: Options = Options(),
                           chunk: int = CHUNK, backend: str = "auto"):
    """Actuator forces X ``(N, 9)`` by the fused kernel, chunk by chunk.

    Args:
        fd: From :func:`prepare`.
        q, qd, qdd: ``(N, 9)`` [m, rad], rates, accelerations.
        g: ``(3,)`` gravity [m/s²].
        opts: What to compute (:class:`Options`).
        chunk: Samples per chunk (memory stays O(chunk) besides the output).
        backend: ``"numpy"`` (vectorised kernel below), ``"numba"`` (the same formulas
            compiled, :mod:`.fused_numba`), or ``"auto"``: Numba when installed and the
            inputs are float64, else NumPy.

    Returns:
        ``(X, cond, diag)``: X ``(N, 9)`` (leg columns zero when ``opts.legs`` is
        False); the 1-norm condition number ``(N,)`` of the dimensionless Stewart
        Jacobian when ``opts.conditioning``, else None; with ``opts.diagnostics`` a dict
        of ``(N, 6)`` arrays ``length`` [m], ``theta1``, ``theta2`` [rad], ``cos_theta2``,
        else None.
    """
    if opts.leg_model not in LEG_MODELS:
        raise ValueError(f"unknown leg model '{opts.leg_model}'; use one of {LEG_MODELS}")
    if backend not in BACKENDS:
        raise ValueError(f"unknown backend '{backend}'; use one of {BACKENDS}")
    if backend == "numba" or (backend == "auto" and q.dtype == np.float64
                              and numba_available()):
        return _numba(fd, q, qd, qdd, g, opts)
    N = q.shape[0]
    X = np.empty((N, 9), dtype=q.dtype)
    with_legs = opts.legs
    cond = np.empty(N) if opts.conditioning and with_legs else None
    diag = ({k: np.empty((N, 6)) for k in DIAGNOSTICS}
            if opts.diagnostics and with_legs else None)
    g = tuple(float(x) for x in g)
    if N <= SCALAR_MAX:
        try:
            for k, (qk, qdk, qddk) in enumerate(zip(q.tolist(), qd.tolist(), qdd.tolist())):
                X[k], c = _sample(fd, qk, qdk, qddk, g, opts, diag, k)
                if cond is not None:
                    cond[k] = c
            return X, cond, diag
        except ZeroDivisionError:
            pass    # exactly singular (e.g. U-joint gimbal): arrays give inf/NaN instead
    # An exactly singular sample (a U-joint at gimbal lock, coincident anchors) yields
    # inf/NaN there, which the singularity policy of solve() reports; no FP warnings.
    with np.errstate(divide="ignore", invalid="ignore"):
        for start in range(0, N, chunk):
            sl = slice(start, min(start + chunk, N))
            Xc, cc = _chunk(fd, np.ascontiguousarray(q[sl].T), np.ascontiguousarray(qd[sl].T),
                            np.ascontiguousarray(qdd[sl].T), g, opts,
                            None if diag is None else {k: v[sl] for k, v in diag.items()})
            X[sl] = Xc
            if cond is not None:
                cond[sl] = cc
    return X, cond, diag
