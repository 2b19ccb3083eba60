"""Serial chains: structure read from a URDF, and batched kinematics on a moving base.

This is the paper's Section 3.2 (Eqs. 27-30) in recursive form. A chain is a sequence of
bodies, body ``k`` being moved by joint ``k`` (revolute or prismatic) relative to body
``k-1``; body ``-1`` is the *base*, which may itself move (the hybrid robot's platform) or
be fixed (a robot arm on the ground). Links welded by fixed joints are merged into one
rigid body (exact: the mass properties add).

Generalized speeds are ``u = (u_base, qd)``: the base's ``nb`` speeds followed by the
chain's joint rates (paper Eq. 18, ``u_r = dq_r/dt``). Partial velocities are stored as
``(N, nb + n, 3)`` arrays: axis 1 is ``r``, axis 2 the world component.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from ..spatial import axis_angle_matrix, cross
from ..model.urdf import MOVABLE, URDF


@dataclass(frozen=True)
class SerialChain:
    """What Kane's method needs of a serial chain, read from a URDF.

    Attributes:
        base_link: Name of the base link.
        joint_names: ``(n,)`` movable joints in chain order.
        body_names: ``(n,)`` child link of each joint (welded links merged into it).
        prismatic: ``(n,)`` bool, True for a prismatic joint.
        p_parent_joint: ``(n, 3)`` joint origin in the parent body frame [m].
        R_parent_joint: ``(n, 3, 3)`` joint frame orientation in the parent body frame.
        axis: ``(n, 3)`` unit joint axis in the joint frame.
        mass: ``(n,)`` body masses [kg].
        com: ``(n, 3)`` centres of mass in the body frames [m].
        inertia: ``(n, 3, 3)`` central inertias in body axes [kg·m²].
        lower, upper: ``(n,)`` joint limits [rad or m].
        frames: ``{name: (body index, p_body_frame (3,), R_body_frame (3, 3))}`` for every
            welded link (``-1`` for links welded to the base).
    """

    base_link: str
    joint_names: tuple
    body_names: tuple
    prismatic: np.ndarray
    p_parent_joint: np.ndarray
    R_parent_joint: np.ndarray
    axis: np.ndarray
    mass: np.ndarray
    com: np.ndarray
    inertia: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    frames: dict

    @property
    def n(self) -> int:
        """Number of movable joints."""
        return len(self.joint_names)


def merged_inertial(urdf: URDF, link: str):
    """Mass properties of ``link`` and every link welded to it, in ``link``'s frame.

    Returns:
        ``(mass [kg], com (3,) [m], central inertia (3, 3) [kg·m²], welded)`` where
        ``welded`` is :meth:`URDF.rigid_group`'s list.
    """
    welded = urdf.rigid_group(link)
    mass, first = 0.0, np.zeros(3)
    parts = []
    for name, p, R in welded:
        inertial = urdf.inertial(name)
        if inertial is None or inertial.mass == 0.0:
            continue
        c = p + R @ inertial.com
        parts.append((inertial.mass, c, R @ inertial.inertia @ R.T))
        mass += inertial.mass
        first += inertial.mass * c
    if mass == 0.0:
        return 0.0, np.zeros(3), np.zeros((3, 3)), welded
    com = first / mass
    inertia = np.zeros((3, 3))
    for m, c, I in parts:  # parallel-axis theorem
        d = c - com
        inertia += I + m * (d @ d * np.eye(3) - np.outer(d, d))
    return mass, com, inertia, welded


def chain_from_urdf(urdf: URDF, base_link: str, stop_at: tuple = ()) -> SerialChain:
    """Follow the movable joints below ``base_link`` as one serial chain.

    Args:
        urdf: Parsed URDF.
        base_link: Link the chain is mounted on.
        stop_at: Joint names below which not to descend (they are not part of the chain).

    Raises:
        ModelError: a body has two movable children (branching, naming both joints), or a
            joint is floating, planar or mimics another.
    """
    names, bodies, prism, ps, Rs, axes, masses, coms, inertias, lo, up = ([] for _ in range(11))
    frames = {name: (-1, p, R) for name, p, R in urdf.rigid_group(base_link)}
    link = base_link
    while True:
        children = [j for j in urdf.movable_children(link) if j.name not in stop_at]
        if not children:
            break
        if len(children) > 1:
            raise ModelError(
                f"the chain branches below link '{link}' (joints "
                f"{', '.join(repr(j.name) for j in children)}): give a URDF whose movable "
                "joints form one serial chain", element=children[1].name)
        j = children[0]
        if j.type not in MOVABLE:
            raise ModelError(f"joint '{j.name}' is {j.type}: a serial chain takes revolute, "
                             "continuous and prismatic joints only", element=j.name)
        if j.mimic is not None:
            raise ModelError(f"joint '{j.name}' mimics '{j.mimic}': mimic joints are not "
                             "supported, remove the <mimic> element", element=j.name)
        # The joint may hang from a link welded to the current body: compose placements.
        _, p_w, R_w = next((f for f in urdf.rigid_group(link) if f[0] == j.parent))
        mass, com, inertia, welded = merged_inertial(urdf, j.child)
        k = len(names)
        for name, p, R in welded:
            frames[name] = (k, p, R)
        names.append(j.name)
        bodies.append(j.child)
        prism.append(j.type == "prismatic")
        ps.append(p_w + R_w @ j.xyz)
        Rs.append(R_w @ j.R)
        axes.append(j.axis)
        masses.append(mass)
        coms.append(com)
        inertias.append(inertia)
        lo.append(j.lower)
        up.append(j.upper)
        link = j.child
    n = len(names)
    return SerialChain(
        base_link, tuple(names), tuple(bodies), np.array(prism, dtype=bool),
        np.array(ps).reshape(n, 3), np.array(Rs).reshape(n, 3, 3), np.array(axes).reshape(n, 3),
        np.array(masses), np.array(coms).reshape(n, 3), np.array(inertias).reshape(n, 3, 3),
        np.array(lo), np.array(up), frames)


@dataclass
class BaseMotion:
    """Motion of a chain's base frame, batched over N samples (world axes).

    Attributes:
        R: ``(N, 3, 3)`` ``R_world_base``.
        p: ``(N, 3)`` base origin [m].
        omega, alpha: ``(N, 3)`` angular velocity [rad/s] and acceleration [rad/s²].
        v, a: ``(N, 3)`` velocity [m/s] and acceleration [m/s²] of the base origin.
        V, W: ``(N, nb, 3)`` partial velocities of the base origin and partial angular
            velocities of the base, for the base's ``nb`` generalized speeds.
    """

    R: np.ndarray
    p: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    v: np.ndarray
    a: np.ndarray
    V: np.ndarray
    W: np.ndarray

    @classmethod
    def fixed(cls, n_samples: int, R=None, p=None) -> "BaseMotion":
        """A base at rest at pose (``R``, ``p``) (identity and origin by default)."""
        z = np.zeros((n_samples, 3))
        Rb = np.broadcast_to(np.eye(3) if R is None else R, (n_samples, 3, 3))
        pb = np.broadcast_to(np.zeros(3) if p is None else p, (n_samples, 3))
        empty = np.zeros((n_samples, 0, 3))
        return cls(Rb, pb, z, z, z, z, empty, empty)


@dataclass
class BodyMotion:
    """Kinematics of one rigid body, batched over N samples (world axes).

    Attributes:
        R: ``(N, 3, 3)`` ``R_world_body``.
        p: ``(N, 3)`` body frame origin [m].
        p_com: ``(N, 3)`` centre of mass [m].
        omega, alpha: ``(N, 3)`` [rad/s], [rad/s²].
        v_com, a_com: ``(N, 3)`` centre-of-mass velocity [m/s] and acceleration [m/s²].
        V, W: ``(N, nu, 3)`` partial velocities of the centre of mass, partial angular
            velocities.
    """

    R: np.ndarray
    p: np.ndarray
    p_com: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    v_com: np.ndarray
    a_com: np.ndarray
    V: np.ndarray
    W: np.ndarray


def chain_kinematics(chain: SerialChain, q, qd, qdd, base: BaseMotion) -> list[BodyMotion]:
    """Poses, velocities, accelerations and partial velocities of every chain body.

    Args:
        chain: The chain.
        q, qd, qdd: ``(N, n)`` joint positions [rad or m], rates, accelerations.
        base: Motion of the base (:meth:`BaseMotion.fixed` for a fixed base).

    Returns:
        One :class:`BodyMotion` per chain body; partials are ``(N, nb + n, 3)``.
    """
    N, n = q.shape
    nb = base.V.shape[1]
    R, p, w, al, v, a = base.R, base.p, base.omega, base.alpha, base.v, base.a
    V = np.zeros((N, nb + n, 3))  # partial velocities of the current body's origin
    W = np.zeros((N, nb + n, 3))
    V[:, :nb] = base.V
    W[:, :nb] = base.W
    out = []
    for k in range(n):
        # joint frame in the world
        p_j = p + R @ chain.p_parent_joint[k]
        R_j = R @ chain.R_parent_joint[k]
        z = R_j @ chain.axis[k]
        r = p_j - p  # parent origin -> joint origin
        v_j = v + cross(w, r)
        a_j = a + cross(al, r) + cross(w, cross(w, r))
        V = V + cross(W, r[:, None, :])
        if chain.prismatic[k]:
            d = z * q[:, k, None]
            R_c, p_c = R_j, p_j + d
            w_c = w
            al_c = al
            v_c = v_j + cross(w, d) + z * qd[:, k, None]
            a_c = (a_j + cross(al, d) + cross(w, cross(w, d))
                   + 2.0 * cross(w, z) * qd[:, k, None] + z * qdd[:, k, None])
            V = V + cross(W, d[:, None, :])
            V[:, nb + k] += z
        else:
            R_c = R_j @ axis_angle_matrix(chain.axis[k], q[:, k])
            p_c = p_j
            w_c = w + z * qd[:, k, None]
            al_c = al + z * qdd[:, k, None] + cross(w, z) * qd[:, k, None]
            v_c, a_c = v_j, a_j
            W = W.copy()
            W[:, nb + k] += z
        rc = R_c @ chain.com[k]
        out.append(BodyMotion(
            R=R_c, p=p_c, p_com=p_c + rc, omega=w_c, alpha=al_c,
            v_com=v_c + cross(w_c, rc),
            a_com=a_c + cross(al_c, rc) + cross(w_c, cross(w_c, rc)),
            V=V + cross(W, rc[:, None, :]), W=W))
        R, p, w, al, v, a = R_c, p_c, w_c, al_c, v_c, a_c
    return out
