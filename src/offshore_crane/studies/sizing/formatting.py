"""Envelopes and verdicts as text tables for the terminal and reports."""

from __future__ import annotations

import math

import numpy as np

from offshore_crane.conventions import ACTUATOR_UNITS, ACTUATORS
from offshore_crane.studies.sizing.envelopes import (CAPACITIES, Envelope, KINDS, POSITION_UNITS,
                                                     SPEED_UNITS)
from offshore_crane.studies.sizing.verdicts import Verdict


# --------------------------------------------------------------------------- report
def _fmt(x: float, spec: str = ".4g") -> str:
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def _pct(x: float) -> str:
    return "—" if math.isnan(x) else f"{100 * x:.1f}"


def format_envelope(env: Envelope) -> str:
    """The envelope as a fixed-width table (one line per actuator the run has)."""
    lines = [f"{'actuator':<9}{'unit':<5}{'peak push':>11}{'at t [s]':>9}{'peak pull':>11}"
             f"{'at t [s]':>9}{'RMS':>10}{'peak speed':>12}{'peak |P| W':>12}"
             f"{'mean |P| W':>12}{'stroke used':>22}"]
    for k, name in enumerate(ACTUATORS):
        if not env.present[k]:
            continue
        stroke = f"{env.stroke_min[k]:.4g}..{env.stroke_max[k]:.4g} {POSITION_UNITS[k]}"
        lines.append(f"{name:<9}{ACTUATOR_UNITS[k]:<5}{env.peak_push[k]:>11.4g}"
                     f"{_fmt(env.t_push[k], '.2f'):>9}{env.peak_pull[k]:>11.4g}"
                     f"{_fmt(env.t_pull[k], '.2f'):>9}{env.rms[k]:>10.4g}"
                     f"{env.peak_speed[k]:>8.4g} {SPEED_UNITS[k]:<3}"
                     f"{env.peak_power[k]:>12.4g}{env.mean_abs_power[k]:>12.4g}"
                     f"{stroke:>22}")
    for kind in KINDS:
        if not math.isnan(env.kappa[kind]):
            lines.append(f"worst {kind} condition number: {env.kappa[kind]:.4g} at "
                         f"t = {env.t_kappa[kind]:.2f} s")
    if not math.isnan(env.sway_max):
        lines.append(f"hanging load: max sway {math.degrees(env.sway_max):.3g}° from the "
                     f"tip's vertical, cable tension {env.tension_min:.4g}.."
                     f"{env.tension_max:.4g} N (static {env.static_tension:.4g} N)")
    return "\n".join(lines)


def format_verdict(v: Verdict, present) -> str:
    """The utilisation table of a verdict, in percent ('—': no capacity given)."""
    lines = [f"utilisation [%]: {v.describe()}",
             f"{'actuator':<9}" + "".join(f"{c:>9}" for c in CAPACITIES) + f"{'worst':>9}"
             + "  judged: value / capacity"]
    for k, name in enumerate(ACTUATORS):
        if not present[k]:
            continue
        u = v.utilisation[k]
        worst = math.nan if np.isnan(u).all() else float(np.nanmax(u))
        flag = "  EXCEEDED" if worst > 1.0 else ""
        lines.append(f"{name:<9}" + "".join(f"{_pct(x):>9}" for x in u)
                     + f"{_pct(worst):>9}" + _judged(v, k, u) + flag)
    if v.load is not None:
        lines += format_load(v.load)
    worst, who, cap = v.worst()
    if who is None:
        lines.append("no capacity is given for these actuators: nothing to judge")
    else:
        lines.append(f"worst: {who} {cap} at {100 * worst:.1f} % "
                     f"({'EXCEEDS its capacity' if worst > 1.0 else 'within capacity'})")
    if v.load is not None and v.load.exceeded:
        over = [k for k, x in v.load.utilisation.items() if x > 1.0]
        lines.append(f"the hanging load EXCEEDS its limits: {', '.join(over)}")
    return "\n".join(lines)


#: Units of each capacity column, per actuator kind (arm joints 0-1 revolute, the rest
#: prismatic).
_UNITS = {"push": ACTUATOR_UNITS, "pull": ACTUATOR_UNITS, "speed": SPEED_UNITS,
          "power": ("W",) * 9, "stroke": POSITION_UNITS}


def _judged(v: Verdict, k: int, u) -> str:
    """The worst column's value beside its capacity (``speed 0.43 / 0.46 m/s``)."""
    if v.limits is None or np.isnan(u).all():
        return ""
    c = CAPACITIES[int(np.nanargmax(u))]
    return (f"  {c} {v.peaks[c][k]:.3g} / {v.limits[c][k]:.3g} "
            f"{_UNITS[c][k]}")


def format_load(load) -> list[str]:
    """The hanging load's verdict lines: each value beside the limit it is judged against
    (angles in degrees)."""
    lim, u = load.limits, load.utilisation

    def judged(key: str, limit_text: str) -> str:
        x = u[key]
        if math.isnan(x):
            return "no limit given"
        verdict = "EXCEEDED" if x > 1.0 else "within"
        return f"limit {limit_text}: {_pct(x)} % {verdict}"

    sway_limit = "—" if math.isinf(lim.sway_max) else f"{math.degrees(lim.sway_max):.3g}°"
    ratio_limit = ("—" if math.isnan(lim.tension_ratio_min)
                   else f"≥ {lim.tension_ratio_min:.3g}")
    t_limit = "—" if math.isinf(lim.tension_max) else f"{lim.tension_max:.4g} N"
    return ["hanging load (on the same basis as the utilisation above):",
            f"  sway max {math.degrees(load.sway):.3g}° (largest observed "
            f"{math.degrees(load.observed['sway']):.3g}°); {judged('sway', sway_limit)}",
            f"  tension min {load.tension_min:.4g} N = {load.ratio_min:.3g} × static "
            f"{load.static:.4g} N (smallest observed {load.observed['tension_min']:.4g} N); "
            f"{judged('slack', ratio_limit)}",
            f"  tension max {load.tension_max:.4g} N (largest observed "
            f"{load.observed['tension_max']:.4g} N); {judged('tension', t_limit)}"] + [
            f"  winch {key} {value:.4g} {unit} (largest observed "
            f"{load.observed['winch ' + key]:.4g} {unit}); "
            f"{judged('winch ' + key, f'{cap:.4g} {unit}')}"
            for (key, unit), value, cap in zip(
                (("pull", "N"), ("speed", "m/s"), ("acceleration", "m/s²"), ("power", "W")),
                load.winch.values(), _winch_caps(load))]


def _winch_caps(load) -> list:
    """The winch's capacities in the order of its verdict's demands."""
    if not load.winch:
        return []
    return [load.winch_capacities.pull_max, load.winch_capacities.speed_max,
            load.winch_capacities.acceleration_max, load.winch_capacities.power_max]
