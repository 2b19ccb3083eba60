"""Crane operations: smooth point-to-point motions of the arm joints q7, q8, q9.

An operation is a list of waypoints ``[[t, q7, q8, q9], ...]`` (times [s] strictly
increasing; q7, q8 [rad], q9 [m]; ``docs/conventions.md``). Between consecutive
waypoints the joints move *rest to rest* along the quintic blend

    q(t) = q_k + (q_{k+1} - q_k) b(s),   b(s) = 10 s^3 - 15 s^4 + 6 s^5,
    s = (t - t_k) / (t_{k+1} - t_k) in [0, 1],

whose velocity and acceleration vanish at both ends, so that position, velocity and
acceleration are continuous everywhere (the jerk jumps at the waypoints). The
derivatives are analytic: ``qd = Δq b'(s) / T``, ``qdd = Δq b''(s) / T²`` with
``T = t_{k+1} - t_k``, ``b' = 30 s² - 60 s³ + 30 s⁴``, ``b'' = 60 s - 180 s² + 120 s³``.
Equal consecutive positions are a dwell (the joint rests). Before the first waypoint the
arm rests at the first position, after the last at the last one (at rest, so the
derivatives stay continuous). The peak speed of a move is ``1.875 |Δq| / T`` (at
``s = 1/2``) and the peak acceleration ``(10/√3) |Δq| / T²`` (at ``s = 1/2 ∓ √3/6``).

Joint limits: ``b`` is monotonic on [0, 1], so each move stays between its two waypoints;
the whole operation is therefore inside the robot's limits
(``robot.hybrid.arm.lower``/``.upper``, from the URDF) if and only if every waypoint is.
That is what :meth:`Operation.check` verifies, exactly.

Times are those of the robot (model scale), the same axis as the trajectory the
operation is combined with (:func:`offshore_crane.motion.sea.platform_trajectory`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import ARM_JOINTS
from offshore_crane.errors import SeaStateError
from offshore_crane.validation import as_real

__all__ = ["Operation", "operation"]

#: Units of q7, q8, q9, for messages.
_UNITS = ("rad", "rad", "m")


def as_times(t) -> tuple[np.ndarray, bool]:
    """Times for a motion source evaluated at any times: ``(t (N,) [s] float64, whether t
    was a scalar)``.

    Raises:
        SeaStateError: t is not numeric, has more than one axis or holds a non-finite
            value (naming the sample).
    """
    arr = as_real("t", t, SeaStateError, "s")
    if arr.ndim > 1:
        raise SeaStateError(f"t must be a scalar or a 1-D array of times [s], got shape "
                            f"{arr.shape}", name="t")
    scalar = arr.ndim == 0
    arr = np.atleast_1d(arr)
    bad = ~np.isfinite(arr)
    if bad.any():
        k = int(np.argmax(bad))
        raise SeaStateError(f"t[{k}] = {float(arr[k])!r} is not finite: give finite times "
                            "[s]", name="t", index=k)
    return arr, scalar


@dataclass(frozen=True, eq=False)
class Operation:
    """A crane operation: quintic rest-to-rest moves of q7..q9 through waypoints.

    Build it with :meth:`from_waypoints`; call it like a trajectory source:
    ``q, qd, qdd = op(t)``.

    Attributes:
        times: ``(K,)`` waypoint times [s], strictly increasing.
        positions: ``(K, 3)`` q7 [rad], q8 [rad], q9 [m] at the waypoints (any ``(K, m)``
            columns blend alike: a winch's cable length is one).
    """

    times: np.ndarray
    positions: np.ndarray

    @classmethod
    def from_waypoints(cls, waypoints, robot=None) -> "Operation":
        """Validate ``[[t, q7, q8, q9], ...]`` and build the operation.

        Args:
            waypoints: ``(K, 4)`` rows ``t [s], q7 [rad], q8 [rad], q9 [m]``, K >= 1,
                times strictly increasing.
            robot: Optional robot from :func:`offshore_crane.load_robot`: every waypoint
                must then lie inside its arm joint limits (see :meth:`check`).

        Raises:
            SeaStateError: not a (K, 4) array of finite numbers, times not increasing,
                or a waypoint outside the limits (``index`` is the waypoint's row).
        """
        try:
            w = np.array(waypoints, dtype=float)
        except (TypeError, ValueError):
            raise SeaStateError(
                f"waypoints must be rows [t, q7, q8, q9] of numbers, got {waypoints!r}",
                name="waypoints") from None
        if w.ndim == 1 and w.size == 4:
            w = w[None, :]
        if w.ndim != 2 or w.shape[1] != 4 or w.shape[0] == 0:
            raise SeaStateError(
                f"waypoints must have shape (K, 4) with rows [t, q7, q8, q9], K >= 1; got "
                f"shape {w.shape}", name="waypoints")
        bad = ~np.isfinite(w)
        if bad.any():
            k, j = (int(x) for x in np.argwhere(bad)[0])
            raise SeaStateError(
                f"waypoint {k}: {('t', 'q7', 'q8', 'q9')[j]} = {float(w[k, j])!r} is not finite",
                name="waypoints", index=k)
        dt = np.diff(w[:, 0])
        if (dt <= 0.0).any():
            k = int(np.argmax(dt <= 0.0)) + 1
            raise SeaStateError(
                f"waypoint {k}: time {float(w[k, 0])!r} s does not increase after "
                f"{float(w[k - 1, 0])!r} s: give waypoints in increasing time (a dwell is "
                "two waypoints with equal positions)", name="waypoints", index=k)
        op = cls(np.ascontiguousarray(w[:, 0]), np.ascontiguousarray(w[:, 1:]))
        if robot is not None:
            op.check(robot)
        return op

    def check(self, robot) -> None:
        """Raise :class:`SeaStateError` unless every waypoint is inside the arm's limits.

        Exact for the whole operation: the quintic blend is monotonic between waypoints
        (module docstring). A robot without arm accepts only the all-zero operation.
        """
        arm = robot.hybrid.arm
        if arm.n == 0:
            if np.any(self.positions != 0.0):
                raise SeaStateError(
                    "the robot has no arm (with_arm = 0): an operation must keep q7..q9 at "
                    "zero", name="waypoints")
            return
        lower, upper = np.asarray(arm.lower, float), np.asarray(arm.upper, float)
        outside = (self.positions < lower) | (self.positions > upper)
        if outside.any():
            k, j = (int(x) for x in np.argwhere(outside)[0])
            raise SeaStateError(
                f"waypoint {k}: q{j + 7} ({ARM_JOINTS[j]}) = {self.positions[k, j]:.6g} "
                f"{_UNITS[j]} is outside the joint's limits [{lower[j]:.6g}, "
                f"{upper[j]:.6g}] {_UNITS[j]}: move the waypoint inside them",
                name="waypoints", index=k)

    def __call__(self, t):
        """Positions, velocities, accelerations at times ``t`` (any order, any spacing).

        Args:
            t: Time [s], scalar or ``(n,)``.

        Returns:
            ``(q, qd, qdd)``, each ``(n, 3)`` (``(3,)`` for a scalar ``t``): q7, q8 [rad],
            q9 [m] and their rates [rad/s, m/s] and accelerations [rad/s², m/s²]
            (``(n, m)`` for ``m`` columns of positions).

        Raises:
            SeaStateError: ``t`` not numeric, not 1-D, or not finite.
        """
        t, scalar = as_times(t)
        T, P = self.times, self.positions
        n, m = t.shape[0], P.shape[1]
        q = np.empty((n, m))
        qd = np.zeros((n, m))
        qdd = np.zeros((n, m))
        k = np.searchsorted(T, t, side="right") - 1          # segment index, -1 before
        before, after = k < 0, k >= len(T) - 1
        q[before] = P[0]
        q[after] = P[-1]
        inside = ~(before | after)
        if inside.any():
            ki = k[inside]
            span = T[ki + 1] - T[ki]
            s = ((t[inside] - T[ki]) / span)[:, None]
            dq = P[ki + 1] - P[ki]
            s2 = s * s
            b = s2 * s * (10.0 + s * (-15.0 + 6.0 * s))
            b1 = s2 * (30.0 + s * (-60.0 + 30.0 * s))
            b2 = s * (60.0 + s * (-180.0 + 120.0 * s))
            q[inside] = P[ki] + dq * b
            qd[inside] = dq * b1 / span[:, None]
            qdd[inside] = dq * b2 / (span * span)[:, None]
        if scalar:
            return q[0], qd[0], qdd[0]
        return q, qd, qdd


def operation(t, waypoints, robot=None):
    """q7..q9 of a crane operation at times ``t``: ``Operation.from_waypoints(...)(t)``.

    Args:
        t: Time [s], scalar or ``(n,)``, any order.
        waypoints: ``(K, 4)`` rows ``[t, q7, q8, q9]`` ([s], [rad], [rad], [m]).
        robot: Optional: check the waypoints against its arm joint limits.

    Returns:
        ``(q, qd, qdd)``, each ``(n, 3)`` ([rad, rad, m] and rates, accelerations).

    Raises:
        SeaStateError: bad waypoints, a waypoint outside the limits, bad ``t``.
    """
    return Operation.from_waypoints(waypoints, robot)(t)
