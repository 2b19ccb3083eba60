"""Serial chains: structure read from a URDF, and batched kinematics on a moving base.

This is the paper's Section 3.2 (Eqs. 27-30) in recursive form. A chain is a sequence of
bodies, body ``k`` being moved by joint ``k`` (revolute, continuous or prismatic) relative
to body ``k-1``; body ``-1`` is the *base*, which may itself move (the hybrid robot's
platform) or be fixed (a robot arm on the ground). Links welded by fixed joints are merged
into one rigid body (exact: the mass properties add). A continuous joint is a revolute
joint without limits (one angle).

Generalized speeds are ``u = (u_base, qd)``: the base's ``nb`` speeds followed by the
chain's joint rates (paper Eq. 18, ``u_r = dq_r/dt``). Partial velocities are stored as
``(N, nb + n, 3)`` arrays: axis 1 is ``r``, axis 2 the world component.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import ModelError
from ..spatial import skew
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
        tip: The link the chain was cut at (``tip`` of :func:`chain_from_urdf`), or None.
        locked: Movable joints below the base but off the base→tip path, locked at zero
            position (their links welded to their parents as at q = 0); empty without tip.
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
    tip: str | None = None
    locked: tuple = ()

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


def path_joints(urdf: URDF, base_link: str, tip: str) -> list[str]:
    """Joints (fixed ones included) on the path from ``base_link`` down to link ``tip``.

    Raises:
        ModelError: ``tip`` is not a link of the URDF, or is not below ``base_link``.
    """
    if tip not in urdf.inertials:
        raise ModelError(f"the URDF has no link or frame '{tip}' (the tip asked for)",
                         element=tip)
    path, link = [], tip
    while link != base_link:
        jname = urdf.parent_joint.get(link)
        if jname is None:
            raise ModelError(f"the tip '{tip}' is not below the base link '{base_link}'",
                             element=tip)
        path.append(jname)
        link = urdf.joints[jname].parent
    return path[::-1]


def lock_off_path(urdf: URDF, base_link: str, tip: str) -> tuple[URDF, tuple]:
    """A copy of ``urdf`` whose movable joints below ``base_link`` and off the path to
    ``tip`` are made fixed at their zero position (mimic, floating and planar included).

    Returns:
        ``(urdf, locked)``: the modified URDF (the input is not changed) and the names of
        the locked joints in depth-first order.
    """
    on_path = set(path_joints(urdf, base_link, tip))
    joints, locked = dict(urdf.joints), []
    stack = list(reversed(urdf.child_joints.get(base_link, [])))
    while stack:  # depth-first, in file order
        jname = stack.pop()
        j = urdf.joints[jname]
        if j.type != "fixed" and jname not in on_path:
            # At q = 0 the child frame is the joint frame: a fixed joint with the same
            # origin welds it exactly there.
            joints[jname] = replace(j, type="fixed", axis=np.zeros(3), mimic=None)
            locked.append(jname)
        stack += reversed(urdf.child_joints.get(j.child, []))
    return URDF(urdf.name, urdf.inertials, joints, urdf.child_joints, urdf.parent_joint), \
        tuple(locked)


def chain_from_urdf(urdf: URDF, base_link: str, stop_at: tuple = (),
                    tip: str | None = None) -> SerialChain:
    """Follow the movable joints below ``base_link`` as one serial chain.

    Args:
        urdf: Parsed URDF.
        base_link: Link the chain is mounted on.
        stop_at: Joint names below which not to descend (they are not part of the chain).
        tip: Optional link (or welded frame) to end the chain at: only the movable joints
            on the path from ``base_link`` to ``tip`` are kept; every other movable joint
            below ``base_link`` is locked at zero position, its links welded (see
            :func:`lock_off_path`). Lets a chain be cut out of a branching tree.

    Raises:
        ModelError: a body has two movable children (branching, naming both joints), or a
            joint is floating, planar or mimics another, or ``tip`` is not below
            ``base_link``.
    """
    locked = ()
    if tip is not None:
        urdf, locked = lock_off_path(urdf, base_link, tip)
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
                "joints form one serial chain, or a tip link to cut one out of the tree",
                element=children[1].name)
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
        np.array(lo), np.array(up), frames, tip, locked)


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


def _cross0(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product over axis 0 of component-first arrays ``(3, ...)``, broadcast.

    :func:`offshore_crane.spatial.cross` works on the last axis of ``(..., 3)`` arrays;
    :func:`chain_kinematics` keeps its work arrays component-first so that every NumPy
    loop runs over the N samples (contiguous) rather than over 3 components.
    """
    first = a[1] * b[2]
    out = np.empty((3,) + first.shape, dtype=first.dtype)
    np.subtract(first, a[2] * b[1], out=out[0])
    np.multiply(a[2], b[0], out=out[1])
    out[1] -= a[0] * b[2]
    np.multiply(a[0], b[1], out=out[2])
    out[2] -= a[1] * b[0]
    return out


def chain_kinematics(chain: SerialChain, q, qd, qdd, base: BaseMotion, *,
                     trim: bool = False) -> list[BodyMotion]:
    """Poses, velocities, accelerations and partial velocities of every chain body.

    Args:
        chain: The chain.
        q, qd, qdd: ``(N, n)`` joint positions [rad or m], rates, accelerations.
        base: Motion of the base (:meth:`BaseMotion.fixed` for a fixed base).
        trim: Body ``k`` moves with the base speeds and joints ``0..k`` only, so its
            partials are zero in columns ``nb + k + 1`` and beyond. With ``trim=True``
            those columns are left out: body ``k``'s ``V`` and ``W`` are
            ``(N, nb + k + 1, 3)``, which halves the O(n²) work and memory.

    Returns:
        One :class:`BodyMotion` per chain body; partials are ``(N, nb + n, 3)`` (see
        ``trim``). The arrays are views of component-first work arrays (``(3, N)``,
        ``(3, 3, N)``, ``(3, columns, N)``), so they are not C-contiguous, and with
        ``trim`` the bodies' ``W`` share memory: treat them as read-only.
    """
    N, n = q.shape
    nb = base.V.shape[1]
    nu = nb + n
    # Component-first (samples last) copies, so that NumPy's loops run over samples:
    # vectors (3, N), rotations (3, 3, N) as [i, j, sample], partials (3, r, N).
    qT, qdT, qddT = (np.ascontiguousarray(np.transpose(x)) for x in (q, qd, qdd))
    R = np.ascontiguousarray(np.transpose(base.R, (1, 2, 0)))
    p, w, al, v, a = (np.ascontiguousarray(np.transpose(x))
                      for x in (base.p, base.omega, base.alpha, base.v, base.a))
    V = np.ascontiguousarray(np.transpose(base.V, (2, 1, 0)))  # current body's origin
    W_all = np.zeros((3, nu, N))  # column r is set once, by the base or joint r
    W_all[:, :nb] = np.transpose(base.W, (2, 1, 0))
    out = []
    for k in range(n):
        m = nb + k  # columns already non-zero; joint k adds column m
        # Joint frame in the world. With R (3, 3, N): matmul(c, R)[i] = Σ_j R[i, j] c[j]
        # (R c) and matmul(Cᵀ, R)[i, k] = Σ_j R[i, j] C[j, k] (R C), as BLAS products.
        p_j = p + np.matmul(chain.p_parent_joint[k], R)
        R_j = np.matmul(chain.R_parent_joint[k].T, R)
        z = np.matmul(chain.axis[k], R_j)
        r = p_j - p  # parent origin -> joint origin
        v_j = v + _cross0(w, r)
        a_j = a + _cross0(al, r) + _cross0(w, _cross0(w, r))
        V_o = np.empty((3, m + 1, N))  # partial velocities of the new origin
        if chain.prismatic[k]:
            d = z * qT[k]
            R_c, p_c = R_j, p_j + d
            w_c = w
            al_c = al
            v_c = v_j + _cross0(w, d) + z * qdT[k]
            a_c = (a_j + _cross0(al, d) + _cross0(w, _cross0(w, d))
                   + 2.0 * _cross0(w, z) * qdT[k] + z * qddT[k])
            V_o[:, m] = z
        else:
            # R_j exp(K q) = R_j + sin q (R_j K) + (1 - cos q) (R_j K²)  (Rodrigues)
            K = skew(chain.axis[k])
            R_c = (R_j + np.sin(qT[k]) * np.matmul(K.T, R_j)
                   + (1.0 - np.cos(qT[k])) * np.matmul((K @ K).T, R_j))
            p_c = p_j
            w_c = w + z * qdT[k]
            al_c = al + z * qddT[k] + _cross0(w, z) * qdT[k]
            v_c, a_c = v_j, a_j
            V_o[:, m] = 0.0
            W_all[:, m] = z
        # v_r of the new origin = v_r of the old one + w_r x (p_c - p)
        np.add(V, _cross0(W_all[:, :m], (p_c - p)[:, None]), out=V_o[:, :m])
        W = W_all[:, :m + 1]
        rc = np.matmul(chain.com[k], R_c)
        V_com = V_o + _cross0(W, rc[:, None])
        if not trim:
            V_com = np.concatenate((V_com, np.zeros((3, nu - m - 1, N))), axis=1)
            W = np.concatenate((W, np.zeros((3, nu - m - 1, N))), axis=1)
        out.append(BodyMotion(
            R=np.transpose(R_c, (2, 0, 1)), p=p_c.T, p_com=(p_c + rc).T, omega=w_c.T,
            alpha=al_c.T, v_com=(v_c + _cross0(w_c, rc)).T,
            a_com=(a_c + _cross0(al_c, rc) + _cross0(w_c, _cross0(w_c, rc))).T,
            V=np.transpose(V_com, (2, 1, 0)), W=np.transpose(W, (2, 1, 0))))
        R, p, w, al, v, a = R_c, p_c, w_c, al_c, v_c, a_c
        V = V_o
    return out
