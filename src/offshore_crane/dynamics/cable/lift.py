"""What decides a lift: the cable's tension against its static value (slack criterion,
snap loads), the time slack, and the winch's demand against its capacities."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class LiftMetrics:
    """One run's lift figures (:func:`lift_metrics`).

    Attributes:
        static_tension: ``m |g|`` [N].
        tension_min, tension_max: [N] (the largest refined between samples for an
            elastic cable: the snap's peak).
        ratio_min, ratio_max: the same over ``m |g|`` (the slack criterion reads
            ``ratio_min``, the snap load ``ratio_max``).
        time_slack: Time with the cable slack [s] (a sample's state held over its
            interval).
        winch_pull, winch_speed, winch_acceleration, winch_power: The winch's largest
            line pull [N], |L̇| [m/s], |L̈| [m/s²], |Fw L̇| [W]; NaN without a winch.
    """

    static_tension: float
    tension_min: float
    tension_max: float
    ratio_min: float
    ratio_max: float
    time_slack: float
    winch_pull: float = math.nan
    winch_speed: float = math.nan
    winch_acceleration: float = math.nan
    winch_power: float = math.nan

    def winch_utilisation(self, capacities) -> dict:
        """``{name: demand / capacity}`` of the winch's pull, speed, acceleration and
        power against a :class:`~offshore_crane.robot.description.WinchCapacities` (NaN
        where not given or without a winch)."""
        pairs = (("pull", self.winch_pull, capacities.pull_max),
                 ("speed", self.winch_speed, capacities.speed_max),
                 ("acceleration", self.winch_acceleration, capacities.acceleration_max),
                 ("power", self.winch_power, capacities.power_max))
        return {name: (demand / cap if math.isfinite(cap) else math.nan)
                for name, demand, cap in pairs}


def time_slack(t: np.ndarray, tension: np.ndarray) -> float:
    """Time [s] a cable of ``tension (N,)`` [N] at times ``t (N,)`` spent slack (not
    pulling): the intervals whose first sample is slack (its state held over them)."""
    t, tension = np.asarray(t), np.asarray(tension)
    if len(t) < 2:
        return 0.0
    return float(np.diff(t)[~(tension[:-1] > 0.0)].sum())


def lift_metrics(res, gravity=(0.0, 0.0, -9.81)) -> LiftMetrics:
    """The lift figures of a :class:`~.result.CableResult` or
    :class:`~.elastic.ElasticResult` (tension and slack while the load is off a deck,
    the winch throughout).

    Args:
        gravity: ``(3,)`` [m/s²] for the static tension of a rigid cable's result (an
            elastic result carries its own).
    """
    air = slice(*getattr(res, "airborne", (0, None)))    # judged while off the deck
    T, t = np.asarray(res.tension)[air], np.asarray(res.t)[air]
    static = getattr(res, "static_tension", None)
    if static is None:
        static = res.mass * float(np.linalg.norm(gravity))
    slack_time = time_slack(t, T)
    peak = res.peak_tension() if hasattr(res, "peak_tension") else float(T.max())
    winch = {}
    if res.hoist is not None:
        H, Tw = np.asarray(res.hoist), np.asarray(res.tension)   # the winch: throughout
        winch = dict(winch_pull=float(Tw.max()), winch_speed=float(np.abs(H[:, 1]).max()),
                     winch_acceleration=float(np.abs(H[:, 2]).max()),
                     winch_power=float(np.abs(Tw * H[:, 1]).max()))
    return LiftMetrics(static, float(T.min()), peak, float(T.min()) / static,
                       peak / static, slack_time, **winch)
