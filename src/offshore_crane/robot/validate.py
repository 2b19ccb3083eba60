"""Physical validity of a URDF, checked on every load.

A robot loaded from a description file is checked first, field by field, by
:mod:`offshore_crane.robot.description` (messages name the file and the field). This
module checks the URDF itself, whatever its origin (a description's expansion, or a
URDF given directly), before the solvers read it, naming the URDF link or joint:

- **Masses**: finite and ``≥ 0`` for every link.
- **Inertias** (about the centre of mass): finite and symmetric; principal moments
  ``λ ≥ 0`` (positive semi-definite) and the *triangle inequality*
  ``λ_i ≤ λ_j + λ_k`` for each moment, both with the relative tolerance
  :data:`INERTIA_RTOL` of ``λ_1 + λ_2 + λ_3`` (URDF files are often printed with 6–7
  significant digits; a thin disc sits exactly on the triangle boundary). For a link
  with mass these two conditions are exactly the inertias a non-negative density can
  produce: a positive definite inertia, or the two idealisations that are singular but
  physical, the slender rod (one zero moment, the other two equal; the legs'
  ``leg_*_radius = 0``, used by the thin-rod tests) and the point mass (all zero).
  Inverse dynamics never inverts an inertia, so neither costs accuracy. A massless link
  may have any PSD inertia satisfying the inequality (normally zero).
- **Lengths**: a revolute joint coaxial with its parent revolute joint (a zero-length
  link between them) is rejected.
- **Joint ranges**: every limited joint has ``lower < upper``; a leg's stroke also
  ``lower > 0``.
- **Home pose** (``q = 0`` except ``q3 = home_height``; inferred from the U-joint axes
  when not given): every sphere centre above its U-joint, every leg length
  inside its stroke (a leg that cannot reach its home pose), and the 6x6 Stewart matrix
  not singular (condition number below :data:`HOME_CONDITION_LIMIT`).

Structural problems (missing joints, wrong joint types) are left to
:func:`offshore_crane.robot.hybrid.hybrid_from_urdf`, which names them.
"""

from __future__ import annotations

import re

import numpy as np

from offshore_crane.conventions import INERTIA_RTOL
from offshore_crane.errors import ModelError
from offshore_crane.robot.urdf import MOVABLE, URDF

#: A design whose Stewart matrix at the home pose has a larger 1-norm condition number
#: is rejected (the default error threshold of the singularity policy, kinematics/workspace.py).
HOME_CONDITION_LIMIT = 1e8

_LEG = re.compile(r"^leg(\d+)_(lower|upper|u1|u2|slide)$")


def _generic(name: str) -> str:
    m = _LEG.match(name)
    return f"leg_{m.group(2)}" if m else name


def validate(urdf: URDF, home_height: float | None = None) -> None:
    """Check masses, inertias, joint ranges and the home pose (module docstring).

    Args:
        urdf: The parsed URDF (:func:`offshore_crane.robot.urdf.parse_urdf`).
        home_height: q3 of the home pose [m] when known (a description gives it); None:
            inferred from the U-joint frames.

    Raises:
        ModelError: the first violation, naming the link or joint (``element``).
    """
    _check_inertials(urdf)
    _check_joints(urdf)
    _check_home(urdf, home_height)


def _check_inertials(urdf: URDF) -> None:
    for link, inertial in urdf.inertials.items():
        if inertial is None:
            continue
        m = inertial.mass
        if not np.isfinite(m) or m < 0.0:
            what = "is not finite" if not np.isfinite(m) else "is negative"
            raise ModelError(f"link '{link}': mass {m:g} kg {what}; give a mass >= 0",
                             element=link)
        I = inertial.inertia
        if not np.all(np.isfinite(I)):
            raise ModelError(f"link '{link}': inertia is not finite", element=link)
        scale = np.abs(I).max()
        if np.abs(I - I.T).max() > 1e-12 * scale:
            raise ModelError(f"link '{link}': inertia is not symmetric", element=link)
        lam = np.linalg.eigvalsh(0.5 * (I + I.T))          # ascending principal moments
        tol = INERTIA_RTOL * np.abs(lam).sum()
        moments = ", ".join(f"{x:.6g}" for x in lam)
        if lam[0] < -tol:
            raise ModelError(
                f"link '{link}': inertia is not positive definite, principal moments "
                f"({moments}) kg·m² include a negative one", element=link)
        if lam[2] > lam[0] + lam[1] + tol:
            raise ModelError(
                f"link '{link}': principal moments of inertia ({moments}) kg·m² violate "
                f"the triangle inequality ({lam[2]:.6g} > {lam[0]:.6g} + {lam[1]:.6g}); "
                "no rigid body has them", element=link)


def _check_joints(urdf: URDF) -> None:
    for j in urdf.joints.values():
        if j.type in ("revolute", "prismatic") and not (j.lower < j.upper):
            what = "the leg stroke" if _generic(j.name) == "leg_slide" else "limits"
            raise ModelError(f"joint '{j.name}': {what} [{j.lower + 0.0:g}, {j.upper + 0.0:g}] "
                             f"{'m' if j.type == 'prismatic' else 'rad'} is empty (need "
                             "lower < upper)", element=j.name)
        if j.name.endswith("_slide") and j.name.startswith("leg") and not j.lower > 0.0:
            raise ModelError(f"joint '{j.name}': the leg stroke starts at {j.lower:g} m; a "
                             "leg length must be positive", element=j.name)
        if j.type not in MOVABLE:
            continue
        parent = urdf.parent_joint.get(j.parent)
        pj = urdf.joints.get(parent) if parent else None
        if pj is None or pj.type != "revolute" or j.type != "revolute":
            continue
        axis = j.R @ j.axis                                  # in the parent link frame
        if (abs(abs(float(np.dot(axis, pj.axis))) - 1.0) < 1e-12
                and np.linalg.norm(np.cross(j.xyz, axis)) <= 1e-12):
            raise ModelError(f"joint '{j.name}' is coaxial with joint '{pj.name}': link "
                             f"'{j.parent}' between them has zero length", element=j.parent)


def _leg_geometry(urdf: URDF):
    """``(P (6, 3), R_U (6, 3, 3), s (6, 3), stroke (6, 2))`` or None if not a 6-leg robot."""
    try:
        anchors = {name: p for name, p, _ in urdf.rigid_group("platform")}
        rows = []
        for i in range(1, 7):
            u1, sl = urdf.joints[f"leg{i}_u1"], urdf.joints[f"leg{i}_slide"]
            rows.append((u1.xyz, u1.R, anchors[f"platform_anchor{i}"], (sl.lower, sl.upper)))
    except KeyError:
        return None
    P, RU, s, stroke = (np.array([r[k] for r in rows]) for k in range(4))
    return P, RU, s, stroke


def home_height(urdf: URDF) -> float | None:
    """q3 of the home pose inferred from the U-joint frames (None if not a 6-leg robot).

    A description orients each U-joint frame by default so that its z axis points at
    S_i at home; with ``S_i = s_i + h e_z`` that fixes ``h`` (least squares over the
    legs). For U-joints oriented otherwise the estimate is only indicative.
    """
    geo = _leg_geometry(urdf)
    if geo is None:
        return None
    P, RU, s, _ = geo
    num = den = 0.0
    for i in range(6):
        z = RU[i][:, 2]
        c = np.cross(np.array([0.0, 0.0, 1.0]), z)      # (d0 + h e_z) × z = 0
        num -= float(np.dot(np.cross(s[i] - P[i], z), c))
        den += float(np.dot(c, c))
    return num / den if den > 0.0 else None


def _check_home(urdf: URDF, h: float | None) -> None:
    geo = _leg_geometry(urdf)
    if h is None:
        h = home_height(urdf)
    if geo is None or h is None:
        return
    P, RU, s, stroke = geo
    hh = f" (home height {h:g} m)"
    d = s + np.array([0.0, 0.0, h]) - P                     # S_i − P_i at home, R = I
    length = np.linalg.norm(d, axis=1)
    for i in range(6):
        if d[i, 2] <= 0.0:
            raise ModelError(
                f"at the home pose sphere centre S{i + 1} is {-d[i, 2]:.4g} m below its "
                f"U-joint (platform below the base){hh}", element=f"leg{i + 1}_slide")
        lo, hi = stroke[i]
        if not lo <= length[i] <= hi:
            raise ModelError(
                f"leg {i + 1} cannot reach the home pose: |P{i + 1}S{i + 1}| = "
                f"{length[i]:.6g} m is outside the stroke [{lo:g}, {hi:g}] m of joint "
                f"'leg{i + 1}_slide'{hh}", element=f"leg{i + 1}_slide")
    from offshore_crane.spatial import condition_1

    u = d / length[:, None]
    L = float(np.linalg.norm(s, axis=1).mean())
    A = np.concatenate([u.T, np.cross(s, u).T / L])[None] if L > 0 else None
    kappa = float(condition_1(A)[0]) if A is not None else np.inf
    if not kappa < HOME_CONDITION_LIMIT:
        raise ModelError(
            f"the legs are singular at the home pose (Stewart matrix condition number "
            f"{kappa:.3g}): move the anchors", element="platform")
