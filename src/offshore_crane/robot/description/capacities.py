"""The actuators' capacities, the winch's and the hanging load's limits of a robot
description (``actuators.*``, ``payload.limits.*``), read and checked.

Each reader takes ``get(name, default)`` (the description's resolved number),
``has(name)`` (given in the file or the overrides) and ``fail(name, problem)`` (raises
the description's error naming the field).
"""

from __future__ import annotations

import math

import numpy as np

from offshore_crane.robot.description.results import Capacities, LoadLimits, WinchCapacities
from offshore_crane.robot.description.schema import ACTUATOR, ACTUATORS


def capacities(has, get, fail) -> Capacities:
    """The actuators' :class:`Capacities` (``actuators.<name>`` or the group's
    ``actuators.Fl``), each checked."""
    cols = {k: [] for k in ACTUATOR}
    for name in ACTUATORS:
        group = "Fl" if name.startswith("Fl") else name
        for key in ACTUATOR:
            own, common = f"actuators.{name}.{key}", f"actuators.{group}.{key}"
            field_ = own if has(own) else common
            x = get(field_, math.inf)
            positive = key in ("speed_max", "power_max")
            if x < 0.0 or (positive and x == 0.0):
                fail(field_, f"{x:g} must be {'> 0' if positive else '>= 0'}")
            cols[key].append(x)
    return Capacities(ACTUATORS, *(np.array(cols[k]) for k in ACTUATOR))

def winch_capacities(get, fail) -> WinchCapacities:
    """``actuators.winch``: each given capacity > 0, a given reflected mass finite and
    ≥ 0."""
    mass = get("actuators.winch.reflected_mass", 0.0)
    if not (math.isfinite(mass) and mass >= 0.0):
        fail("actuators.winch.reflected_mass", f"{mass:g} kg must be finite and >= 0 (0: an "
             "ideal winch whose length follows its profile)")
    values = {"reflected_mass": mass}
    for key in WinchCapacities.__dataclass_fields__:
        if key == "reflected_mass":
            continue
        name = f"actuators.winch.{key}"
        x = get(name, math.inf)
        if not x > 0.0:
            fail(name, f"{x:g} must be > 0")
        values[key] = x
    return WinchCapacities(**values)

def load_limits(get, fail) -> LoadLimits:
    """``payload.limits``: each given value checked (a sway angle in (0, 90]°, a
    tension ratio in [0, 1), a tension > 0)."""
    pre = "payload.limits"
    sway = get(f"{pre}.sway_max_deg", math.inf)
    if not (0.0 < sway <= 90.0 or sway == math.inf):
        fail(f"{pre}.sway_max_deg", f"{sway:g}° must be in (0, 90]")
    ratio = get(f"{pre}.tension_ratio_min", math.nan)
    if not (math.isnan(ratio) or 0.0 <= ratio < 1.0):
        fail(f"{pre}.tension_ratio_min", f"{ratio:g} must be in [0, 1) (a fraction "
                  "of the static tension m·g, e.g. 0.1)")
    tension = get(f"{pre}.tension_max", math.inf)
    if not tension > 0.0:
        fail(f"{pre}.tension_max", f"{tension:g} N must be > 0")
    return LoadLimits(math.radians(sway) if sway != math.inf else math.inf, ratio,
                      tension)
