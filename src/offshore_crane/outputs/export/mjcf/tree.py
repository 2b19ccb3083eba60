"""The URDF's tree written as MJCF bodies: placements, inertials, drawings, the legs' loops
closed by equality constraints.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import ModelError
from offshore_crane.spatial import axis_angle_matrix, rpy_matrix
from offshore_crane.outputs.export.mjcf.settings import (INTEGRATOR, MASSLESS, MJCF,
                                                         POINT_MASS_INERTIA, SOLIMP, SOLREF,
                                                         SOLVER, SOLVER_ITERATIONS,
                                                         SOLVER_TOLERANCE, TIMESTEP)


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
    moments = np.linalg.eigvalsh(inertia) if mass > MASSLESS else np.zeros(3)
    if mass > MASSLESS and np.abs(inertia).max() <= 1e-15:
        return                                          # a point mass: boundinertia
    if mass <= MASSLESS or moments.min() <= 1e-15:
        what = "no mass" if mass <= MASSLESS else (
            f"principal moments of inertia {', '.join(f'{x:.3g}' for x in moments)} kg·m²")
        raise ModelError(f"joint '{joint}' moves link '{link}', which has {what}: MuJoCo "
                         "needs a positive mass and inertia on every moving body (give the "
                         "link a mass and a radius or inertia, or weld it)", element=link)


def _mergeable(urdf, visuals, link: str) -> str | None:
    """The single movable child joint of a massless, undrawn link (a virtual link or a
    U-joint cross, merged into its child's MuJoCo body), else None."""
    inertial = urdf.inertials.get(link)
    children = urdf.child_joints.get(link, [])
    if (inertial is not None and inertial.mass > MASSLESS) or visuals.get(link) \
            or len(children) != 1:
        return None
    child = urdf.joints[children[0]]
    return child.name if child.type != "fixed" else None


def mjcf_from_urdf(urdf_text: str, positions: dict, *, name: str = "robot",
                   gravity=GRAVITY, actuators=(), ctrlrange: dict | None = None,
                   loops=(), hold=None, joint_limits: bool = False, virtual=(),
                   timestep: float = TIMESTEP, description=None) -> MJCF:
    """An MJCF model of any URDF tree, written at the given joint positions.

    Joints carry no armature and no friction; their viscous ``damping`` is the URDF's
    ``<dynamics damping>`` [N·s/m or N·m·s/rad] (the hanging load's sway joints:
    ``payload.sway_damping``), 0 where the URDF gives none.

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
        if i is not None and i.mass > MASSLESS:
            _inertial(el, i.mass, i.com, i.inertia)

    def contents(el, link):
        geoms(el, link)
        for jname in urdf.child_joints.get(link, []):
            j = urdf.joints[jname]
            if j.type == "fixed":
                child = j.child
                i = urdf.inertials.get(child)
                if (i is None or i.mass <= MASSLESS) and not urdf.child_joints.get(child) \
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
                if jj.damping != 0:            # the URDF's <dynamics damping> (the sway's)
                    je.set("damping", _num(jj.damping))
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
