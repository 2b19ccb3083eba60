"""MuJoCo model (MJCF) of the robot, with the six loops closed (``docs/mjcf.md``).

The model is generated from the robot's expanded URDF (the equivalent tree, parsed as
``robot.description``; the drawing from ``robot.urdf``) and nothing else: every mass,
centre of mass, inertia tensor, joint placement and axis is the URDF's. Plain XML
(:mod:`xml.etree`); writing a model needs no MuJoCo, loading and checking one does
(:func:`load`, :func:`forward`, optional extra ``mujoco``).

Structure (MuJoCo bodies, in the order of the URDF tree):

- ``platform``: one body carrying the six virtual joints of the URDF, in its order:
  slides ``platform_x``, ``platform_y``, ``platform_z`` (q1, q2, q3 [m]) then hinges
  ``platform_yaw`` (q6), ``platform_pitch`` (q5), ``platform_roll`` (q4) [rad]. MuJoCo
  applies the joints of one body in order, each about its axis in the frame the previous
  ones moved, so the platform's orientation is ``Rz(q6) Ry(q5) Rx(q4)``: the convention
  of ``docs/conventions.md``. (The URDF's massless links between them cannot be MuJoCo
  bodies: MuJoCo refuses a moving body without mass.) No motor, damping or armature.
- ``arm_column`` (welded to the platform), ``arm_link1``, ``arm_link2``, ``arm_slider``
  on hinges ``arm_joint1`` (q7), ``arm_joint2`` (q8) and slide ``arm_slide`` (q9);
  ``arm_tip`` and ``payload`` welded below (a site when massless). When the URDF has the
  hanging load's joints ``cable_joint1`` (about x of ``arm_tip``) and ``cable_joint2``
  (about y), they become two hinges of the ``payload`` body (phi1, phi2 [rad]).
- ``leg{i}_lower``: the U-joint, hinges ``leg{i}_u1`` (axis a1) then ``leg{i}_u2``;
  ``leg{i}_upper`` below it on slide ``leg{i}_slide``, whose position is the leg length
  [m]. The sites ``leg{i}_tip`` (on the upper link) and ``platform_anchor{i}`` (on the
  platform) are the sphere centre S_i seen from either side.
- ``<equality><connect site1="leg{i}_tip" site2="platform_anchor{i}">``: the spherical
  joints, which close the loops (MuJoCo's soft constraints, made as stiff as MuJoCo
  allows: :data:`SOLREF`, :data:`SOLIMP`).
- Motors with gear 1 on the nine actuated joints, named and ordered as X
  (``T1, T2, Fs, Fl1..Fl6``): ``data.ctrl`` is X [N·m, N].

Joint positions equal the URDF's (``ref`` sets each joint's value in the written
configuration, see :func:`_chain_placement`): ``qpos`` holds q1..q9 (platform rotations
in the order q6, q5, q4), the U-joint angles and the leg lengths (:attr:`MJCF.joints`).
The model is written in a configuration where the loops are closed, the robot's home
pose or a given ``q``, so that ``qpos0`` closes them; the keyframe ``hold`` holds that
pose with the static actuator forces as ``ctrl``.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import (ACTUATED_JOINTS, ACTUATORS, ARM_JOINTS, GRAVITY, N_LEGS,
                           PLATFORM_ANCHORS, PLATFORM_JOINTS, LEG_TIPS)
from offshore_crane.errors import InputError, ModelError
from offshore_crane.spatial import axis_angle_matrix, rpy_matrix

__all__ = ["MJCF", "export", "mjcf_from_urdf", "joint_values", "mujoco_state", "load",
           "forward", "MujocoForward", "AGREEMENT", "CABLE_JOINTS", "TIMESTEP", "INTEGRATOR", "SOLREF", "SOLIMP"]

#: Integration step of the written model [s] (``<option timestep>``); MuJoCo's
#: soft-constraint time constant may not be shorter than two steps (its ``refsafe``).
TIMESTEP = 1e-3
#: ``<option integrator>``: implicit in the velocity-dependent forces, explicit in the
#: constraint forces (MuJoCo's recommended default since 3.0).
INTEGRATOR = "implicitfast"
#: Loop constraints' ``solref``: time constant [s] and damping ratio. The shortest time
#: constant MuJoCo accepts at :data:`TIMESTEP` (2 steps), critically damped.
SOLREF = (2 * TIMESTEP, 1.0)
#: Loop constraints' ``solimp`` (dmin, dmax, width [m], midpoint, power): impedance
#: 0.9999 at every violation, MuJoCo's largest (mjMAXIMP). The constraint force then
#: meets the exact one up to a regulariser of relative size (1 - d)/d = 1e-4.
SOLIMP = (0.9999, 0.9999, 0.001, 0.5, 2.0)
#: MuJoCo's accelerations at our exact states meet ours to this, per coordinate, relative
#: to the largest acceleration the loop constraints produce (:meth:`MujocoForward.agreement`):
#: MuJoCo's regulariser makes the constraint forces err by ~(1 - d)/d = 1e-4 of
#: themselves (MuJoCo scales the regulariser by weights computed at qpos0, so the written
#: pose matters): measured 6.4e-5 for the model written at home, up to 2.1e-4 written
#: off home (benchmarks/mjcf_agreement.py, docs/mjcf.md); the bound is 2.4x above the
#: worst. A 1 % error in the upper leg links' mass gives 1.7e-3.
AGREEMENT = 5e-4
#: Constraint solver: Newton to a tight tolerance (the loops are the only constraints).
SOLVER, SOLVER_TOLERANCE, SOLVER_ITERATIONS = "Newton", 1e-12, 200
#: Joints of the hanging load (docs/cable.md) in the arm_tip frame: phi1 about x, phi2
#: about y.
CABLE_JOINTS = ("cable_joint1", "cable_joint2")
#: A mass below this [kg] counts as none (MuJoCo's mjMINVAL is 1e-15).
_MASSLESS = 1e-12
#: MuJoCo's compiler lower bound on a body's principal moments [kg·m²] (``boundinertia``):
#: it reaches only a point mass (the hanging payload, whose moments are zero); its effect
#: on the swing is 1e-12 / (m L²) relative (2e-12 for 2 kg on 0.5 m).
POINT_MASS_INERTIA = 1e-12


@dataclass(frozen=True)
class MJCF:
    """A MuJoCo model of the robot.

    Attributes:
        xml: The MJCF text.
        joints: Names of the model's joints in the order of ``qpos`` and ``qvel`` (all
            have one degree of freedom).
        actuators: Motor names in the order of ``ctrl`` (``T1, T2, Fs, Fl1..Fl6``, the
            arm's three absent for a Stewart platform alone).
        qpos0: ``(nq,)`` the written configuration [m, rad] (loops closed).
        hold: ``(nu,)`` static actuator forces holding ``qpos0`` [N·m, N] (the keyframe
            ``hold``'s ctrl), or None when not computed.
    """

    xml: str
    joints: tuple
    actuators: tuple
    qpos0: np.ndarray
    hold: np.ndarray | None = None


# --------------------------------------------------------------------------- our state
def _has_cable(robot) -> bool:
    """True when the robot's URDF hangs the payload on a cable; checks that a description
    asking for a cable (``payload.cable_length`` > 0) has one."""
    joints = robot.description.joints
    if all(name in joints for name in CABLE_JOINTS):
        return True
    values = getattr(robot.spec, "values", None) or {}
    length = values.get("payload.cable_length", 0.0)
    if length:
        raise ModelError(f"the description sets payload.cable_length = {length:g} m but its "
                         f"URDF has no joints {', '.join(CABLE_JOINTS)}: update the xacro "
                         "(docs/cable.md) before exporting the hanging load", element="payload")
    return False


def joint_values(robot, q, qd=None, sway=None, sway_rate=None) -> dict:
    """The URDF's joint positions and rates that close the loops at ``q``.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` coordinates [m, rad] (``docs/conventions.md``).
        qd: Same shape, rates [m/s, rad/s] (zero if omitted).
        sway: ``(N, 2)`` or ``(2,)`` cable angles (phi1, phi2) [rad] for a robot with a
            hanging load (zero if omitted); refused without one.
        sway_rate: Same shape, [rad/s].

    Returns:
        ``{joint name: (position (N,), rate (N,))}`` for every movable joint of the URDF:
        the platform's six virtual joints and the arm's (from q), the U-joint angles
        θ1, θ2 [rad] and the leg lengths [m] (:func:`offshore_crane.robot.kinematics.legs`), the
        cable joints (from ``sway``).

    Raises:
        InputError: bad shapes or non-finite values; ``sway`` for a robot without cable.
        ModelError: a movable URDF joint this function does not know.
    """
    from offshore_crane.robot.kinematics import legs
    from offshore_crane.validation import as_samples

    q = as_samples("q", q)[0]
    N = len(q)
    qd = np.zeros_like(q) if qd is None else as_samples("qd", qd)[0]
    if len(qd) != N:
        raise InputError(f"qd has {len(qd)} samples, q has {N}: give one rate per sample",
                         name="qd")
    out = {}
    for k, name in enumerate(PLATFORM_JOINTS):
        out[name] = (q[:, k], qd[:, k])
    if robot.hybrid.has_arm:
        for k, name in enumerate(ARM_JOINTS):
            out[name] = (q[:, 6 + k], qd[:, 6 + k])
    L = legs(robot, q, qd)
    for i in range(N_LEGS):
        out[f"leg{i + 1}_u1"] = (L.theta[:, i, 0], L.theta_d[:, i, 0])
        out[f"leg{i + 1}_u2"] = (L.theta[:, i, 1], L.theta_d[:, i, 1])
        out[f"leg{i + 1}_slide"] = (L.length[:, i], L.rate[:, i])
    if _has_cable(robot):
        s = np.zeros((N, 2)) if sway is None else as_samples("sway", sway, width=2)[0]
        sd = np.zeros((N, 2)) if sway_rate is None else as_samples("sway_rate", sway_rate,
                                                                    width=2)[0]
        for name, a in (("sway", s), ("sway_rate", sd)):
            if len(a) != N:
                raise InputError(f"{name} has {len(a)} samples, q has {N}", name=name)
        for k, name in enumerate(CABLE_JOINTS):
            out[name] = (s[:, k], sd[:, k])
    elif sway is not None or sway_rate is not None:
        raise InputError("sway given, but the robot has no hanging load (joints "
                         f"{', '.join(CABLE_JOINTS)}): leave it out", name="sway")
    movable = [j.name for j in robot.description.joints.values() if j.type != "fixed"]
    unknown = [name for name in movable if name not in out]
    if unknown:
        raise ModelError(f"the URDF has movable joints {unknown} that the MJCF export does "
                         "not know how to place: it knows the platform's, the legs', the "
                         "arm's and the cable's", element=unknown[0])
    return out


def _static_forces(robot, q: np.ndarray, gravity, sway=None) -> np.ndarray:
    """Actuator forces X ``(9,)`` [N·m, N] that hold ``q`` at rest.

    With a hanging load they come from ``offshore_crane.dynamics.cable.inverse_dynamics`` at the
    robot's rest, the payload at ``sway`` (default hanging straight down the tip frame's
    z) with no sway rate: the forces of that instant (an equilibrium when the cable is
    vertical).
    """
    if _has_cable(robot):
        from offshore_crane.dynamics import cable

        rest = np.repeat(q[None], 2, axis=0)
        res = cable.inverse_dynamics(robot, np.array([0.0, 1e-3]), rest, 0 * rest, 0 * rest,
                                     gravity=gravity, initial=(0.0, 0.0) if sway is None
                                     else np.reshape(sway, 2), limits=False)
        return np.asarray(res.X)[0]
    from offshore_crane.dynamics import inverse_dynamics

    zeros = np.zeros(9)
    return inverse_dynamics(robot, q, zeros, zeros, gravity=gravity)


# --------------------------------------------------------------------------- export
def export(robot, q=None, *, sway=None, gravity=GRAVITY, limits: bool = False,
           hold: bool = True, timestep: float = TIMESTEP) -> MJCF:
    """The robot as a MuJoCo model, written at ``q`` with the loops closed.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(9,)`` the configuration to write [m, rad]; default the home pose
            ``(0, 0, home_height, 0, 0, 0, 0, 0, 0)``. It must lie in the workspace.
        sway: ``(2,)`` cable angles (phi1, phi2) [rad] for a robot with a hanging load.
        gravity: ``(3,)`` [m/s²] in the base frame (``<option gravity>``).
        limits: False (the comparison model): no joint ranges, no force limits. True:
            the URDF's joint ranges on the legs' and arm's joints (never on the
            platform's virtual joints) and the motors' ``ctrlrange`` from
            ``robot.capacities`` (``[-pull_max, push_max]`` where finite).
        hold: Compute the static actuator forces at ``q`` for the keyframe ``hold``.
        timestep: ``<option timestep>`` [s]; the loops' time constant is two steps.

    Returns:
        :class:`MJCF`.

    Raises:
        InputError: a bad ``q``, ``sway``, ``gravity`` or ``timestep``.
        WorkspaceError: ``q`` outside the workspace (leg stroke, joint limits).
        ModelError: a URDF the exporter cannot map (unknown movable joints, a moving
            body without mass), or a hanging load without its dynamics module.
    """
    from offshore_crane.validation import as_gravity, as_samples

    g = as_gravity(gravity)
    if q is None:
        q = robot.home_pose()
    q = as_samples("q", q)[0]
    if len(q) != 1:
        raise InputError(f"q must be one configuration (9,), got {len(q)} samples",
                         name="q")
    q = q[0]
    if not (isinstance(timestep, (int, float)) and np.isfinite(timestep) and timestep > 0):
        raise InputError(f"timestep {timestep:g} s must be a finite number > 0",
                         name="timestep")
    values = joint_values(robot, q, sway=None if sway is None else np.reshape(sway, (1, -1)))
    positions = {name: float(v[0][0]) for name, v in values.items()}
    _check_limits(robot.description, positions, PLATFORM_JOINTS)
    X = _static_forces(robot, q, g, sway) if hold else None
    names = robot.hybrid.actuators
    joints = [ACTUATED_JOINTS[ACTUATORS.index(a)] for a in names]
    ranges = None
    if limits:
        caps = robot.capacities
        ranges = {a: (-caps.pull_max[ACTUATORS.index(a)], caps.push_max[ACTUATORS.index(a)])
                  for a in names}
    ctrl = None if X is None else np.array([X[ACTUATORS.index(a)] for a in names])
    model_name = robot.spec.name if robot.spec is not None else robot.description.name
    return mjcf_from_urdf(robot.urdf, positions, name=model_name, gravity=g,
                          actuators=list(zip(names, joints)), ctrlrange=ranges,
                          loops=list(zip(LEG_TIPS, PLATFORM_ANCHORS)), hold=ctrl,
                          joint_limits=limits, virtual=PLATFORM_JOINTS, timestep=timestep,
                          description=robot.description)


def _check_limits(urdf, positions: dict, virtual) -> None:
    """Every joint of the written configuration inside its URDF range (leg strokes,
    U-joint and arm limits; the platform's virtual joints have none).

    Raises:
        WorkspaceError: naming the joint, its value and its range.
    """
    from offshore_crane.errors import WorkspaceError

    for name, value in positions.items():
        j = urdf.joints[name]
        if name in virtual or j.type == "continuous":
            continue
        if not j.lower <= value <= j.upper:
            unit = "m" if j.type == "prismatic" else "rad"
            raise WorkspaceError(f"the pose puts joint '{name}' at {value:.6g} {unit}, outside its "
                                 f"range [{j.lower:g}, {j.upper:g}] {unit}: give a pose "
                                 "inside the workspace", joint=name, value=value)


def _num(x) -> str:
    """A float as MJCF text, round-tripping exactly (17 significant digits)."""
    x = float(x)
    return "0" if x == 0.0 else repr(x)


def _vec(v) -> str:
    return " ".join(_num(x) for x in v)


def _quat(R: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a rotation matrix (MuJoCo's order), Shepperd's
    method: the largest of the four squared components is taken first."""
    t = np.trace(R)
    d = np.array([t, R[0, 0], R[1, 1], R[2, 2]])
    k = int(np.argmax(d))
    if k == 0:
        w = np.sqrt(1.0 + t) / 2
        qv = np.array([w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w),
                       (R[1, 0] - R[0, 1]) / (4 * w)])
    else:
        i, j, m = k - 1, k % 3, (k + 1) % 3
        s = np.sqrt(1.0 + 2 * R[i, i] - t) / 2
        qv = np.empty(4)
        qv[0] = (R[m, j] - R[j, m]) / (4 * s)
        qv[1 + i] = s
        qv[1 + j] = (R[j, i] + R[i, j]) / (4 * s)
        qv[1 + m] = (R[m, i] + R[i, m]) / (4 * s)
    return qv if qv[0] >= 0 else -qv


def _placement(el, p: np.ndarray, R: np.ndarray) -> None:
    if np.any(p != 0):
        el.set("pos", _vec(p))
    if not np.allclose(R, np.eye(3), rtol=0, atol=1e-15):
        el.set("quat", _vec(_quat(R)))


# --------------------------------------------------------------------------- drawing
def _visuals(urdf_text: str) -> dict:
    """``{link: [(kind, size, p_link_geom (3,), R_link_geom (3, 3), rgba)]}`` from the
    URDF's ``<visual>`` elements (cylinder, box, sphere; other shapes are skipped)."""
    root = ET.fromstring(urdf_text)
    colours = {}
    for mat in root.findall("material"):
        c = mat.find("color")
        if mat.get("name") and c is not None and c.get("rgba"):
            colours[mat.get("name")] = c.get("rgba")
    out: dict = {}
    for link in root.findall("link"):
        shapes = []
        for vis in link.findall("visual"):
            geo = vis.find("geometry")
            origin = vis.find("origin")
            xyz = np.array([float(x) for x in (origin.get("xyz", "0 0 0") if origin is not
                                               None else "0 0 0").split()])
            rpy = [float(x) for x in (origin.get("rpy", "0 0 0") if origin is not None
                                      else "0 0 0").split()]
            rgba = "0.7 0.7 0.7 1"
            mat = vis.find("material")
            if mat is not None:
                c = mat.find("color")
                rgba = c.get("rgba") if c is not None else colours.get(mat.get("name"), rgba)
            shape = None if geo is None else next(iter(geo), None)
            if shape is None:
                continue
            if shape.tag == "cylinder":
                size = (float(shape.get("radius")), float(shape.get("length")) / 2)
            elif shape.tag == "box":
                size = tuple(float(x) / 2 for x in shape.get("size").split())
            elif shape.tag == "sphere":
                size = (float(shape.get("radius")),)
            else:
                continue
            shapes.append((shape.tag, size, xyz, rpy_matrix(rpy), rgba))
        out[link.get("name")] = shapes
    return out


# --------------------------------------------------------------------------- the tree
def _motion(joint, value: float) -> tuple[np.ndarray, np.ndarray]:
    """``(p, R)`` of a joint's own motion at ``value`` (in its joint frame)."""
    if joint.type == "prismatic":
        return joint.axis * value, np.eye(3)
    return np.zeros(3), axis_angle_matrix(joint.axis, np.asarray(value))


def _chain_placement(chain, positions: dict):
    """Body frame and joint axes of joints merged into one MuJoCo body.

    The URDF places the body's link at ``T(r) = E1 J1(r1) E2 J2(r2) ... En Jn(rn)``
    (``E_k`` the joints' origins, ``J_k`` their motions at the written values r). MuJoCo
    places a body at ``M exp(B1 Δ1) ... exp(Bn Δn)`` with ``Δ_k = qpos_k - ref_k``, each
    ``B_k`` a joint axis (through ``pos``) fixed in the body frame as written: the product
    of exponentials in body form. With ``M = T(r)``, ``ref_k = r_k`` and ``B_k`` the axis
    of joint k at the configuration r expressed in the frame ``T(r)``, both agree for
    every joint value: qpos is the URDF's joint position.

    Returns:
        ``(p_parent_body (3,), R_parent_body (3, 3), [(joint, axis (3,), point (3,),
        ref)])`` with axis and point in the body frame.
    """
    p, R = np.zeros(3), np.eye(3)
    axes = []
    for j in chain:
        p, R = p + R @ j.xyz, R @ j.R                 # the joint frame, before its motion
        axes.append((j, R @ j.axis, p.copy(), positions[j.name]))
        dp, dR = _motion(j, positions[j.name])
        p, R = p + R @ dp, R @ dR
    local = [(j, R.T @ a, R.T @ (c - p), r) for j, a, c, r in axes]
    return p, R, local


def _inertial(el, mass: float, com: np.ndarray, I: np.ndarray) -> None:
    """``<inertial>``: ``fullinertia`` (the URDF's six numbers) for a positive definite
    tensor, else its principal axes (``quat``) and moments (``diaginertia``), which
    MuJoCo accepts for a singular one (a point mass, a thin rod on a welded body)."""
    w, V = np.linalg.eigh(I)
    if w.min() > 1e-9 * max(w.max(), 0.0):
        ET.SubElement(el, "inertial", pos=_vec(com), mass=_num(mass),
                      fullinertia=_vec((I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2])))
        return
    if np.linalg.det(V) < 0:
        V[:, 2] = -V[:, 2]
    e = ET.SubElement(el, "inertial", pos=_vec(com), mass=_num(mass),
                      diaginertia=_vec(np.maximum(w, 0.0)))
    if not np.allclose(V, np.eye(3), rtol=0, atol=1e-15):
        e.set("quat", _vec(_quat(V)))


def _check_moving(urdf, joint: str, link: str) -> None:
    """MuJoCo refuses a moving body whose mass or a principal moment of inertia is zero
    (below its mjMINVAL, 1e-15): say which link, and what to give it. A point mass (mass,
    no inertia: the hanging payload) passes: the compiler's ``boundinertia``
    (:data:`POINT_MASS_INERTIA`) gives it the smallest moments.

    Raises:
        ModelError: naming the link.
    """
    from offshore_crane.robot.chain import merged_inertial

    mass, _, inertia, _ = merged_inertial(urdf, link)
    moments = np.linalg.eigvalsh(inertia) if mass > _MASSLESS else np.zeros(3)
    if mass > _MASSLESS and np.abs(inertia).max() <= 1e-15:
        return                                          # a point mass: boundinertia
    if mass <= _MASSLESS or moments.min() <= 1e-15:
        what = "no mass" if mass <= _MASSLESS else (
            f"principal moments of inertia {', '.join(f'{x:.3g}' for x in moments)} kg·m²")
        raise ModelError(f"joint '{joint}' moves link '{link}', which has {what}: MuJoCo "
                         "needs a positive mass and inertia on every moving body (give the "
                         "link a mass and a radius or inertia, or weld it)", element=link)


def _mergeable(urdf, visuals, link: str) -> str | None:
    """The single movable child joint of a massless, undrawn link (a virtual link or a
    U-joint cross, merged into its child's MuJoCo body), else None."""
    inertial = urdf.inertials.get(link)
    children = urdf.child_joints.get(link, [])
    if (inertial is not None and inertial.mass > _MASSLESS) or visuals.get(link) \
            or len(children) != 1:
        return None
    child = urdf.joints[children[0]]
    return child.name if child.type != "fixed" else None


def mjcf_from_urdf(urdf_text: str, positions: dict, *, name: str = "robot",
                   gravity=GRAVITY, actuators=(), ctrlrange: dict | None = None,
                   loops=(), hold=None, joint_limits: bool = False, virtual=(),
                   timestep: float = TIMESTEP, description=None) -> MJCF:
    """An MJCF model of any URDF tree, written at the given joint positions.

    Args:
        urdf_text: The URDF (its ``<visual>`` shapes are drawn, without collisions).
        positions: ``{joint name: position [m or rad]}`` for every movable joint: the
            written configuration (``qpos0``; each joint's ``ref``).
        name: Model name.
        gravity: ``(3,)`` [m/s²].
        actuators: ``[(motor name, joint name)]``, motors with gear 1 in ``ctrl`` order.
        ctrlrange: ``{motor name: (lower, upper)}`` [N·m or N], infinite bounds ignored;
            None: no control limits.
        loops: ``[(site1, site2)]``: massless links (URDF frames) joined by
            ``equality/connect`` (ball joints).
        hold: ``(len(actuators),)`` ctrl of the keyframe ``hold``, or None.
        joint_limits: Write the URDF's joint ranges (except on ``virtual`` joints).
        virtual: Joints that are coordinates rather than mechanisms (never limited).
        timestep: [s].
        description: The parsed URDF when the caller has it (else parsed here).

    Returns:
        :class:`MJCF`.

    Raises:
        ModelError: a joint without position, an unsupported joint type, a moving body
            without mass, a loop or actuator naming an unknown frame or joint.
    """
    from offshore_crane.robot.urdf import parse_urdf

    urdf = description if description is not None else parse_urdf(urdf_text)
    visuals = _visuals(urdf_text)
    missing = [j.name for j in urdf.joints.values()
               if j.type != "fixed" and j.name not in positions]
    if missing:
        raise ModelError(f"no position given for joints {missing}", element=missing[0])
    for j in urdf.joints.values():
        if j.type in ("floating", "planar"):
            raise ModelError(f"joint '{j.name}' is {j.type}: the MJCF export handles "
                             "revolute, continuous, prismatic and fixed joints", element=j.name)

    root = ET.Element("mujoco", model=name)
    ET.SubElement(root, "compiler", angle="radian", inertiafromgeom="false",
                  autolimits="true", boundinertia=_num(POINT_MASS_INERTIA))
    option = ET.SubElement(root, "option", timestep=_num(timestep), integrator=INTEGRATOR,
                           gravity=_vec(gravity), solver=SOLVER,
                           tolerance=_num(SOLVER_TOLERANCE), iterations=str(SOLVER_ITERATIONS))
    ET.SubElement(option, "flag", contact="disable")
    default = ET.SubElement(root, "default")
    ET.SubElement(default, "joint", armature="0", damping="0", frictionloss="0")
    ET.SubElement(default, "geom", contype="0", conaffinity="0", group="1")
    ET.SubElement(default, "site", size="0.01", rgba="1 0 0 1", group="4")
    world = ET.SubElement(root, "worldbody")
    ET.SubElement(world, "light", name="sun", pos="0 0 4", dir="0 0 -1", directional="true")

    order: list[str] = []
    sites: set = set()

    def geoms(el, link):
        for k, (kind, size, p, R, rgba) in enumerate(visuals.get(link, [])):
            g = ET.SubElement(el, "geom", name=f"{link}_visual{k}" if k else f"{link}_visual",
                              type=kind, size=_vec(size), rgba=rgba)
            _placement(g, p, R)

    def inertial(el, link):
        i = urdf.inertials.get(link)
        if i is not None and i.mass > _MASSLESS:
            _inertial(el, i.mass, i.com, i.inertia)

    def contents(el, link):
        geoms(el, link)
        for jname in urdf.child_joints.get(link, []):
            j = urdf.joints[jname]
            if j.type == "fixed":
                child = j.child
                i = urdf.inertials.get(child)
                if (i is None or i.mass <= _MASSLESS) and not urdf.child_joints.get(child) \
                        and not visuals.get(child):
                    s = ET.SubElement(el, "site", name=child)
                    _placement(s, j.xyz, j.R)
                    sites.add(child)
                    continue
                body = ET.SubElement(el, "body", name=child)
                _placement(body, j.xyz, j.R)
                inertial(body, child)
                contents(body, child)
                continue
            chain = [j]
            while (nxt := _mergeable(urdf, visuals, chain[-1].child)) is not None:
                chain.append(urdf.joints[nxt])
            child = chain[-1].child
            _check_moving(urdf, chain[-1].name, child)
            p, R, axes = _chain_placement(chain, positions)
            body = ET.SubElement(el, "body", name=child)
            _placement(body, p, R)
            for jj, axis, point, ref in axes:
                kind = "slide" if jj.type == "prismatic" else "hinge"
                je = ET.SubElement(body, "joint", name=jj.name, type=kind, axis=_vec(axis))
                if kind == "hinge" and np.any(point != 0):
                    je.set("pos", _vec(point))
                if ref != 0:
                    je.set("ref", _num(ref))
                if joint_limits and jj.name not in virtual and jj.type != "continuous" \
                        and np.isfinite(jj.lower) and np.isfinite(jj.upper):
                    je.set("range", _vec((jj.lower, jj.upper)))
                order.append(jj.name)
            inertial(body, child)
            contents(body, child)

    contents(world, urdf.root)

    for a, b in loops:
        for s in (a, b):
            if s not in sites:
                raise ModelError(f"loop frame '{s}' is not a massless leaf link of the URDF",
                                 element=s)
    if loops:
        eq = ET.SubElement(root, "equality")
        for k, (a, b) in enumerate(loops):
            ET.SubElement(eq, "connect", name=f"loop{k + 1}", site1=a, site2=b,
                          solref=_vec(SOLREF), solimp=_vec(SOLIMP))
    names = [a for a, _ in actuators]
    if actuators:
        act = ET.SubElement(root, "actuator")
        for motor, joint in actuators:
            if joint not in order:
                raise ModelError(f"motor '{motor}' drives joint '{joint}', which the model "
                                 "does not have", element=joint)
            m = ET.SubElement(act, "motor", name=motor, joint=joint, gear="1")
            lo, hi = (ctrlrange or {}).get(motor, (-np.inf, np.inf))
            if np.isfinite(lo) or np.isfinite(hi):
                m.set("ctrlrange", _vec((lo if np.isfinite(lo) else -1e30,
                                         hi if np.isfinite(hi) else 1e30)))
                m.set("ctrllimited", "true")
    qpos0 = np.array([positions[j] for j in order])
    key = ET.SubElement(ET.SubElement(root, "keyframe"), "key", name="hold", time="0",
                        qpos=_vec(qpos0), qvel=_vec(np.zeros(len(order))))
    if hold is not None:
        hold = np.asarray(hold, dtype=float)
        if hold.shape != (len(names),):
            raise ModelError(f"hold has shape {hold.shape}, expected ({len(names)},)")
        key.set("ctrl", _vec(hold))
    ET.indent(root, space="  ")
    text = ET.tostring(root, encoding="unicode")
    header = ("<!-- offshore-crane: MJCF generated from the robot's URDF (docs/mjcf.md). "
              "qpos order: " + " ".join(order) + ". ctrl order: " + " ".join(names)
              + ". -->\n")
    return MJCF(xml=header + text + "\n", joints=tuple(order), actuators=tuple(names),
                qpos0=qpos0, hold=hold)


# --------------------------------------------------------------------------- MuJoCo
def mujoco_state(model: MJCF, robot, q, qd=None, sway=None, sway_rate=None):
    """Our state as MuJoCo's ``(qpos (N, nq), qvel (N, nv))`` for ``model``.

    Args:
        model: From :func:`export` for this robot.
        robot, q, qd, sway, sway_rate: As :func:`joint_values`.
    """
    values = joint_values(robot, q, qd, sway, sway_rate)
    qpos = np.stack([values[j][0] for j in model.joints], axis=1)
    qvel = np.stack([values[j][1] for j in model.joints], axis=1)
    return qpos, qvel


def load(model: MJCF):
    """``(mujoco.MjModel, mujoco.MjData)`` of ``model`` (imports mujoco).

    Raises:
        BackendMissingError: mujoco is not installed (``pip install offshore-crane[mujoco]``).
        ModelError: MuJoCo refuses the model (its message).
    """
    from offshore_crane.errors import require

    mujoco = require("mujoco", "mujoco", "Loading the MJCF model in MuJoCo")
    try:
        m = mujoco.MjModel.from_xml_string(model.xml)
    except ValueError as exc:
        raise ModelError(f"MuJoCo refuses the exported model: {exc}") from None
    return m, mujoco.MjData(m)


@dataclass(frozen=True)
class MujocoForward:
    """MuJoCo's forward dynamics at our states (:func:`forward`).

    Attributes:
        qdd: ``(N, 9)`` accelerations of q1..q9 [m/s², rad/s²] (zeros for an absent arm).
        constraint: ``(N, 9)`` the part of ``qdd`` the loop constraints produce,
            ``qacc - qacc_smooth`` (MuJoCo's unconstrained acceleration) [m/s², rad/s²]:
            the scale of the soft constraints' error.
        qacc: ``(N, nv)`` MuJoCo's ``qacc`` in :attr:`MJCF.joints` order.
        loop: ``(N,)`` largest distance between the two sites of a loop [m].
    """

    qdd: np.ndarray
    constraint: np.ndarray
    qacc: np.ndarray
    loop: np.ndarray

    def agreement(self, qdd_ref) -> np.ndarray:
        """``(9,)`` per coordinate: ``max_n |qdd - qdd_ref| / max_n |constraint|`` (0 where
        the constraints produce nothing), to compare with :data:`AGREEMENT`."""
        err = np.abs(self.qdd - np.asarray(qdd_ref)).max(axis=0)
        scale = np.abs(self.constraint).max(axis=0)
        return np.divide(err, scale, out=np.zeros(9), where=scale > 0)


def forward(model: MJCF, robot, q, qd, X, sway=None, sway_rate=None) -> MujocoForward:
    """MuJoCo's forward dynamics of ``model`` at our states under actuator forces X.

    Sets ``qpos``, ``qvel`` (:func:`mujoco_state`) and ``ctrl`` = X, runs
    ``mujoco.mj_forward`` per sample (MuJoCo has no batched call) and reads ``qacc``.
    ``mj_inverse`` cannot be used instead: it does not route loads through equality
    constraints.

    Args:
        model: From :func:`export`.
        robot, q, qd, sway, sway_rate: As :func:`joint_values`; ``(N, 9)``.
        X: ``(N, 9)`` actuator forces [N·m, N] in the order of ``ACTUATORS`` (the
            columns of absent actuators are ignored).

    Returns:
        :class:`MujocoForward`.
    """
    from offshore_crane.validation import as_samples

    m, d = load(model)
    import mujoco

    X = as_samples("X", X, finite=False)[0]
    qpos, qvel = mujoco_state(model, robot, q, qd, sway, sway_rate)
    if len(X) != len(qpos):
        raise InputError(f"X has {len(X)} samples, q has {len(qpos)}", name="X")
    ctrl = X[:, [ACTUATORS.index(a) for a in model.actuators]]   # absent arm: NaN columns
    as_samples("X of the model's motors", ctrl, width=ctrl.shape[1])
    index = {name: k for k, name in enumerate(model.joints)}
    ours = [index.get(name) for name in PLATFORM_JOINTS + ARM_JOINTS]
    qacc, smooth = np.empty_like(qvel), np.empty_like(qvel)
    loop = np.zeros(len(qpos))
    for n in range(len(qpos)):
        d.qpos[:], d.qvel[:], d.ctrl[:] = qpos[n], qvel[n], ctrl[n]
        mujoco.mj_forward(m, d)
        qacc[n], smooth[n] = d.qacc, d.qacc_smooth
        if d.ne:
            loop[n] = np.linalg.norm(d.efc_pos[:d.ne].reshape(-1, 3), axis=1).max()
    qdd, constraint = np.zeros((len(qpos), 9)), np.zeros((len(qpos), 9))
    for k, i in enumerate(ours):
        if i is not None:
            qdd[:, k], constraint[:, k] = qacc[:, i], qacc[:, i] - smooth[:, i]
    return MujocoForward(qdd, constraint, qacc, loop)
