"""The hanging load's criteria: sway, the slack criterion, the largest tension and the
winch's demands against ``payload.limits`` and ``actuators.winch`` — one definition for
a run's envelope (a sweep's row), a case's verdict over seeds (``size``) and a sweep's
verdict table (the "no slack" operability diagram).

Utilisations (1 = at the limit, NaN = no limit given):

- ``sway = sway_max / limits.sway_max``, ``tension = T_max / limits.tension_max``,
  ``winch {k} = demand / capacity`` for the pull [N], speed [m/s], acceleration [m/s²]
  and power [W] — peaks, so the Gumbel fit's most probable maximum of a utilisation is
  that of the peak over the limit (location-scale equivariance);
- ``slack = limits.tension_ratio_min / (T_min / (m |g|))``: 1 when the smallest tension
  reaches the criterion's fraction of the static tension, inf when the cable goes slack
  (``T_min ≤ 0``). It is not linear in ``T_min``: over seeds it is taken of the most
  probable *minimum* of the tension ratio (the Gumbel fit of its negation).
"""

from __future__ import annotations

import math

import numpy as np

#: The winch's demands judged, in order (capacities ``actuators.winch.{k}_max``).
WINCH_DEMANDS = ("pull", "speed", "acceleration", "power")
#: The load criteria's utilisation names, in order.
LOAD_CRITERIA = ("sway", "slack", "tension", *(f"winch {k}" for k in WINCH_DEMANDS))


def util_column(criterion: str) -> str:
    """The row column of a load criterion's utilisation: ``sway_util``, ``slack_util``,
    ``tension_util``, ``winch_util_{demand}`` (as an actuator's ``{name}_util_{capacity}``)."""
    return (f"winch_util_{criterion.split()[1]}" if criterion.startswith("winch ")
            else f"{criterion}_util")


#: The hanging load's columns of a row (:meth:`Envelope.row`), all float: the sway [rad],
#: the tension range [N] and over ``m |g|`` [-], the time slack [s], the slack criterion's
#: fraction [-], the winch's peaks, and the utilisations (``load_util`` their worst).
LIFT = ("sway_max", "tension_min", "tension_max", "tension_ratio_min", "tension_ratio_max",
        "time_slack_s", "tension_ratio_limit", *(f"winch_{k}" for k in WINCH_DEMANDS),
        *(util_column(c) for c in LOAD_CRITERIA), "load_util")


def utilisation(value, capacity):
    """``value / capacity``: NaN where the capacity is infinite (not given); a zero
    capacity is a real limit, not a missing one: 1 (no headroom) for a zero demand, inf
    for any demand."""
    value = np.asarray(value, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = value / capacity
    out = np.where((capacity == 0) & (value == 0), 1.0, out)
    return np.where(np.isinf(capacity), np.nan, out)


def slack_utilisation(limit: float, ratio: float) -> float:
    """The slack criterion's utilisation ``limit / ratio`` of a smallest tension ratio
    ``ratio = T_min / (m |g|)`` [-] against the fraction ``limit`` [-] (NaN: no limit;
    inf: the cable went slack, ``ratio ≤ 0``)."""
    if math.isnan(limit):
        return math.nan
    return math.inf if not ratio > 0 else limit / ratio


def winch_capacities(caps) -> dict:
    """``{demand: capacity}`` of a :class:`~offshore_crane.robot.description.WinchCapacities`
    (inf: not given)."""
    return {k: float(getattr(caps, f"{k}_max")) for k in WINCH_DEMANDS}


def load_utilisation(sway: float, ratio_min: float, tension_max: float, limits,
                     winch: dict | None = None, capacities=None) -> dict:
    """``{criterion: utilisation}`` over :data:`LOAD_CRITERIA` (the winch's only with a
    winch).

    Args:
        sway: Largest sway angle [rad]. ratio_min: Smallest tension over ``m |g|`` [-].
        tension_max: Largest tension [N].
        limits: :class:`~offshore_crane.robot.description.LoadLimits`.
        winch: ``{demand: peak}`` over :data:`WINCH_DEMANDS` [N, m/s, m/s², W], or None.
        capacities: The :class:`WinchCapacities` (with ``winch``).
    """
    def ratio(value, limit):
        return float(utilisation(np.array([value]), np.array([limit]))[0])

    out = {"sway": ratio(sway, limits.sway_max),
           "slack": slack_utilisation(limits.tension_ratio_min, ratio_min),
           "tension": ratio(tension_max, limits.tension_max)}
    if winch:
        caps = winch_capacities(capacities)
        out.update({f"winch {k}": ratio(winch[k], caps[k]) for k in WINCH_DEMANDS})
    return out


def worst_load(util: dict) -> tuple[float, str]:
    """``(utilisation, criterion)`` of the largest of ``util`` (NaN, "" when none is
    judged)."""
    judged = {k: u for k, u in util.items() if not math.isnan(u)}
    if not judged:
        return math.nan, ""
    key = max(judged, key=judged.get)
    return judged[key], key


def load_row(env) -> dict:
    """The :data:`LIFT` columns of an :class:`~.envelopes.Envelope` (NaN without a
    cable; the winch's without a winch)."""
    row = dict.fromkeys(LIFT, math.nan)
    if math.isnan(env.sway_max):
        return row
    static = env.static_tension
    row.update(sway_max=env.sway_max, tension_min=env.tension_min,
               tension_max=env.tension_max, time_slack_s=env.time_slack,
               tension_ratio_min=env.tension_min / static if static > 0 else math.nan,
               tension_ratio_max=env.tension_max / static if static > 0 else math.nan)
    row.update({f"winch_{k}": v for k, v in env.winch.items()})
    if env.load_limits is None:
        return row
    row["tension_ratio_limit"] = env.load_limits.tension_ratio_min
    util = load_utilisation(env.sway_max, row["tension_ratio_min"], env.tension_max,
                            env.load_limits, env.winch, env.winch_capacities)
    row.update({util_column(k): u for k, u in util.items()})
    row["load_util"] = worst_load(util)[0]
    return {k: float(v) for k, v in row.items()}
