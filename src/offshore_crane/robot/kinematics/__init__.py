"""Kinematics of the hybrid robot: the formulas (:mod:`.formulas`), the workspace and
singularity checks (:mod:`.workspace`), and batched evaluations for users and tests.

:func:`legs` evaluates the leg formulas on ``(N, 9)`` trajectories with NumPy (the
vectorised backend of the one text) and returns every leg quantity with leading axes
``(N, 6)``. It is meant for analysis, plots and checks (a motion source can check its own
output against the robot); the dynamics kernels evaluate the same formulas inline.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.lazy import submodule_getattr
from offshore_crane.robot.kinematics import formulas as F
from offshore_crane.validation import thread_count

__all__ = ["LegState", "actuator_motion", "check_workspace", "leg_positions", "legs",
           "platform_pose"]


@dataclass
class LegState:
    """Kinematics of the six legs; arrays have leading axes ``(N, 6)`` (base frame).

    Attributes:
        p_S, v_S, a_S: ``(N, 6, 3)`` sphere centre S_i [m], [m/s], [m/s²].
        length, rate, accel: ``(N, 6)`` leg length l_i [m], l̇_i [m/s], l̈_i [m/s²].
        u: ``(N, 6, 3)`` unit vector from P_i to S_i.
        theta, theta_d, theta_dd: ``(N, 6, 2)`` U-joint angles [rad], rates, accelerations.
        cos_theta2: ``(N, 6)`` ``cos θ2`` (zero at the U-joint gimbal singularity).
        R: ``(N, 6, 3, 3)`` ``R_base_leg`` (both leg links' frames).
        omega, alpha: ``(N, 6, 3)`` the legs' angular velocity [rad/s], acceleration.
        V_S: ``(N, 6, 6, 3)`` partial velocities of S_i for u1..u6 [m/s per u_r].
        J: ``(N, 6, 6)`` leg-length (actuation) Jacobian, ``l̇ = J · q̇[:6]``.
    """

    p_S: np.ndarray
    v_S: np.ndarray
    a_S: np.ndarray
    length: np.ndarray
    rate: np.ndarray
    accel: np.ndarray
    u: np.ndarray
    theta: np.ndarray
    theta_d: np.ndarray
    theta_dd: np.ndarray
    cos_theta2: np.ndarray
    R: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    V_S: np.ndarray
    J: np.ndarray


#: Samples per block of :func:`check_workspace`: the block's temporaries (64 KiB each)
#: stay in cache; 1.08·10⁶ samples took 0.48 s in one block, 0.27 s in blocks of 2¹³
#: (leg positions alone, this project's 2-core machine).
CHECK_BLOCK = 1 << 13


def _samples(x, N=None):
    from offshore_crane.validation import as_samples

    return as_samples("q", x)[0] if x is not None else np.zeros((N, 9))


def platform_pose(q) -> tuple[np.ndarray, np.ndarray]:
    """``(p_base_O2 (N, 3) [m], R_base_platform (N, 3, 3))`` of ``q`` ``(N, 9)``."""
    q = _samples(q)
    R = F.attitude(q.T)[0]
    return q[:, :3].copy(), np.moveaxis(np.array(R, dtype=float), (0, 1), (1, 2))


def legs(robot, q, qd=None, qdd=None) -> LegState:
    """Leg kinematics along ``q`` ``(N, 9)`` (rates and accelerations zero if omitted).

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q, qd, qdd: ``(N, 9)`` or ``(9,)`` [m, rad], rates, accelerations.

    Returns:
        :class:`LegState`.
    """
    q = _samples(q)
    N = len(q)
    qd, qdd = _samples(qd, N), _samples(qdd, N)
    m = robot.hybrid
    RU = m.R_base_U
    qT, qdT, qddT = q.T, qd.T, qdd.T
    R, w4, w5, w6 = F.attitude(qT)
    omega, alpha = F.platform_rates(w4, w5, qdT, qddT)
    p, v, a = (qT[0], qT[1], qT[2]), (qdT[0], qdT[1], qdT[2]), (qddT[0], qddT[1], qddT[2])
    out = {k: [] for k in ("p_S", "v_S", "a_S", "length", "rate", "accel", "u", "theta",
                           "theta_d", "theta_dd", "cos_theta2", "R", "omega", "alpha", "V_S")}
    Vw, Ww = np.empty((9, 3), dtype=object), np.empty((9, 3), dtype=object)
    with np.errstate(divide="ignore", invalid="ignore"):
        for i in range(len(RU)):
            X, Y, Z = RU[i, :, 0], RU[i, :, 1], RU[i, :, 2]
            r, d, length, il, u, dx, dy, dz, h = F.leg_geometry(p, R, m.p_platform_S[i],
                                                                m.p_base_P[i], X, Y, Z)
            a2, n = F.ujoint_axes(X, Z, dx, dz, h)
            v_S = F.point_velocity(v, omega, r)
            a_S = F.point_acceleration(a, omega, alpha, r)
            rate, accel, w, al, _, _, th1d, th2d = F.leg_motion(v_S, a_S, u, length, il, Y, a2,
                                                                n, length / h, True)
            F.platform_partials(w4, w5, w6, r, Vw, Ww)
            values = dict(p_S=F.add(p, r), v_S=v_S, a_S=a_S, length=length, rate=rate,
                          accel=accel, u=u, theta=F.ujoint_angles(dx, dy, dz, h),
                          theta_d=(th1d, th2d), theta_dd=(F.dot(al, Y), F.dot(al, a2)),
                          cos_theta2=h / length, R=F.leg_frame(u, a2), omega=w, alpha=al,
                          V_S=[[Vw[r_, k] for k in range(3)] for r_ in range(6)])
            for key, value in values.items():
                out[key].append(np.moveaxis(_array(value, N), -1, 0))
    res = {k: np.stack(v, axis=1) for k, v in out.items()}
    J = np.einsum("nlk,nlrk->nlr", res["u"], res["V_S"])
    return LegState(J=J, **res)


def _array(value, N: int) -> np.ndarray:
    """Nested tuples of ``(N,)`` arrays or scalars as one array ``nested + (N,)``."""
    if isinstance(value, (tuple, list)):
        return np.stack([_array(v, N) for v in value])
    return np.broadcast_to(np.asarray(value, dtype=float), (N,))


def leg_positions(robot, q) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The legs' position quantities along ``q`` ``(N, 9)`` [m, rad], no rates:
    ``(length (N, 6) [m], height (N, 6) [m] of each sphere centre S_i above its U-joint
    centre P_i in the base frame, theta (N, 6, 2) [rad] U-joint angles)``, from the same
    formulas as :func:`legs` and the dynamics kernels."""
    q = _samples(q)
    m = robot.hybrid
    qT = q.T
    R = F.attitude(qT)[0]
    p = (qT[0], qT[1], qT[2])
    length, height, theta = [], [], []
    with np.errstate(divide="ignore", invalid="ignore"):
        for i, RU in enumerate(m.R_base_U):
            _, d, l_i, _, _, dx, dy, dz, h = F.leg_geometry(p, R, m.p_platform_S[i],
                                                            m.p_base_P[i], RU[:, 0],
                                                            RU[:, 1], RU[:, 2])
            length.append(l_i)
            height.append(d[2])
            theta.append(np.stack(F.ujoint_angles(dx, dy, dz, h), axis=-1))
    return np.stack(length, axis=1), np.stack(height, axis=1), np.stack(theta, axis=1)


class WorkspaceWatch:
    """:func:`check_workspace` of a motion while it is being computed: :meth:`feed` takes
    the blocks of :data:`CHECK_BLOCK` samples a record has filled so far (a simulation's
    q, while its loop runs on another core), and :func:`check_workspace` given the
    watch checks only the samples past them: the same blocks, the same verdict.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
    """

    def __init__(self, robot):
        from offshore_crane.robot.kinematics import workspace as ws

        self.robot, self.limits = robot, ws.limits_of(robot.hybrid)
        self.health = ws.new_health()
        #: Samples taken so far (a multiple of :data:`CHECK_BLOCK` until the last block).
        self.done = 0

    def _take(self, q: np.ndarray, end: int) -> None:
        from offshore_crane.robot.kinematics import workspace as ws

        chunk = q[self.done:end]
        ws.record_limits(self.health, self.limits, chunk, *leg_positions(self.robot, chunk),
                         offset=self.done)
        self.done = end

    def feed(self, q: np.ndarray, ready: int) -> None:
        """Take the whole blocks among the first ``ready`` rows of ``q`` ``(N, 9)`` [m,
        rad] not taken yet (rows past ``ready`` are not read)."""
        while self.done + CHECK_BLOCK <= ready:
            self._take(q, self.done + CHECK_BLOCK)

    def health_of(self, q: np.ndarray) -> np.ndarray:
        """The health record of all of ``q`` (its first :attr:`done` rows those fed)."""
        while self.done < len(q):
            self._take(q, min(self.done + CHECK_BLOCK, len(q)))
        return self.health


def check_workspace(robot, q, t=None, *, pose: str | None = None, threads: int = 1,
                    watch: WorkspaceWatch | None = None) -> None:
    """Raise :class:`~offshore_crane.errors.WorkspaceError` for the first sample of ``q``
    ``(N, 9)`` [m, rad] outside the robot's workspace: arm joints outside their limits,
    a sphere centre not above its U-joint (platform below the base), a leg length outside
    its stroke, a U-joint angle outside its limits — the checks and messages of the
    dynamics' ``limits=True``, from the positions alone (no dynamics evaluated; a hanging
    payload changes nothing here).

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` coordinates [m, rad], finite.
        t: ``(N,)`` times [s] for the message, or None.
        pose: The name of one pose a user gave (``"--pose"``): the message names it, not
            a sample, and asks for a pose inside the workspace.
        threads: Threads sharing the blocks of :data:`CHECK_BLOCK` samples (NumPy
            releases the GIL in its loops); the same verdict in any count.
        watch: A :class:`WorkspaceWatch` fed with the first blocks of ``q`` as it was
            being filled: only the samples past them are checked now (one thread);
            ignored when it took more samples than ``q`` holds.

    Raises:
        InputError: q is not finite or has the wrong shape, a bad ``threads``.
        WorkspaceError: as above.
    """
    from offshore_crane.robot.kinematics import workspace as ws

    q = _samples(q)
    limits = ws.limits_of(robot.hybrid)
    starts = range(0, len(q), CHECK_BLOCK)

    def record(share) -> np.ndarray:
        health = ws.new_health()
        for a in share:
            chunk = q[a:a + CHECK_BLOCK]
            ws.record_limits(health, limits, chunk, *leg_positions(robot, chunk), offset=a)
        return health

    threads = min(thread_count(threads), len(starts))
    if threads <= 1:
        if watch is None or watch.done > len(q):
            watch = WorkspaceWatch(robot)
        health = watch.health_of(q)
    else:                                  # every thread-th block: equal shares
        from concurrent.futures import ThreadPoolExecutor

        with ThreadPoolExecutor(threads) as pool:
            health = ws.merge(list(pool.map(record, (starts[i::threads]
                                                     for i in range(threads)))))
    ws.check_limits(health, limits, q, None if t is None else np.asarray(t, dtype=float),
                    pose)


def actuator_motion(robot, q, qd, legs: bool = True):
    """Position and rate of each actuator's joint.

    The leg lengths and rates are evaluated by the kinematics' one text
    (:mod:`offshore_crane.robot.kinematics.formulas`: ``attitude``, ``platform_rates``,
    ``leg_geometry``, ``point_velocity``) on NumPy arrays, vectorised over the samples:
    ``l_i = |O2 + R s_i − P_i|``, ``l̇_i = u_i · (v + ω × R s_i)``; the same values as
    :func:`offshore_crane.robot.kinematics.legs` without its partial velocities and frames.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q, qd: ``(N, 9)`` [m, rad], [m/s, rad/s].
        legs: False: leave the leg columns NaN (the legs not evaluated).

    Returns:
        ``(p, v)`` each ``(N, 9)``: ``p = [q7, q8, q9, l1..l6]`` [rad, m] and its rate
        ``v = [q̇7, q̇8, q̇9, l̇1..l̇6]`` [rad/s, m/s].
    """
    N = len(q)
    p, v = np.full((N, 9), np.nan), np.full((N, 9), np.nan)
    p[:, :3], v[:, :3] = q[:, 6:9], qd[:, 6:9]
    if legs:
        m = robot.hybrid
        qT, qdT = q.T, qd.T
        R, w4, w5, _ = F.attitude(qT)
        omega, _ = F.platform_rates(w4, w5, qdT, qdT)
        origin, velocity = (qT[0], qT[1], qT[2]), (qdT[0], qdT[1], qdT[2])
        for i in range(len(m.R_base_U)):
            U = m.R_base_U[i]
            r, _, length, _, u, *_ = F.leg_geometry(origin, R, m.p_platform_S[i],
                                                    m.p_base_P[i], U[:, 0], U[:, 1],
                                                    U[:, 2])
            p[:, 3 + i] = length
            v[:, 3 + i] = F.dot(u, F.point_velocity(velocity, omega, r))
    return p, v


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
