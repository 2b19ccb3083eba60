"""The hanging load's modes, linearised about the static hang: what a record must spin up
for and what lightly damped resonances a scene has (:func:`cable_modes`)."""

from __future__ import annotations

import math


def cable_modes(robot, gravity: float, length: float | None = None, ea: float | None = None,
                damping: float = 0.0) -> list[tuple[str, float, float]]:
    """``[(name, ω [rad/s], ζ [-]), ...]`` of the payload on its cable, small motions about
    hanging still below a still tip:

    - ``"sway"``: the pendulum, ``ω = √(g / L)``, ``ζ = c / (2 m L² ω)`` with ``c`` the
      sway joints' damping [N·m·s/rad] (``payload.sway_damping``, from the URDF);
    - ``"axial"`` (an elastic cable of stiffness ``ea``): the payload on the spring
      ``k = EA / L``, ``ω = √(k / m)``, ``ζ = c_a / (2 √(k m))`` with ``c_a`` the cable's
      axial damping [N·s/m].

    Args:
        robot: With a payload on a cable (its mass [kg] and length [m] from the URDF).
        gravity: ``|g|`` [m/s²].
        length: The cable's length [m] (default the description's).
        ea: The elastic cable's EA [N], or None for an inextensible one.
        damping: The elastic cable's axial damping [N·s/m].
    """
    m = float(robot.hybrid.cable.mass[-1])
    L = float(robot.hybrid.cable_length if length is None else length)
    c = float(robot.hybrid.sway_damping[0])
    omega = math.sqrt(gravity / L)
    modes = [("sway", omega, c / (2.0 * m * L * L * omega))]
    if ea is not None:
        k = float(ea) / L
        modes.append(("axial", math.sqrt(k / m), float(damping) / (2.0 * math.sqrt(k * m))))
    return modes
