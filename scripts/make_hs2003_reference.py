"""Write tests/data/hs2003_reference.npz (provenance: tests/data/hs2003_reference.md): the leg forces of the Harib & Srinivasan (2003) 6-U-P-S
platform as the public re-implementation github.com/krex4715/stewart_platform_Dynamics
(get_Dynamics.m, commit 1c505b27, "[impl]") models it, with its three errors corrected,
on two smooth 6-DOF trajectories, in offshore-crane's coordinates.

The dynamics below is written from the equations (Newton-Euler of each leg about its
base joint, then of the platform), not translated from [impl]'s code. [impl]'s model:

- base frame z up, base joints b_i at z = 0 (radius 0.120 m, 20, 100, 140, 220, 260,
  340 deg); platform frame origin O2 = the platform's centre of mass, platform joints
  a_i at z = 0 of that frame (radius 0.095 m, 40, 80, 160, 200, 280, 320 deg); home
  0.39 m above the base;
- orientation by ZXZ Euler angles, R = Rz(phi) Rx(theta) Rz(psi) ([impl] adds 0.01 deg
  to its theta input; the angles here are the actual ones);
- gravity (0, 0, -9.8) m/s^2;
- each leg: an upper part (0.553 kg, centre of mass on the axis 0.1601 m from the
  platform joint) and a lower part (2.991 kg, 0.1658 m from the base joint), each
  symmetric about the leg axis, WITHOUT spin about it (leg angular velocity n x v_S / l):
  transverse moment about the centre of mass Inn = sqrt(I_x^2 + I_y^2) of [impl]'s
  I_1_*, I_2_*; the axial moment I_z multiplies only spin terms, which vanish;
- platform: 8.08 kg, inertia R Ipp R^T with [impl]'s Ipp in the platform frame;
- output: each actuator's force along the leg (base joint to platform joint), positive
  when it extends the leg.

The three corrections: (1) the platform's rotational equation takes the platform's
angular velocity and acceleration (from the ZXZ rates), where [impl] takes leg 1's;
(2) the third ZXZ rate axis is Rz(phi) Rx(theta) e_z = (sin phi sin theta, -cos phi sin
theta, cos theta) (and its time derivative in the angular acceleration), where [impl]
has cos theta in place of sin theta in the first component; (3) the leg's length
acceleration is a_S.n + (|v_S|^2 - ldot^2)/l: the second term uses the joint's
velocity, where [impl] uses the leg's position vector.

Ipp: [impl] writes its (3,1) entry 1.10079550e-6 and its (1,3) entry 1.0079550e-6.
``F1``, ``F2`` take the (1,3) value for both (the symmetric tensor a rigid body can
have); ``F1_ipp_as_written``, ``F2_ipp_as_written`` keep the asymmetric matrix.

Arrays (k = 1, 2): ``t{k}`` (N,) [s]; ``q{k}``, ``qd{k}``, ``qdd{k}`` (N, 9) in
offshore-crane's coordinates (docs/conventions.md: O2's position, roll, pitch, yaw with
R = Rz(q6) Ry(q5) Rx(q4), arm joints zero; rates and accelerations exact, converted
analytically from the ZXZ ones); ``F{k}``, ``F{k}_ipp_as_written`` (N, 6) [N];
``gravity`` (3,).

    python scripts/make_hs2003_reference.py [--out FILE] [--check FILE]
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

# [impl]'s numbers, SI
GRAVITY = 9.8
BASE_RADIUS, BASE_DEG = 0.120, (20, 100, 140, 220, 260, 340)
PLATFORM_RADIUS, PLATFORM_DEG = 0.095, (40, 80, 160, 200, 280, 320)
HOME_Z = 0.39
M_UPPER, M_LOWER, M_PLATFORM = 0.553, 2.991, 8.08          # m1, m2, mp [kg]
C_UPPER, C_LOWER = 0.1601, 0.1658                          # l1 (from S_i), l2 (from P_i) [m]
I_UPPER = (1.7648208e-4, 2.7088440e-3, 2.7881148e-3)       # I_1_x, I_1_y, I_1_z [kg m^2]
I_LOWER = (3.2057427e-3, 2.7092491e-2, 2.2567492e-2)       # I_2_x, I_2_y, I_2_z
IPP_AS_WRITTEN = np.array([[7.7193130e-2, -3.4624009e-7, 1.0079550e-6],
                           [-3.4624009e-7, 1.1936907e-1, 5.5786021e-5],
                           [1.10079550e-6, 5.5786021e-5, 7.7138054e-2]])
IPP_SYMMETRIC = IPP_AS_WRITTEN.copy()
IPP_SYMMETRIC[2, 0] = IPP_AS_WRITTEN[0, 2]


def _dot(x, y):
    return np.einsum("...i,...i->...", x, y)


def anchors():
    """Base joints b_i (base frame) and platform joints a_i (platform frame), (6, 3)."""
    def circle(r, degs):
        a = np.deg2rad(np.asarray(degs, float))
        return np.stack([r * np.cos(a), r * np.sin(a), np.zeros(6)], axis=1)
    return circle(BASE_RADIUS, BASE_DEG), circle(PLATFORM_RADIUS, PLATFORM_DEG)


def zxz(e):
    """R = Rz(phi) Rx(theta) Rz(psi) for e = (phi, theta, psi) (N, 3) -> (N, 3, 3)."""
    cf, sf = np.cos(e[:, 0]), np.sin(e[:, 0])
    ct, st = np.cos(e[:, 1]), np.sin(e[:, 1])
    cs, ss = np.cos(e[:, 2]), np.sin(e[:, 2])
    return np.stack([np.stack([cf * cs - sf * ct * ss, -cf * ss - sf * ct * cs, sf * st], -1),
                     np.stack([sf * cs + cf * ct * ss, -sf * ss + cf * ct * cs, -cf * st], -1),
                     np.stack([st * ss, st * cs, ct], -1)], axis=1)


def zxz_motion(e, ed, edd):
    """Platform angular velocity and acceleration (base frame) from ZXZ angles, rates
    and accelerations: omega = phid e_z + thetad Rz(phi) e_x + psid Rz(phi) Rx(theta) e_z."""
    cf, sf = np.cos(e[:, 0]), np.sin(e[:, 0])
    ct, st = np.cos(e[:, 1]), np.sin(e[:, 1])
    fd, td = ed[:, 0], ed[:, 1]
    z, one = np.zeros_like(cf), np.ones_like(cf)
    W = np.stack([np.stack([z, z, one], -1), np.stack([cf, sf, z], -1),
                  np.stack([sf * st, -cf * st, ct], -1)], axis=-1)
    Wd = np.stack([np.stack([z, z, z], -1), np.stack([-fd * sf, fd * cf, z], -1),
                   np.stack([fd * cf * st + td * sf * ct, fd * sf * st - td * cf * ct, -td * st], -1)],
                  axis=-1)
    w = np.einsum("nij,nj->ni", W, ed)
    return w, np.einsum("nij,nj->ni", W, edd) + np.einsum("nij,nj->ni", Wd, ed)


def leg_forces(p, pd, pdd, R, w, al, Ipp=IPP_SYMMETRIC, g=GRAVITY):
    """Actuator forces (N, 6) [N], positive = extension.

    p, pd, pdd (N, 3): O2's position in the base frame [m], velocity, acceleration;
    R (N, 3, 3) the platform's rotation; w, al (N, 3) its angular velocity and
    acceleration in the base frame.
    """
    b, a = anchors()
    gv = np.array([0.0, 0.0, -g])
    inn = np.hypot(*I_UPPER[:2]) + np.hypot(*I_LOWER[:2])  # both parts' transverse moments
    iaa = I_UPPER[2] + I_LOWER[2]                          # axial (no effect: no spin)

    s = np.einsum("nij,kj->nki", R, a)                     # O2 -> S_i, base axes (N, 6, 3)
    d = p[:, None] + s - b                                 # P_i -> S_i
    l = np.linalg.norm(d, axis=-1)
    n = d / l[..., None]
    w6, al6 = w[:, None], al[:, None]
    vS = pd[:, None] + np.cross(w6, s)
    aS = pdd[:, None] + np.cross(al6, s) + np.cross(w6, np.cross(w6, s))
    ld = _dot(vS, n)
    ldd = _dot(aS, n) + (_dot(vS, vS) - ld ** 2) / l       # correction 3
    wl = np.cross(n, vS) / l[..., None]                    # leg: no spin about n
    all_ = (np.cross(n, aS) - 2 * ld[..., None] * wl) / l[..., None]

    r_up = (l - C_UPPER)[..., None] * n                    # CoMs from P_i
    r_lo = C_LOWER * n
    a_up = (ldd[..., None] * n + 2 * ld[..., None] * np.cross(wl, n)
            + np.cross(all_, r_up) + np.cross(wl, np.cross(wl, r_up)))
    a_lo = np.cross(all_, r_lo) + np.cross(wl, np.cross(wl, r_lo))

    # moment about P_i the leg's motion and weight need (axisymmetric parts)
    wn, an = _dot(wl, n), _dot(all_, n)
    need = (iaa * an[..., None] * n + inn * (all_ - an[..., None] * n)
            + (iaa - inn) * wn[..., None] * np.cross(wl, n)
            + M_UPPER * np.cross(r_up, a_up - gv) + M_LOWER * np.cross(r_lo, a_lo - gv))
    # the U-joint carries a moment about [impl]'s c_i = e_z only; its component along n
    # is round-off (no spin, CoMs on the axis): it does not change the forces
    ez = np.array([0.0, 0.0, 1.0])
    need = need - (_dot(need, n) / n[..., 2])[..., None] * ez
    # force of leg i on the platform: f_i n_i + t_i with t_i from that moment balance
    t_i = np.cross(n, need) / l[..., None]

    # platform (CoM at O2): m (a - g) = sum F_i, I al + w x I w = sum s_i x F_i
    Ip = np.einsum("nij,jk,nlk->nil", R, np.asarray(Ipp, float), R)
    rhs = np.concatenate([M_PLATFORM * (pdd - gv) - t_i.sum(1),
                          np.einsum("nij,nj->ni", Ip, al) + np.cross(w, np.einsum("nij,nj->ni", Ip, w))
                          - np.cross(s, t_i).sum(1)], axis=-1)
    A = np.concatenate([n, np.cross(s, n)], axis=-1)      # row i: (n_i, s_i x n_i)
    f = np.linalg.solve(np.swapaxes(A, 1, 2), rhs[..., None])[..., 0]
    # the upper part along n: m1 (a_up - g).n = F_actuator - f
    return M_UPPER * _dot(a_up - gv, n) + f


# ---- offshore-crane's coordinates ---------------------------------------------------
def rpy_axes(ang, angd):
    """E with omega = E (rolld, pitchd, yawd) for R = Rz(yaw) Ry(pitch) Rx(roll), and dE/dt."""
    cp, sp = np.cos(ang[:, 1]), np.sin(ang[:, 1])
    cy, sy = np.cos(ang[:, 2]), np.sin(ang[:, 2])
    pd, yd = angd[:, 1], angd[:, 2]
    z, one = np.zeros_like(cp), np.ones_like(cp)
    E = np.stack([np.stack([cy * cp, sy * cp, -sp], -1), np.stack([-sy, cy, z], -1),
                  np.stack([z, z, one], -1)], axis=-1)
    Ed = np.stack([np.stack([-yd * sy * cp - pd * cy * sp, yd * cy * cp - pd * sy * sp, -pd * cp], -1),
                   np.stack([-yd * cy, -yd * sy, z], -1), np.stack([z, z, z], -1)], axis=-1)
    return E, Ed


def to_offshore_crane(R, w, al):
    """(roll, pitch, yaw), rates and accelerations (N, 3) of R, w, al (exact)."""
    ang = np.stack([np.arctan2(R[:, 2, 1], R[:, 2, 2]), np.arcsin(np.clip(-R[:, 2, 0], -1, 1)),
                    np.arctan2(R[:, 1, 0], R[:, 0, 0])], -1)
    E, _ = rpy_axes(ang, np.zeros_like(ang))
    angd = np.linalg.solve(E, w[..., None])[..., 0]
    E, Ed = rpy_axes(ang, angd)
    angdd = np.linalg.solve(E, (al - np.einsum("nij,nj->ni", Ed, angd))[..., None])[..., 0]
    return ang, angd, angdd


# ---- trajectories ----------------------------------------------------------------------
# per coordinate (x, y, z [m], phi, theta, psi [rad]): offset, [(amplitude, rad/s, phase)]
# theta stays >= 0.04 rad (ZXZ is singular at 0); yaw (~ phi + psi) within 18 deg
TRAJECTORIES = {
    1: [(0.0, [(0.010, 2.0, 0.0), (0.004, 5.1, 0.7)]),
        (0.0, [(0.008, 2.7, 1.1), (0.003, 6.3, 0.2)]),
        (HOME_Z, [(0.015, 3.1, 0.4), (0.005, 7.0, 1.9)]),
        (0.30, [(0.20, 1.7, 0.3), (0.10, 4.4, 2.0)]),
        (0.08, [(0.03, 2.3, 0.0), (0.01, 6.1, 1.2)]),
        (-0.25, [(-0.20, 1.7, 0.3), (0.08, 5.5, 0.9)])],
    2: [(0.005, [(0.012, 3.3, 0.5), (0.003, 8.0, 0.1)]),
        (-0.004, [(0.010, 2.1, 2.2), (0.004, 7.7, 1.0)]),
        (HOME_Z - 0.01, [(0.020, 2.5, 1.3), (0.004, 9.2, 0.3)]),
        (-1.2, [(0.30, 2.2, 0.9), (0.15, 6.6, 0.4)]),
        (0.10, [(0.04, 3.7, 0.2), (0.015, 8.3, 2.5)]),
        (1.15, [(-0.30, 2.2, 0.9), (0.12, 7.1, 0.6)])],
}


def trajectory(k, samples=401, duration=4.0):
    """t (N,) and the (N, 6) coordinates (p, ZXZ angles), rates and accelerations."""
    t = np.linspace(0.0, duration, samples)
    X, Xd, Xdd = (np.zeros((samples, 6)) for _ in range(3))
    for j, (offset, terms) in enumerate(TRAJECTORIES[k]):
        X[:, j] = offset
        for amp, om, ph in terms:
            X[:, j] += amp * np.sin(om * t + ph)
            Xd[:, j] += amp * om * np.cos(om * t + ph)
            Xdd[:, j] -= amp * om * om * np.sin(om * t + ph)
    return t, X, Xd, Xdd


def reference(k):
    """t, q, qd, qdd (offshore-crane) and the forces (symmetric Ipp, Ipp as written)."""
    t, X, Xd, Xdd = trajectory(k)
    R = zxz(X[:, 3:])
    w, al = zxz_motion(X[:, 3:], Xd[:, 3:], Xdd[:, 3:])
    args = (X[:, :3], Xd[:, :3], Xdd[:, :3], R, w, al)
    ang, angd, angdd = to_offshore_crane(R, w, al)
    zero = np.zeros((len(t), 3))
    q = np.concatenate([X[:, :3], ang, zero], 1)
    qd = np.concatenate([Xd[:, :3], angd, zero], 1)
    qdd = np.concatenate([Xdd[:, :3], angdd, zero], 1)
    return t, q, qd, qdd, leg_forces(*args, Ipp=IPP_SYMMETRIC), leg_forces(*args, Ipp=IPP_AS_WRITTEN)


def arrays():
    out = {"gravity": np.array([0.0, 0.0, -GRAVITY])}
    for k in TRAJECTORIES:
        t, q, qd, qdd, F, Fw = reference(k)
        out.update({f"t{k}": t, f"q{k}": q, f"qd{k}": qd, f"qdd{k}": qdd,
                    f"F{k}": F, f"F{k}_ipp_as_written": Fw})
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(Path(__file__).resolve().parents[1] / "tests"
                                         / "data" / "hs2003_reference.npz"))
    ap.add_argument("--check", metavar="FILE", help="compare with an existing file instead of writing")
    args = ap.parse_args(argv)
    data = arrays()
    if args.check:
        old = np.load(args.check)
        for key in sorted(data):
            scale = max(np.abs(old[key]).max(), 1e-300)
            sys.stdout.write(f"{key}: max |new - file| / max |file| = {np.abs(data[key] - old[key]).max() / scale:.2e}\n")
        return 0
    np.savez_compressed(args.out, **data)
    sys.stdout.write(f"wrote {args.out}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
