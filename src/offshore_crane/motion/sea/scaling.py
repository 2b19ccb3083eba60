"""Froude scaling of the ship's motion onto the platform, and the search for the smallest scale
whose motion stays in the robot's workspace.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import SeaStateError, SeaWorkspaceError, WorkspaceError
from offshore_crane.motion.operations import as_times
from offshore_crane.motion.sea.arguments import DEFAULT_DIRECTIONS, SCALE_HINT, real
from offshore_crane.motion.sea.synthesis import ShipMotion, sea_state


# Workspace search: relative width of the final bracket on lambda.
SCALE_RTOL = 1e-3
# Workspace search: doublings of lambda tried before giving up. After 60 the translations
# are scaled by 2^-60 < 1e-18, below the float resolution of the positions (~1e-16 m at
# 1 m): the pose is then the rotation-only pose to round-off.
_MAX_DOUBLINGS = 60


# ------------------------------------------------------------------ Froude-scaled motion
@dataclass(frozen=True, eq=False)
class SeaMotion:
    """The robot's reference motion from a ship in a sea state, at model scale λ.

    ``q, qd, qdd = motion(t)`` at any model-scale times (an integrator's stages too):
    ``q1..q3 = home + x_P(t√λ)/λ``, ``q4..q6 = θ(t√λ)`` (roll, pitch, yaw),
    ``q7..q9`` from the crane operation (zeros without one); rates and accelerations
    are the exact derivatives (Froude: linear rates / √λ, linear accelerations
    unchanged, angular rates × √λ, angular accelerations × λ). Build it with
    :func:`sea_motion`.

    Attributes:
        ship: The full-scale :class:`ShipMotion`.
        scale: λ, full-scale length / model length (> 0).
        home: ``(9,)`` home pose: zeros except ``q3 = home_height`` [m].
        operation: :class:`~offshore_crane.motion.operations.Operation` or None.
        duration: Model-scale record length [s].
        rate: Model-scale sampling rate [Hz].
    """

    ship: ShipMotion
    scale: float
    home: np.ndarray
    operation: object
    duration: float
    rate: float

    def time_grid(self) -> np.ndarray:
        """The model-scale record's times ``(N,)`` [s] (``trajectories.time_grid``)."""
        from offshore_crane.motion.trajectories import time_grid

        return time_grid(self.duration, self.rate)

    def __call__(self, t, threads: int = 1):
        """``(q, qd, qdd)`` at model-scale times ``t`` [s]: each ``(n, 9)`` (``(9,)`` for a
        scalar), [m, rad], [m/s, rad/s], [m/s², rad/s²]; ``threads`` share the ship's FFT
        (:meth:`ShipMotion.__call__`: the same numbers in any count).

        Raises:
            SeaStateError: non-finite times, or times beyond the record's non-repeating
                span (``ship.repetition_period / √λ``). InputError: a bad ``threads``.
        """
        t, scalar = as_times(t)
        root = math.sqrt(self.scale)
        xva = _full_scale(self.ship, self.scale, self.duration, t, threads)
        n = t.size
        q = np.empty((n, 9))
        qd = np.empty((n, 9))
        qdd = np.empty((n, 9))
        np.divide(xva[:, 0:3], self.scale, out=q[:, 0:3])       # Froude: x/λ, φ;
        q[:, 3:6] = xva[:, 3:6]
        q[:, :3] += self.home[:3]
        np.divide(xva[:, 6:9], root, out=qd[:, 0:3])            # v/√λ, ω√λ;
        np.multiply(xva[:, 9:12], root, out=qd[:, 3:6])
        qdd[:, 0:3] = xva[:, 12:15]                              # a, α λ
        np.multiply(xva[:, 15:18], self.scale, out=qdd[:, 3:6])
        if self.operation is None:
            q[:, 6:] = self.home[6:]
            qd[:, 6:] = 0.0
            qdd[:, 6:] = 0.0
        else:
            q[:, 6:], qd[:, 6:], qdd[:, 6:] = self.operation(t)
        return (q[0], qd[0], qdd[0]) if scalar else (q, qd, qdd)

    def trajectory(self, name: str = "sea", threads: int = 1):
        """The record on its design grid as a
        :class:`~offshore_crane.motion.trajectories.Trajectory` (``threads`` as
        :meth:`__call__`)."""
        from offshore_crane.motion.trajectories import Trajectory

        t = self.time_grid()
        return Trajectory(name, t, *self(t, threads), source=self)

    def check(self, robot, trajectory=None, threads: int = 1) -> None:
        """Raise :class:`SeaWorkspaceError` if the record leaves the robot's workspace.

        Every sample's leg lengths, U-joint angles and sphere heights are checked by
        :func:`offshore_crane.dynamics.solve` (``limits=True``). On failure the error
        names the first violation (sample, leg, value) and the smallest scale λ at which
        the whole record fits: found by bisection in log λ to a relative bracket of
        :data:`SCALE_RTOL`, on the assumption that a record that fits at λ also fits at
        every larger λ (the translations shrink towards home while the rotations stay);
        the bracket's ends are checked (the lower one fails, the reported upper one fits
        over the whole record). If the rotations alone (λ → ∞) leave the workspace, it
        says that no scale fits.

        Args:
            robot: From :func:`offshore_crane.load_robot`.
            trajectory: The design-grid :class:`Trajectory` if already computed.
            threads: Threads sharing the record's check (and its synthesis when
                ``trajectory`` is None).
        """
        traj = self.trajectory(threads=threads) if trajectory is None else trajectory
        _check_scaled(robot, traj.t, traj.q, self.home, self.scale, threads)


def _full_scale(ship: ShipMotion, scale: float, duration: float, t: np.ndarray,
                threads: int = 1):
    """``ship``'s ``x, v, a`` side by side, ``(n, 18)`` (:meth:`ShipMotion.side_by_side`),
    at model-scale times ``t (n,)`` [s] (full scale ``t √λ``).

    Raises:
        SeaStateError: a time outside ``[0, repetition period / √λ]``, the model-scale
            span on which the sea does not repeat.
    """
    root = math.sqrt(scale)
    end = ship.repetition_period / root
    outside = (t < 0.0) | (t > end)
    if outside.any():
        k = int(np.argmax(outside))
        raise SeaStateError(
            f"t[{k}] = {float(t[k]):.9g} s is outside [0, {end:.9g}] s, the model-scale "
            f"span on which this sea does not repeat (record {duration:g} s at scale "
            f"{scale:g}): build the motion for a longer duration", name="t", index=k)
    return ship.side_by_side(t * root, threads=threads)


@dataclass(frozen=True, eq=False)
class DeckMotion:
    """A point on a second vessel's deck in the same sea state, at model scale λ: its
    displacement from its mean position, base axes (the second vessel's axes taken
    parallel to the first's: x forward, y port, z up), for a crane landing a load on it
    (ship-to-ship transfer). ``x, v, a = deck(t)`` at model-scale times: each ``(n, 3)``
    [m], [m/s], [m/s²] — ``x_P(t√λ)/λ``, ``v_P/√λ``, ``a_P`` (Froude). Build it with
    :func:`deck_motion`.

    Attributes:
        ship: The second vessel's full-scale :class:`ShipMotion` at the deck point.
        scale: λ. duration: The model-scale record it was built for [s].
    """

    ship: ShipMotion
    scale: float
    duration: float

    def __call__(self, t):
        t, scalar = as_times(t)
        xva = _full_scale(self.ship, self.scale, self.duration, t)
        out = (xva[:, 0:3] / self.scale, xva[:, 6:9] / math.sqrt(self.scale),
               np.ascontiguousarray(xva[:, 12:15]))
        return tuple(o[0] for o in out) if scalar else out


def deck_motion(duration, rate, hs, tp, heading_deg, scale, *, vessel="supply", seed=0,
                point=(0.0, 0.0, 0.0), kind: str = "jonswap", gamma=None, spreading=None,
                directions: int = DEFAULT_DIRECTIONS, highpass=None) -> DeckMotion:
    """The motion of a point on a second vessel's deck (:class:`DeckMotion`): the
    vessel's RAOs (``vessel``) in the sea state ``hs, tp, heading_deg`` with its own
    random phases (``seed``: another vessel elsewhere in the same sea), transferred to
    ``point`` [m] (full scale, the vessel's axes from its RAO reference point), on the
    frequency grid of a model-scale record of ``duration`` [s] at ``rate`` [Hz].

    Raises:
        SeaStateError: bad arguments (the checks of :func:`sea_state`).
    """
    from offshore_crane.motion.trajectories import time_grid

    time_grid(duration, rate)
    scale = real(scale, "scale", "-", SCALE_HINT, low=0.0)
    root = math.sqrt(scale)
    ship = sea_state(hs, tp, heading_deg, duration * root, rate / root, vessel=vessel,
                     seed=seed, point=point, kind=kind, gamma=gamma, spreading=spreading,
                     directions=directions, highpass=highpass)
    return DeckMotion(ship, scale, float(duration))


def _violation(robot, q, t, threads: int = 1):
    """The WorkspaceError that ``q`` meets (:func:`offshore_crane.robot.kinematics.check_workspace`),
    or None."""
    from offshore_crane.robot.kinematics import check_workspace

    try:
        check_workspace(robot, q, t, threads=threads)
    except WorkspaceError as exc:
        return exc
    return None


def _what(exc) -> str:
    """The descriptive part of a workspace message (before its advice)."""
    return str(exc).split(";")[0]


def _check_scaled(robot, t, q, home, scale, threads: int = 1) -> None:
    from offshore_crane.conventions import ARM_JOINTS

    first = _violation(robot, q, t, threads)
    if first is None:
        return
    if first.joint in ARM_JOINTS:
        raise first
    shift = (q[:, :3] - home[:3]) * scale                 # full-scale translations [m]

    def pose(lam, idx=None):
        qq = q.copy() if idx is None else q[idx].copy()
        qq[:, :3] = home[:3] + (shift if idx is None else shift[idx]) / lam
        return qq

    head = (f"the ship motion at scale {scale:g} leaves the workspace: {_what(first)}")
    data = dict(joint=first.joint, index=first.index, value=first.value, scale=scale)
    rot = _violation(robot, pose(math.inf), t, threads)
    if rot is not None:
        raise SeaWorkspaceError(
            f"{head}; no scale fits: the rotations alone (translations removed) leave it too "
            f"({_what(rot)}): choose a milder sea state, another heading or a point nearer "
            "the vessel's centre of rotation", rotations_only=True, **data)
    witnesses = {first.index}

    def fits(lam) -> bool:
        idx = np.array(sorted(witnesses))
        if _violation(robot, pose(lam, idx), t[idx]) is not None:
            return False
        exc = _violation(robot, pose(lam), t, threads)
        if exc is not None:
            witnesses.add(exc.index)
            return False
        return True

    lo, hi = scale, 2.0 * scale
    for _ in range(_MAX_DOUBLINGS):
        if fits(hi):
            break
        lo, hi = hi, 2.0 * hi
    else:
        raise SeaWorkspaceError(
            f"{head}; no scale up to {hi:g} fits although the rotations alone do: the "
            "rotations are at the workspace's edge; choose a milder sea state",
            rotations_only=False, **data)
    while hi / lo - 1.0 > SCALE_RTOL:
        mid = math.sqrt(lo * hi)
        if fits(mid):
            hi = mid
        else:
            lo = mid
    span = (t[-1] - t[0]) * math.sqrt(scale)
    raise SeaWorkspaceError(
        f"{head}; this full-scale record ({span:.6g} s) fits from scale {hi:.4g} (bisection: "
        f"{lo:.4g} fails, {hi:.4g} fits): use scale >= {hi:.4g} (to replay the same record "
        f"there, scale duration and rate by sqrt({scale:g}/scale); other values draw "
        "another record), or a milder sea state", min_scale=hi, **data)


def _sea_motion(duration, rate, hs, tp, heading_deg, scale, robot, **options):
    from offshore_crane.motion.operations import Operation
    from offshore_crane.motion.trajectories import time_grid

    operation = options.pop("operation", None)
    time_grid(duration, rate)                           # validates duration, rate, size
    scale = real(scale, "scale", "-", SCALE_HINT, low=0.0)
    try:
        home = robot.home_pose()
    except AttributeError:
        raise SeaStateError("robot must come from offshore_crane.load_robot() (its "
                            "parameters give home_height)", name="robot") from None
    if operation is not None:
        if isinstance(operation, Operation):
            operation.check(robot)
        else:
            operation = Operation.from_waypoints(operation, robot)
    root = math.sqrt(scale)
    ship = sea_state(hs, tp, heading_deg, duration * root, rate / root, **options)
    return SeaMotion(ship, scale, home, operation, float(duration), float(rate))


def sea_motion(duration, rate, hs, tp, heading_deg, scale, robot, *, vessel="supply", seed=0,
               kind: str = "jonswap", gamma=None, point=(0.0, 0.0, 0.0), spreading=None,
               directions: int = DEFAULT_DIRECTIONS, highpass=None, operation=None,
               check: bool = True) -> SeaMotion:
    """The robot's reference motion (a callable source) from a ship in a sea state.

    Args:
        duration: Length of the model-scale record [s] (the full-scale sea spans
            ``duration · √scale``).
        rate: Model-scale sampling rate [Hz] (full scale ``rate / √scale``).
        hs, tp, heading_deg: Sea state at full scale ([m], [s], [deg]).
        scale: Froude scale λ = full-scale length / model length (> 0).
        robot: From :func:`offshore_crane.load_robot` (home height, limits).
        vessel, seed, kind, gamma, point, spreading, directions, highpass: As
            :func:`sea_state` (full-scale values: ``point`` [m], ``highpass`` [rad/s]).
        operation: Crane operation for q7..q9: waypoints ``[[t, q7, q8, q9], ...]``
            (model-scale time [s]) or an :class:`~offshore_crane.motion.operations.Operation`;
            None keeps the arm at zero.
        check: Check the record on its design grid against the workspace
            (:meth:`SeaMotion.check`).

    Returns:
        :class:`SeaMotion`.

    Raises:
        SeaStateError, TrajectoryError: bad arguments. SeaWorkspaceError: the record
        leaves the workspace (with the smallest scale that fits).
    """
    motion = _sea_motion(duration, rate, hs, tp, heading_deg, scale, robot, vessel=vessel,
                         seed=seed, kind=kind, gamma=gamma, point=point, spreading=spreading,
                         directions=directions, highpass=highpass, operation=operation)
    if check:
        motion.check(robot)
    return motion


def platform_trajectory(duration, rate, hs, tp, heading_deg, scale, robot, *,
                        vessel="supply", seed=0, kind: str = "jonswap", gamma=None,
                        point=(0.0, 0.0, 0.0), spreading=None,
                        directions: int = DEFAULT_DIRECTIONS, highpass=None, operation=None,
                        check: bool = True, name: str = "sea", threads: int = 1):
    """The model-scale record of :func:`sea_motion` as a
    :class:`~offshore_crane.motion.trajectories.Trajectory` ``(name, t, q, qd, qdd)``.

    ``t = trajectories.time_grid(duration, rate)``; ``q`` ``(N, 9)`` with analytic
    ``qd``, ``qdd`` (see :class:`SeaMotion`). Arguments as :func:`sea_motion`;
    ``threads`` share the FFT and the workspace check (the same record in any count).

    Raises:
        SeaStateError, TrajectoryError: bad arguments. SeaWorkspaceError: the record
        leaves the workspace; the message names the sample, the leg and the value, and
        the smallest scale at which the whole record fits (or that none does).
    """
    motion = _sea_motion(duration, rate, hs, tp, heading_deg, scale, robot, vessel=vessel,
                         seed=seed, kind=kind, gamma=gamma, point=point, spreading=spreading,
                         directions=directions, highpass=highpass, operation=operation)
    traj = motion.trajectory(name, threads)
    if check:
        motion.check(robot, traj, threads)
    return traj
