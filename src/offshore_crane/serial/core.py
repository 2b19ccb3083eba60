"""Loading a serial chain from a URDF and its Kane inverse dynamics (paper Eqs. 27-31).

Frames and units: the chain's *base* is a URDF link held still (the URDF root by
default). Unless a ``base_pose`` is given, the world frame is the base frame, so
``gravity`` and an external wrench are given in base axes. Joint coordinates are angles
[rad] for revolute and continuous joints (one number each, also for continuous joints,
which Pinocchio stores as ``(cos, sin)``) and displacements [m] for prismatic joints.
"""

from __future__ import annotations

import os
import weakref
from pathlib import Path

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError, ModelError
from offshore_crane.robot.chain import SerialChain, chain_from_urdf
from offshore_crane.robot.urdf import URDF, parse_urdf
from offshore_crane.validation import as_gravity, as_samples, same_length

#: Most random states one call draws (3 x 8 bytes x n joints each: 10 M states of a
#: 7-joint arm take 1.7 GB).
MAX_RANDOM = 10_000_000
# A rotation given as base pose must be orthonormal to this (absolute, per entry). Any
# matrix built from angles in float64 is so to ~1e-15; 1e-9 rejects hand-typed rounded
# matrices, which would silently scale the gravity and the wrench.
_ORTHONORMAL_TOL = 1e-9


def read_urdf(urdf) -> tuple[URDF, str | None]:
    """Parse a URDF given as a path, as XML text, or already parsed.

    Args:
        urdf: ``str`` or ``os.PathLike`` path to a ``.urdf`` file; or a ``str`` holding
            the XML itself (recognised by its first non-blank character ``<``); or a
            :class:`~offshore_crane.robot.urdf.URDF`.

    Returns:
        ``(parsed, text)``; ``text`` is None when ``urdf`` was already parsed.

    Raises:
        InputError: the file cannot be read.
        ModelError: the file is not a valid URDF.
    """
    if isinstance(urdf, URDF):
        return urdf, None
    if isinstance(urdf, str) and urdf.lstrip().startswith("<"):
        text = urdf
    elif isinstance(urdf, (str, os.PathLike)):
        try:
            text = Path(urdf).read_text(encoding="utf-8")
        except OSError as exc:
            raise InputError(f"cannot read the URDF file '{os.fspath(urdf)}': "
                             f"{exc.strerror or exc}", name="urdf") from None
        except UnicodeDecodeError as exc:
            raise InputError(f"{os.fspath(urdf)}: byte {exc.start} is not UTF-8 text: a URDF "
                             "is an XML file in UTF-8", name="urdf") from None
    else:
        raise InputError(f"urdf must be a path, URDF text or a parsed URDF, got "
                         f"{type(urdf).__name__}", name="urdf")
    return parse_urdf(text), text


def load_chain(urdf, tip: str | None = None, base: str | None = None) -> SerialChain:
    """Read a serial chain from a URDF for :func:`inverse_dynamics`.

    The movable joints below ``base`` must form one serial chain of revolute, continuous
    and prismatic joints; links welded by fixed joints are merged into one body (masses,
    centres of mass and inertias added exactly). The joint order is the chain order from
    the base, which is Pinocchio's order for the same URDF.

    Args:
        urdf: Path to a URDF file, URDF XML text, or a parsed URDF (see :func:`read_urdf`).
        tip: Optional link or frame to end the chain at. Only the movable joints on the
            path from ``base`` to ``tip`` are kept; every other movable joint below
            ``base`` (grippers, fingers, other branches, mimic joints) is locked at zero
            position and its links welded to their parent. ``tip`` is also the default
            point of application of the external wrench. Without ``tip``, the chain is
            every movable joint below ``base`` and must not branch.
        base: Link the chain is mounted on (held still); default the URDF's root link.

    Returns:
        :class:`~offshore_crane.robot.chain.SerialChain`: ``joint_names`` ``(n,)``,
        per joint its placement in the parent body ``p_parent_joint`` ``(n, 3)`` [m],
        ``R_parent_joint`` ``(n, 3, 3)``, unit ``axis`` ``(n, 3)`` (joint frame),
        ``prismatic`` ``(n,)``, limits ``lower``/``upper`` ``(n,)`` [rad or m, ±inf when
        absent]; per body ``mass`` ``(n,)`` [kg], ``com`` ``(n, 3)`` [m] and central
        ``inertia`` ``(n, 3, 3)`` [kg·m²] in the body frame; ``frames`` (every welded
        link: body index, position, orientation), ``tip`` and ``locked`` joint names.

    Raises:
        ModelError: naming the joint or link concerned: the chain branches (no tip), a
            joint on it is floating, planar or mimics another, ``tip`` or ``base`` is not
            a link of the URDF or ``tip`` is not below ``base``, no movable joint.
        InputError: the file cannot be read.
    """
    desc, _ = read_urdf(urdf)
    base_link = desc.root if base is None else base
    if base_link not in desc.inertials:
        raise ModelError(f"the URDF has no link '{base_link}' (the base asked for)",
                         element=base_link)
    from offshore_crane.robot.validate import validate

    validate(desc)                        # masses, inertias, joint ranges (every link)
    chain = chain_from_urdf(desc, base_link, tip=tip)
    if chain.n == 0:
        where = f"between '{base_link}' and the tip '{tip}'" if tip else f"below '{base_link}'"
        raise ModelError(f"the URDF has no movable joint {where}: nothing to solve",
                         element=tip or base_link)
    return chain


def random_states(chain: SerialChain, n_samples: int, seed=0):
    """Seeded random joint states for tests and cross-checks.

    Positions are uniform within the joint limits when both are finite, else in
    ``[-π, π]`` rad (revolute, continuous) or ``[-1, 1]`` m (prismatic); rates and
    accelerations are uniform in ``[-2, 2]`` (rad/s or m/s, rad/s² or m/s²).

    Args:
        chain: From :func:`load_chain`.
        n_samples: ``N`` ≥ 1.
        seed: Seed or :class:`numpy.random.Generator`.

    Returns:
        ``(q, qd, qdd)``, each ``(N, n)``.
    """
    if not 1 <= int(n_samples) <= MAX_RANDOM:
        raise InputError(f"the number of random states must be at least 1 and at most "
                         f"{MAX_RANDOM:,}, got {n_samples}", name="n_samples")
    if not isinstance(seed, np.random.Generator) and not (isinstance(seed, (int, np.integer))
                                                          and seed >= 0):
        raise InputError(f"the seed must be an integer ≥ 0, got {seed!r}", name="seed")
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    N, n = int(n_samples), chain.n
    finite = np.isfinite(chain.lower) & np.isfinite(chain.upper)
    default = np.where(chain.prismatic, 1.0, np.pi)
    lo = np.where(finite, chain.lower, -default)
    hi = np.where(finite, chain.upper, default)
    q = lo + (hi - lo) * rng.random((N, n))
    qd = rng.uniform(-2.0, 2.0, (N, n))
    qdd = rng.uniform(-2.0, 2.0, (N, n))
    return q, qd, qdd


def _vectors(name: str, x, N: int) -> np.ndarray:
    """``(3,)`` or ``(N, 3)`` finite -> ``(N, 3)`` (a read-only broadcast view for (3,))."""
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an array of numbers", name=name) from None
    if a.shape not in ((3,), (N, 3)):
        raise InputError(f"{name} has shape {a.shape}; expected (3,) or ({N}, 3)", name=name)
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} has non-finite values", name=name)
    return np.broadcast_to(a, (N, 3))


def _rotations(name: str, x, N: int) -> np.ndarray:
    """``(3, 3)`` or ``(N, 3, 3)`` proper rotations -> ``(N, 3, 3)``."""
    try:
        R = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an array of numbers", name=name) from None
    if R.shape not in ((3, 3), (N, 3, 3)):
        raise InputError(f"{name} has shape {R.shape}; expected (3, 3) or ({N}, 3, 3)",
                         name=name)
    if not np.all(np.isfinite(R)):
        raise InputError(f"{name} has non-finite values", name=name)
    err = np.abs(R @ np.swapaxes(R, -1, -2) - np.eye(3)).max()
    if err > _ORTHONORMAL_TOL or np.any(np.linalg.det(R) < 0.0):
        raise InputError(f"{name} is not a rotation matrix (|R Rᵀ − I| = {err:.1e}, or "
                         "det < 0)", name=name)
    return np.broadcast_to(R, (N, 3, 3))


def inverse_dynamics(chain: SerialChain, q, qd, qdd, gravity=GRAVITY, wrench=None,
                     frame: str | None = None, base_pose=None,
                     backend: str = "auto") -> np.ndarray:
    """Joint torques and forces of a fixed-base serial chain by Kane's method.

    The arm recursion of the hybrid robot's formulas (paper Eqs. 27-30,
    :func:`offshore_crane.dynamics.formulas.arm_forward`) gives every body's motion and
    its inertia-and-gravity wrench ``(m (a − g), I α + ω × I ω)``; the generalized forces
    (Eq. 31, ``F_r + F*_r = 0``) are then accumulated from the tip
    (:func:`~offshore_crane.dynamics.formulas.arm_backward`): joint k's force is
    ``z_k · (moment about o_k of the bodies beyond it)`` (revolute) or ``z_k · (their
    force)`` (prismatic). An external wrench on a body enters its wrench with a minus sign.

    Args:
        chain: From :func:`load_chain`.
        q: ``(N, n)`` or ``(n,)`` joint positions [rad, m] in ``chain.joint_names``
            order (a continuous joint is one angle).
        qd: Same shape, rates [rad/s, m/s].
        qdd: Same shape, accelerations [rad/s², m/s²].
        gravity: ``(3,)`` gravity acceleration in world axes [m/s²].
        wrench: Optional ``(force, torque)`` exerted *on* the robot by its environment,
            each ``(3,)`` or ``(N, 3)`` in world axes: ``force`` [N] applied at the
            origin ``P`` of ``frame``, ``torque`` [N·m] its moment about ``P``.
        frame: Link or welded frame where the wrench acts; default ``chain.tip``, else
            the last body's link. A frame welded to the base takes no torque off the joints.
        base_pose: Optional ``(R_world_base, p_world_base)``, ``(3, 3)`` or ``(N, 3, 3)``
            and ``(3,)`` or ``(N, 3)`` [m]: where the base is held still. Default: the
            base frame is the world frame. (Only ``R`` changes the result: it turns the
            world-axes gravity and wrench into the base's.)

    Returns:
        ``(N, n)`` (``(n,)`` for a 1-D ``q``) generalized forces along each joint axis:
        [N·m] for revolute and continuous joints, [N] for prismatic joints.

    Raises:
        InputError: wrong shapes, non-finite values, a base rotation that is not one, an
            unknown backend.
        ModelError: ``frame`` is not a link of the chain.
        BackendMissingError: ``backend="numba"`` without Numba.
    """
    if wrench is None and base_pose is None and backend in ("auto", "numba"):
        tau = _single(chain, q, qd, qdd, gravity)      # one plain sample: the short way
        if tau is not None:
            return tau
    from offshore_crane.dynamics.runtime import resolve_backend

    backend = resolve_backend(backend)
    n = chain.n
    q, single = as_samples("q", q, n)
    qd, _ = as_samples("qd", qd, n)
    qdd, _ = as_samples("qdd", qdd, n)
    N = same_length(q=q, qd=qd, qdd=qdd)
    g = as_gravity(gravity)
    R_b = np.broadcast_to(np.eye(3), (N, 3, 3))
    if base_pose is not None:
        try:
            R_b, p_b = base_pose
        except (TypeError, ValueError):
            raise InputError("base_pose must be a pair (R_world_base, p_world_base)",
                             name="base_pose") from None
        R_b = _rotations("base_pose R", R_b, N)
        _vectors("base_pose p", p_b, N)       # validated; a base at rest: p changes nothing
    load = None
    if wrench is not None:
        try:
            F, M = wrench
        except (TypeError, ValueError):
            raise InputError("wrench must be a pair (force, torque)", name="wrench") from None
        F, M = _vectors("wrench force", F, N), _vectors("wrench torque", M, N)
        name = frame or chain.tip or chain.body_names[-1]
        if name not in chain.frames:
            raise ModelError(f"the wrench frame '{name}' is not a link of the chain "
                             f"(links: {', '.join(chain.frames)})", element=name)
        load = (name, F, M)
    tau = (_compiled(chain, q, qd, qdd, g, R_b, load) if backend == "numba"
           else _solve(chain, q, qd, qdd, g, R_b, load))
    return tau[0] if single else tau


def _single(chain: SerialChain, q, qd, qdd, gravity):
    """One sample given as three ``(n,)`` (or ``(1, n)``) float arrays, no wrench, no
    base pose, finite, Numba installed: the compiled sample called with no more checking
    than that (the general path's validation costs ~15 µs a call, the sample ~1.5 µs);
    None otherwise (the general path then validates, and raises what it finds)."""
    n = chain.n
    if not (type(q) is type(qd) is type(qdd) is np.ndarray and q.shape == qd.shape
            == qdd.shape and q.shape in ((n,), (1, n)) and q.dtype == qd.dtype
            == qdd.dtype == np.float64):
        return None
    if not _KERNEL:
        from offshore_crane.dynamics.runtime import numba_available

        if not numba_available():
            return None
        from offshore_crane.serial import kernels

        _KERNEL.append(kernels.kane_one)
    C = _constants(chain)
    tau = np.empty(n)
    one = q.ndim == 1
    if not _KERNEL[0](C.flat, C.layout, C.prismatic, q if one else q[0], qd if one else qd[0],
                      qdd if one else qdd[0], as_gravity(gravity), tau):
        return None                                  # not finite: the general path says so
    return tau if one else tau[None]


#: The compiled loop, once loaded (the single-sample path looks it up once).
_KERNEL: list = []


def _constants(chain: SerialChain):
    """The chain's packed constants for the compiled loop, built once per chain."""
    C = _CONSTANTS.get(id(chain))
    if C is None:
        from offshore_crane.serial import kernels

        C = _CONSTANTS[id(chain)] = kernels.constants(chain)
        weakref.finalize(chain, _CONSTANTS.pop, id(chain), None)
    return C


def _compiled(chain: SerialChain, q, qd, qdd, g, R_b, load) -> np.ndarray:
    """:func:`_solve`'s formulas in one compiled loop over the samples."""
    from offshore_crane.dynamics.runtime import compiled_kernels

    compiled_kernels()                                 # Numba installed, or say so
    from offshore_crane.serial import kernels

    C = _constants(chain)
    N = q.shape[0]
    R = np.ascontiguousarray(R_b[:1] if R_b.strides[0] == 0 else R_b)
    k, lever, F, M = -1, np.zeros(3), np.zeros((1, 3)), np.zeros((1, 3))
    if load is not None:
        name, F, M = load
        k, p_frame, _ = chain.frames[name]
        if k >= 0:
            lever = np.asarray(p_frame, dtype=float) - chain.com[k]
        F, M = (np.array(x[:1] if x.strides[0] == 0 else x, dtype=float)   # writable,
                for x in (F, M))          # as the defaults: one signature to compile
    tau = np.empty((N, chain.n))
    f = np.ascontiguousarray
    kernels.kane(C.flat, C.layout, C.prismatic, f(q), f(qd), f(qdd), f(g, dtype=float), R,
                 k if k >= 0 else -1, lever, F, M, tau)
    return tau


#: Each chain's constants for the compiled loop, by ``id`` (dropped with the chain).
_CONSTANTS: dict = {}


def _solve(chain: SerialChain, q, qd, qdd, g, R_b, load) -> np.ndarray:
    """The formulas' arm recursion on the chain, vectorised over the N samples."""
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.formulas import ATT_, F_, STORE_WIDTH, T_, KaneConstants

    B = backends.NUMPY
    N, n = q.shape
    C = KaneConstants(*([None] * len(KaneConstants._fields)))._replace(
        n_arm=n, arm_t=chain.p_parent_joint, arm_Ro=chain.R_parent_joint, arm_axis=chain.axis,
        arm_prism=chain.prismatic, arm_m=chain.mass, arm_c=chain.com, arm_I=chain.inertia)
    R = tuple(tuple(R_b[:, i, j] for j in range(3)) for i in range(3))
    zero = (np.zeros(N),) * 3
    store = np.empty((n, STORE_WIDTH), dtype=object)
    B.arm_forward(C, R, zero, zero, zero, q.T, qd.T, qdd.T, 0, tuple(g), store, True)
    if load is not None:
        name, F, M = load
        k, p_frame, _ = chain.frames[name]
        if k >= 0:      # the force acts at the frame's origin P: moment about the CoM
            Rk = (B.take(store, k, ATT_), B.take(store, k, ATT_ + 3), B.take(store, k, ATT_ + 6))
            lever = B.mv(Rk, B.sub(tuple(p_frame), tuple(chain.com[k])))
            Fe, Me = tuple(F.T), tuple(M.T)
            B.put(store, k, F_, B.sub(B.take(store, k, F_), Fe))
            B.put(store, k, T_, B.sub(B.take(store, k, T_), B.add(Me, B.cross(lever, Fe))))
    rows = np.empty(n, dtype=object)
    B.arm_backward(C, store, rows)
    return np.column_stack([np.broadcast_to(r, (N,)) for r in rows])


def warm_up() -> list[tuple[str, float]]:
    """Compile (or load from the cache) the serial chain's loops, on the lab robot's arm
    (the loops' types are the same for every chain): ``[(name, seconds)]``."""
    import time

    from offshore_crane.robot import load_robot

    t0 = time.perf_counter()
    chain = load_chain(load_robot().urdf, base="platform", tip="arm_tip")
    q = np.zeros((2, chain.n))
    inverse_dynamics(chain, q, q, q, wrench=((0.0, 0.0, 1.0), (0.0, 0.0, 0.0)))
    inverse_dynamics(chain, q[0], q[0], q[0])
    return [("serial chain kernels", time.perf_counter() - t0)]
