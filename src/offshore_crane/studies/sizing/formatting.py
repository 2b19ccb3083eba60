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
        lines.append(f"hanging load: max sway {env.sway_max:.4g} rad from the tip's "
                     f"vertical, cable tension {env.tension_min:.4g}..{env.tension_max:.4g} N")
    return "\n".join(lines)


def format_verdict(v: Verdict, present) -> str:
    """The utilisation table of a verdict, in percent ('—': no capacity given)."""
    lines = [f"utilisation [%]: {v.describe()}",
             f"{'actuator':<9}" + "".join(f"{c:>9}" for c in CAPACITIES) + f"{'worst':>9}"]
    for k, name in enumerate(ACTUATORS):
        if not present[k]:
            continue
        u = v.utilisation[k]
        worst = math.nan if np.isnan(u).all() else float(np.nanmax(u))
        flag = "  EXCEEDED" if worst > 1.0 else ""
        lines.append(f"{name:<9}" + "".join(f"{_pct(x):>9}" for x in u)
                     + f"{_pct(worst):>9}{flag}")
    worst, who, cap = v.worst()
    if who is None:
        lines.append("no capacity is given for these actuators: nothing to judge")
    else:
        lines.append(f"worst: {who} {cap} at {100 * worst:.1f} % "
                     f"({'EXCEEDS its capacity' if worst > 1.0 else 'within capacity'})")
    return "\n".join(lines)
