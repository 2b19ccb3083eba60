"""A small, fast URDF reader (standard library only).

It reads what the dynamics needs (links' inertial data, joints' placement, axis, type and
limits) and the links' visual primitives (box, cylinder, sphere, with their material
colours) that :mod:`offshore_crane.outputs.visual` draws; meshes are skipped (left to viewers such
as yourdfpy or Pinocchio). Parsing the expanded robot takes about a millisecond, against
about a second to import yourdfpy.

Frames: a joint's ``origin`` places the joint frame in its parent link frame,
``T_parent_joint``; the child link frame coincides with the joint frame at zero joint
position. A link's ``inertial/origin`` places its centre-of-mass frame in the link frame; a
``visual/origin`` places the shape's own frame in the link frame (a cylinder's axis is the
z axis of that frame, centred on its origin, as URDF specifies).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np

from offshore_crane.errors import ModelError
from offshore_crane.spatial import rpy_matrix

MOVABLE = ("revolute", "continuous", "prismatic")


@dataclass(frozen=True)
class Inertial:
    """Mass properties of a link.

    Attributes:
        mass: [kg].
        com: ``(3,)`` centre of mass in the link frame [m].
        inertia: ``(3, 3)`` inertia about the centre of mass, link axes [kg·m²].
    """

    mass: float
    com: np.ndarray
    inertia: np.ndarray


@dataclass(frozen=True)
class Joint:
    """A URDF joint.

    Attributes:
        name, type, parent, child: as in the URDF.
        xyz: ``(3,)`` joint origin in the parent link frame [m].
        R: ``(3, 3)`` ``R_parent_joint`` from the origin's rpy.
        axis: ``(3,)`` unit axis in the joint frame (zeros for a fixed joint).
        lower, upper: position limits [m or rad] (``-inf``/``inf`` when absent).
        mimic: name of the mimicked joint, or None.
        damping: viscous damping of ``<dynamics damping>`` [N·s/m or N·m·s/rad] (0 when
            absent).
    """

    name: str
    type: str
    parent: str
    child: str
    xyz: np.ndarray
    R: np.ndarray
    axis: np.ndarray
    lower: float = -np.inf
    upper: float = np.inf
    mimic: str | None = None
    damping: float = 0.0


#: Visual primitives read from ``<visual><geometry>`` (meshes are not read).
SHAPES = ("box", "cylinder", "sphere")


@dataclass(frozen=True)
class Visual:
    """One visual primitive of a link.

    Attributes:
        shape: ``"box"``, ``"cylinder"`` or ``"sphere"``.
        size: ``(3,)`` box edge lengths [m]; for a cylinder ``(radius, radius, length)``,
            for a sphere ``(radius, radius, radius)`` [m].
        xyz: ``(3,)`` origin of the shape's frame in the link frame [m].
        R: ``(3, 3)`` ``R_link_shape`` from the origin's rpy.
        rgba: ``(4,)`` colour in 0..1 (the material's, by reference or inline), or None
            when the visual names no colour.
        material: Name of the material, or None.
    """

    shape: str
    size: np.ndarray
    xyz: np.ndarray
    R: np.ndarray
    rgba: np.ndarray | None = None
    material: str | None = None


@dataclass
class URDF:
    """Links' inertials, visual primitives and joints of a URDF, with parent/child maps.

    Attributes:
        visuals: ``{link: [Visual, ...]}`` for every link (an empty list when it has no
            primitive).
        drag: ``{link: (C_d·A [m²], air density [kg/m³])}`` of the links with a
            ``<drag area air_density/>`` element (this project's extension, which other
            URDF readers ignore: the hanging payload's air drag, docs/cable.md).
    """

    name: str
    inertials: dict[str, Inertial | None]
    joints: dict[str, Joint]
    child_joints: dict[str, list[str]] = field(default_factory=dict)
    parent_joint: dict[str, str] = field(default_factory=dict)
    visuals: dict[str, list[Visual]] = field(default_factory=dict)
    drag: dict[str, tuple[float, float]] = field(default_factory=dict)

    @property
    def root(self) -> str:
        """Name of the root link (the only link that is no joint's child)."""
        roots = [link for link in self.inertials if link not in self.parent_joint]
        if len(roots) != 1:
            raise ModelError(f"the URDF has {len(roots)} root links {roots}; it needs exactly one")
        return roots[0]

    def joint(self, name: str) -> Joint:
        """The joint called ``name``, or :class:`ModelError` naming it."""
        try:
            return self.joints[name]
        except KeyError:
            raise ModelError(f"the URDF has no joint '{name}'", element=name) from None

    def inertial(self, link: str) -> Inertial | None:
        """Inertial of ``link`` (None for a massless link)."""
        if link not in self.inertials:
            raise ModelError(f"the URDF has no link '{link}'", element=link)
        return self.inertials[link]

    def rigid_group(self, link: str) -> list[tuple[str, np.ndarray, np.ndarray]]:
        """All links welded to ``link`` by fixed joints (itself first), with placements.

        Returns:
            ``[(name, p_link_X, R_link_X), ...]``: the position [m] and orientation of
            each welded link frame ``X`` in the frame of ``link``.
        """
        out = [(link, np.zeros(3), np.eye(3))]
        stack = [(link, np.zeros(3), np.eye(3))]
        while stack:
            name, p, R = stack.pop()
            for jname in self.child_joints.get(name, []):
                j = self.joints[jname]
                if j.type == "fixed":
                    entry = (j.child, p + R @ j.xyz, R @ j.R)
                    out.append(entry)
                    stack.append(entry)
        return out

    def movable_children(self, link: str) -> list[Joint]:
        """Movable joints whose parent is ``link`` or a link welded to it."""
        out = []
        for name, _, _ in self.rigid_group(link):
            out += [self.joints[j] for j in self.child_joints.get(name, [])
                    if self.joints[j].type != "fixed"]
        return out


def _floats(text: str | None, n: int, default: float, where: str) -> np.ndarray:
    if text is None:
        return np.full(n, default)
    try:
        values = np.array([float(x) for x in text.split()])
    except ValueError:
        raise ModelError(f"{where}: '{text}' is not a list of {n} numbers", element=where) from None
    if values.shape != (n,) or not np.all(np.isfinite(values)):
        raise ModelError(f"{where}: '{text}' is not a list of {n} finite numbers", element=where)
    return values


def _attr_float(el, key: str, where: str, default: float | None = None) -> float:
    text = el.get(key) if el is not None else None
    if text is None:
        if default is None:
            raise ModelError(f"{where}: missing attribute '{key}'", element=where)
        return default
    try:
        value = float(text)
    except ValueError:
        raise ModelError(f"{where}: {key}='{text}' is not a number", element=where) from None
    return value                        # finiteness: model.validate names the element


def parse_urdf(text: str) -> URDF:
    """Parse URDF XML text.

    Raises:
        ModelError: malformed XML, missing attributes, non-numeric values, unknown
            joint types, dangling parent/child links.
    """
    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        raise ModelError(f"the URDF is not well-formed XML: {exc}") from None
    if root.tag != "robot":
        raise ModelError(f"the URDF's root element is <{root.tag}>, expected <robot>")
    materials = _materials(root)
    inertials: dict[str, Inertial | None] = {}
    visuals: dict[str, list[Visual]] = {}
    drag: dict[str, tuple[float, float]] = {}
    for link in root.findall("link"):
        name = link.get("name")
        if name is None:
            raise ModelError("a <link> has no name")
        if name in inertials:
            raise ModelError(f"the URDF defines link '{name}' twice: give each link a "
                             "unique name", element=name)
        inertials[name] = _parse_inertial(link.find("inertial"), name)
        visuals[name] = [v for k, el in enumerate(link.findall("visual"))
                         if (v := _parse_visual(el, name, k, materials)) is not None]
        el = link.find("drag")
        if el is not None:
            where = f"link '{name}' <drag>"
            area, rho = (_attr_float(el, key, where) for key in ("area", "air_density"))
            if not (np.isfinite(area) and area >= 0.0 and np.isfinite(rho) and rho > 0.0):
                raise ModelError(f"{where}: area = {area:g} m² must be finite and >= 0, "
                                 f"air_density = {rho:g} kg/m³ finite and > 0", element=name)
            drag[name] = (area, rho)
    joints: dict[str, Joint] = {}
    child_joints: dict[str, list[str]] = {}
    parent_joint: dict[str, str] = {}
    for el in root.findall("joint"):
        j = _parse_joint(el)
        for link in (j.parent, j.child):
            if link not in inertials:
                raise ModelError(f"joint '{j.name}' refers to link '{link}', which the URDF "
                                 "does not define", element=j.name)
        if j.name in joints:
            raise ModelError(f"the URDF defines joint '{j.name}' twice: give each joint a "
                             "unique name", element=j.name)
        if j.child in parent_joint:
            raise ModelError(f"link '{j.child}' is the child of two joints "
                             f"('{parent_joint[j.child]}' and '{j.name}'): URDF is a tree",
                             element=j.name)
        joints[j.name] = j
        child_joints.setdefault(j.parent, []).append(j.name)
        parent_joint[j.child] = j.name
    return URDF(root.get("name", ""), inertials, joints, child_joints, parent_joint, visuals,
                drag)


def _rgba(el, where: str) -> np.ndarray | None:
    color = el.find("color") if el is not None else None
    if color is None or color.get("rgba") is None:
        return None
    rgba = _floats(color.get("rgba"), 4, 1.0, where)
    if np.any(rgba < 0.0) or np.any(rgba > 1.0):
        raise ModelError(f"{where}: rgba '{color.get('rgba')}' has values outside 0..1",
                         element=where)
    return rgba


def _materials(root) -> dict[str, np.ndarray]:
    """The robot-level ``<material name><color rgba/></material>`` definitions."""
    out = {}
    for el in root.findall("material"):
        name = el.get("name")
        rgba = _rgba(el, f"material '{name}'")
        if name is not None and rgba is not None:
            out[name] = rgba
    return out


def _parse_visual(el, link: str, k: int, materials: dict) -> Visual | None:
    """A link's ``k``-th ``<visual>`` as a :class:`Visual`, or None for a mesh or an
    empty geometry (not drawn)."""
    where = f"link '{link}' visual {k + 1}"
    geometry = el.find("geometry")
    shape = next((g for g in geometry if g.tag in SHAPES), None) if geometry is not None \
        else None
    if shape is None:
        return None
    if shape.tag == "box":
        size = _floats(shape.get("size"), 3, 0.0, where)
    elif shape.tag == "cylinder":
        r = _attr_float(shape, "radius", where)
        size = np.array([r, r, _attr_float(shape, "length", where)])
    else:
        size = np.full(3, _attr_float(shape, "radius", where))
    if not np.all(np.isfinite(size)) or np.any(size < 0.0):
        raise ModelError(f"{where}: {shape.tag} dimensions {size.tolist()} must be finite "
                         "and >= 0 m", element=link)
    origin = el.find("origin")
    xyz = _floats(origin.get("xyz") if origin is not None else None, 3, 0.0, where)
    rpy = _floats(origin.get("rpy") if origin is not None else None, 3, 0.0, where)
    material = el.find("material")
    name = material.get("name") if material is not None else None
    rgba = _rgba(material, where)
    if rgba is None and name is not None:
        rgba = materials.get(name)
    return Visual(shape.tag, size, xyz, rpy_matrix(rpy), rgba, name)


def _parse_inertial(el, link: str) -> Inertial | None:
    if el is None:
        return None
    where = f"link '{link}' inertial"
    mass = _attr_float(el.find("mass"), "value", where, default=0.0)
    origin = el.find("origin")
    xyz = _floats(origin.get("xyz") if origin is not None else None, 3, 0.0, where)
    rpy = _floats(origin.get("rpy") if origin is not None else None, 3, 0.0, where)
    ie = el.find("inertia")
    k = {key: _attr_float(ie, key, where, default=0.0)
         for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    inertia = np.array([[k["ixx"], k["ixy"], k["ixz"]],
                        [k["ixy"], k["iyy"], k["iyz"]],
                        [k["ixz"], k["iyz"], k["izz"]]])
    R = rpy_matrix(rpy)
    return Inertial(mass, xyz, R @ inertia @ R.T)


def _parse_joint(el) -> Joint:
    name = el.get("name")
    jtype = el.get("type")
    if name is None or jtype is None:
        raise ModelError("a <joint> lacks its name or type")
    if jtype not in MOVABLE + ("fixed", "floating", "planar"):
        raise ModelError(f"joint '{name}' has unknown type '{jtype}'", element=name)
    parent, child = el.find("parent"), el.find("child")
    if parent is None or child is None or parent.get("link") is None or child.get("link") is None:
        raise ModelError(f"joint '{name}' lacks <parent link> or <child link>", element=name)
    origin = el.find("origin")
    where = f"joint '{name}'"
    xyz = _floats(origin.get("xyz") if origin is not None else None, 3, 0.0, where)
    rpy = _floats(origin.get("rpy") if origin is not None else None, 3, 0.0, where)
    axis = np.zeros(3)
    if jtype in MOVABLE or jtype == "planar":
        axis_el = el.find("axis")
        axis = _floats(axis_el.get("xyz") if axis_el is not None else None, 3, 0.0, where)
        if axis_el is None:
            axis = np.array([1.0, 0.0, 0.0])  # URDF default
        norm = np.linalg.norm(axis)
        if norm == 0.0:
            raise ModelError(f"joint '{name}' has a zero axis", element=name)
        axis = axis / norm
    lower, upper = -np.inf, np.inf
    limit = el.find("limit")
    if limit is None and jtype in ("revolute", "prismatic"):
        raise ModelError(f"joint '{name}' is {jtype} but has no <limit> (the URDF format "
                         "requires one; use type 'continuous' for an unlimited revolute "
                         "joint)", element=name)
    if limit is not None and jtype in ("revolute", "prismatic"):
        lower = _attr_float(limit, "lower", where, default=0.0)
        upper = _attr_float(limit, "upper", where, default=0.0)
    mimic = el.find("mimic")
    dyn = el.find("dynamics")
    damping = _attr_float(dyn, "damping", where, default=0.0) if dyn is not None else 0.0
    return Joint(name, jtype, parent.get("link"), child.get("link"), xyz, rpy_matrix(rpy),
                 axis, lower, upper, mimic.get("joint") if mimic is not None else None,
                 damping)
