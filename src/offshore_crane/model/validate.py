"""Physical validity of the robot description, checked on every load.

:func:`validate` runs on the parsed URDF (and the xacro arguments it was expanded with)
before the solvers read it, so that an invalid override fails at once with a message
naming the URDF link or joint and the xacro argument, instead of giving finite but
meaningless forces. What is checked:

- **Masses**: finite and ``≥ 0`` for every link, and every ``*_mass`` xacro argument
  ``≥ 0`` (the xacro drops a payload whose mass is not positive, so its sign must be
  checked on the argument).
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
- **Lengths**: the xacro's length arguments that size a link or place the anchors
  (:data:`POSITIVE_LENGTHS`) must be ``> 0`` (zero-length link), the radii, widths and
  thicknesses (:data:`NON_NEGATIVE_LENGTHS`) ``≥ 0``; with a URDF alone, a revolute
  joint coaxial with its parent revolute joint (a zero-length link between them) is
  rejected.
- **Joint ranges**: every limited joint has ``lower < upper``; a leg's stroke also
  ``lower > 0``.
- **Home pose** (``q = 0`` except ``q3 = home_height``; inferred from the U-joint axes
  when the argument is unknown): every sphere centre above its U-joint, every leg length
  inside its stroke (a leg that cannot reach its home pose), and the 6x6 Stewart matrix
  not singular (condition number below :data:`HOME_CONDITION_LIMIT`).

Structural problems (missing joints, wrong joint types) are left to
:func:`offshore_crane.model.hybrid.hybrid_from_urdf`, which names them.
"""

from __future__ import annotations

import re

import numpy as np

from ..conventions import INERTIA_RTOL
from ..errors import ModelError
from .urdf import MOVABLE, URDF

#: A design whose Stewart matrix at the home pose has a larger 1-norm condition number
#: is rejected (the default error threshold of the singularity policy, kinematics/workspace.py).
HOME_CONDITION_LIMIT = 1e8

#: Link (or ``leg_lower``/``leg_upper`` for ``leg{i}_...``) -> (mass argument, size
#: arguments) of the xacro, to name the argument behind a bad value.
LINK_ARGUMENTS = {
    "platform": ("platform_mass", ("platform_plate_radius", "platform_thickness")),
    "leg_lower": ("leg_lower_mass", ("leg_lower_radius", "leg_lower_length")),
    "leg_upper": ("leg_upper_mass", ("leg_upper_radius", "leg_upper_length")),
    "arm_column": ("column_mass", ("column_radius", "column_height")),
    "arm_link1": ("link1_mass", ("link1_length", "link1_width", "link1_height")),
    "arm_link2": ("link2_mass", ("link2_length", "link2_width", "link2_height")),
    "arm_slider": ("slider_mass", ("slider_length", "slider_width")),
    "payload": ("payload_mass", ("payload_ixx", "payload_iyy", "payload_izz", "payload_ixy",
                                 "payload_ixz", "payload_iyz")),
}
#: Length arguments that must be > 0, with what a zero value would mean.
POSITIVE_LENGTHS = {
    "base_radius": "all U-joint centres P_i would coincide",
    "platform_radius": "all sphere centres S_i would coincide",
    "platform_plate_radius": "link 'platform' would have zero diameter",
    "home_height": "the home pose would put the platform at or below the base",
    "leg_lower_length": "links 'leg{i}_lower' would have zero length",
    "leg_upper_length": "links 'leg{i}_upper' would have zero length",
    "column_height": "link 'arm_column' would have zero length",
    "link1_length": "link 'arm_link1' would have zero length (arm_joint2 on arm_joint1's "
                    "axis)",
    "link2_length": "link 'arm_link2' would have zero length",
    "slider_length": "link 'arm_slider' would have zero length",
    "leg_min_length": "the legs' stroke would start at zero length",
    "leg_max_length": "the legs' stroke would end at zero length",
}
#: Size arguments that must be >= 0 (zero is an idealisation: thin rod, flat plate).
NON_NEGATIVE_LENGTHS = ("leg_lower_radius", "leg_upper_radius", "column_radius",
                        "platform_thickness", "link1_width", "link1_height", "link2_width",
                        "link2_height", "slider_width")
#: Joint -> xacro argument(s) of its limits.
JOINT_ARGUMENTS = {
    "leg_u1": "ujoint_limit", "leg_u2": "ujoint_limit",
    "leg_slide": "leg_min_length, leg_max_length",
    "arm_joint1": "arm_joint1_limit", "arm_joint2": "arm_joint2_limit",
    "arm_slide": "arm_slide_limit",
}
_LEG = re.compile(r"^leg(\d+)_(lower|upper|u1|u2|slide)$")


def _generic(name: str) -> str:
    m = _LEG.match(name)
    return f"leg_{m.group(2)}" if m else name


def _args(names, arguments) -> str:
    """`` (xacro argument a = v)`` / ``(xacro arguments a = v, b = w)`` or ``""``."""
    if arguments is None:
        return ""
    known = [n for n in names if n in arguments]
    if not known:
        return ""
    label = "argument" if len(known) == 1 else "arguments"
    return f" (xacro {label} " + ", ".join(f"{n} = {arguments[n]}" for n in known) + ")"


def validate(urdf: URDF, arguments: dict | None = None) -> None:
    """Check masses, inertias, lengths, joint ranges and the home pose (module docstring).

    Args:
        urdf: The parsed URDF (:func:`offshore_crane.model.urdf.parse_urdf`).
        arguments: ``{xacro argument: value text}`` it was expanded with (defaults and
            overrides), used for the length checks, the home pose and the messages; None
            for a URDF of other origin.

    Raises:
        ModelError: the first violation, naming the link or joint (``element``) and the
            xacro argument behind it when known.
    """
    _check_inertials(urdf, arguments)
    if arguments is not None:
        _check_arguments(arguments)
    _check_joints(urdf, arguments)
    _check_home(urdf, arguments)


def _check_inertials(urdf: URDF, arguments) -> None:
    for link, inertial in urdf.inertials.items():
        if inertial is None:
            continue
        mass_arg, size_args = LINK_ARGUMENTS.get(_generic(link), (None, ()))
        m = inertial.mass
        if not np.isfinite(m) or m < 0.0:
            what = "is not finite" if not np.isfinite(m) else "is negative"
            raise ModelError(f"link '{link}': mass {m:g} kg {what}"
                             f"{_args([mass_arg], arguments)}; give a mass >= 0",
                             element=link)
        I = inertial.inertia
        where = _args([mass_arg, *size_args], arguments)
        if not np.all(np.isfinite(I)):
            raise ModelError(f"link '{link}': inertia is not finite{where}", element=link)
        scale = np.abs(I).max()
        if np.abs(I - I.T).max() > 1e-12 * scale:
            raise ModelError(f"link '{link}': inertia is not symmetric{where}", element=link)
        lam = np.linalg.eigvalsh(0.5 * (I + I.T))          # ascending principal moments
        tol = INERTIA_RTOL * np.abs(lam).sum()
        moments = ", ".join(f"{x:.6g}" for x in lam)
        if lam[0] < -tol:
            raise ModelError(
                f"link '{link}': inertia is not positive definite, principal moments "
                f"({moments}) kg·m² include a negative one{where}", element=link)
        if lam[2] > lam[0] + lam[1] + tol:
            raise ModelError(
                f"link '{link}': principal moments of inertia ({moments}) kg·m² violate "
                f"the triangle inequality ({lam[2]:.6g} > {lam[0]:.6g} + {lam[1]:.6g}); "
                f"no rigid body has them{where}", element=link)


def _check_arguments(arguments: dict) -> None:
    for name, value in arguments.items():       # also masses the xacro may leave out
        if name.endswith("_mass") and float(value) < 0.0:
            raise ModelError(f"xacro argument {name} = {value} kg is negative; give a mass "
                             ">= 0", element=name)
    for name, meaning in POSITIVE_LENGTHS.items():
        if name in arguments and not float(arguments[name]) > 0.0:
            raise ModelError(f"xacro argument {name} = {arguments[name]} m must be positive: "
                             f"{meaning}", element=name)
    for name in NON_NEGATIVE_LENGTHS:
        if name in arguments and float(arguments[name]) < 0.0:
            raise ModelError(f"xacro argument {name} = {arguments[name]} m must not be "
                             "negative", element=name)


def _check_joints(urdf: URDF, arguments) -> None:
    for j in urdf.joints.values():
        arg = JOINT_ARGUMENTS.get(_generic(j.name), "")
        where = _args([a.strip() for a in arg.split(",")], arguments) if arg else ""
        if j.type in ("revolute", "prismatic") and not (j.lower < j.upper):
            what = "the leg stroke" if _generic(j.name) == "leg_slide" else "limits"
            raise ModelError(f"joint '{j.name}': {what} [{j.lower + 0.0:g}, {j.upper + 0.0:g}] "
                             f"{'m' if j.type == 'prismatic' else 'rad'} is empty (need "
                             f"lower < upper){where}", element=j.name)
        if j.name.endswith("_slide") and j.name.startswith("leg") and not j.lower > 0.0:
            raise ModelError(f"joint '{j.name}': the leg stroke starts at {j.lower:g} m; a "
                             f"leg length must be positive{where}", element=j.name)
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


def home_height(urdf: URDF, arguments: dict | None = None) -> float | None:
    """Platform CoM height of the home pose: the argument, else from the U-joint axes.

    The xacro orients each U-joint frame so that its z axis points at S_i at home; with
    ``S_i = s_i + h e_z`` that fixes ``h`` (least squares over the legs).
    """
    if arguments is not None and "home_height" in arguments:
        return float(arguments["home_height"])
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


def _check_home(urdf: URDF, arguments) -> None:
    geo = _leg_geometry(urdf)
    h = home_height(urdf, arguments)
    if geo is None or h is None:
        return
    P, RU, s, stroke = geo
    hh = _args(["home_height"], arguments) or f" (home height {h:g} m)"
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
                f"'leg{i + 1}_slide'"
                f"{_args(['leg_min_length', 'leg_max_length', 'home_height'], arguments)}",
                element=f"leg{i + 1}_slide")
    from ..spatial import condition_1

    u = d / length[:, None]
    L = float(np.linalg.norm(s, axis=1).mean())
    A = np.concatenate([u.T, np.cross(s, u).T / L])[None] if L > 0 else None
    kappa = float(condition_1(A)[0]) if A is not None else np.inf
    if not kappa < HOME_CONDITION_LIMIT:
        raise ModelError(
            f"the legs are singular at the home pose (Stewart matrix condition number "
            f"{kappa:.3g}): move the anchors"
            + _args(["base_radius", "platform_radius", "base_half_angle_deg",
                     "platform_half_angle_deg"], arguments),
            element="platform")
