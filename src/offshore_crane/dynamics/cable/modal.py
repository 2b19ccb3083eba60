"""The hanging load's modes: natural frequencies and damping ratios of the payload on its
cable, linearised about the static hang (docs/cable.md, "Damping and modes").

The tip is held still (the robot's motion is what drives these modes, not part of them)
and gravity ``g`` acts; the payload of mass m hangs on a cable of unstretched length L:

- **sway** (two modes, φ1 about the tip's x, φ2 about its y): a pendulum of length ``ℓ``
  (``L`` on a rigid cable; the static length ``L (1 + m g / EA)`` on an elastic one),
  ``ω = √(g / ℓ)``, damped by ``payload.sway_damping`` ``c_r`` [N·m·s/rad] of each angle:
  ``ζ_r = c_r / (2 m ℓ² ω)``;
- **axial** (elastic cable only): the payload on the spring ``EA / L``,
  ``ω = √(EA / (m L))``, damped by the cable's axial damping c [N·s/m]:
  ``ζ = c / (2 √(m EA / L))``.

The air's quadratic drag ``½ ρ C_d A |v| v`` has no linear part about rest: it adds no
damping to the linearised modes. Given a motion ``amplitude`` X [m] of the payload, its
equivalent linear damping (equal energy taken per cycle, ``∮ k |v|³ dt = c_eq π ω X²``
for ``v = X ω cos ωt``) is ``c_eq = 8 k ω X / (3 π)``, ``k = ½ ρ C_d A``, which adds
``ζ = 4 k X / (3 π m)`` to every mode.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError
from offshore_crane.validation import as_gravity


@dataclass(frozen=True)
class Mode:
    """One mode of the hanging load.

    Attributes:
        name: ``"sway phi1"``, ``"sway phi2"`` or ``"axial"``.
        omega: Undamped natural frequency ω [rad/s].
        zeta: Damping ratio ζ [-] (0: undamped; 1: critical).
    """

    name: str
    omega: float
    zeta: float

    @property
    def period(self) -> float:
        """The undamped period ``2π / ω`` [s]."""
        return 2.0 * math.pi / self.omega

    @property
    def damped_omega(self) -> float:
        """``ω √(1 − ζ²)`` [rad/s], the free oscillation's frequency (0 from ζ = 1 on)."""
        return self.omega * math.sqrt(max(0.0, 1.0 - self.zeta ** 2))

    @property
    def decay_time(self) -> float:
        """``1 / (ζ ω)`` [s]: the free oscillation's amplitude falls by e in it (inf
        undamped)."""
        return math.inf if self.zeta == 0.0 else 1.0 / (self.zeta * self.omega)

    def describe(self) -> str:
        """``sway phi1: ω 3.13 rad/s, ζ 2 %, decay time 16 s``."""
        tau = self.decay_time
        return (f"{self.name}: ω {self.omega:.3g} rad/s, ζ {100 * self.zeta:.2g} %, decay "
                f"time {'∞' if math.isinf(tau) else f'{tau:.3g} s'}")

    @property
    def log_decrement(self) -> float:
        """``ln`` of the ratio of two successive peaks of the free oscillation,
        ``2π ζ / √(1 − ζ²)`` [-] (inf from ζ = 1 on: no second peak)."""
        return (math.inf if self.zeta >= 1.0 else
                2.0 * math.pi * self.zeta / math.sqrt(1.0 - self.zeta ** 2))


def _positive(value, name: str, unit: str, allow_zero: bool = False) -> float:
    ok = (isinstance(value, (int, float, np.floating)) and not isinstance(value, bool)
          and math.isfinite(value) and (value >= 0 if allow_zero else value > 0))
    if not ok:
        raise InputError(f"{name} = {value!r} {unit}: give a finite number "
                         f"{'>= 0' if allow_zero else '> 0'}", name=name)
    return float(value)


def modes(robot, *, ea: float | None = None, damping: float = 0.0,
          length: float | None = None, amplitude: float = 0.0,
          gravity=GRAVITY) -> tuple[Mode, ...]:
    """The payload's modes on its cable, linearised about the static hang under a still
    tip (module docstring).

    Args:
        robot: With a payload on a cable (``payload.mass``, ``payload.cable_length``,
            ``payload.sway_damping``, ``payload.drag_area``, ``payload.air_density``).
        ea: The cable's axial stiffness EA [N] (a scene's ``[cable] ea``); None: a rigid
            cable (no axial mode).
        damping: The cable's axial damping [N·s/m] (``[cable] damping``), with ``ea``.
        length: The cable's unstretched length L [m] (e.g. a winch's); None: the
            description's ``payload.cable_length``.
        amplitude: The payload's motion amplitude X [m] at which the air's drag is
            counted (its equivalent linear damping); 0: not counted (the linearisation).
        gravity: ``(3,)`` [m/s²], base frame.

    Returns:
        ``(sway phi1, sway phi2)`` or, with ``ea``, ``(sway phi1, sway phi2, axial)``
        :class:`Mode` s.

    Raises:
        InputError: a value out of range (``ea``, ``length`` ≤ 0, a negative damping or
            amplitude, no gravity, ``damping`` without ``ea``).
        ModelError: a robot without a cable.
    """
    from offshore_crane.dynamics.cable.grid import cable_robot

    robot = cable_robot(robot)
    m = float(robot.hybrid.cable.mass[-1])
    L = (float(robot.hybrid.cable_length) if length is None
         else _positive(length, "length", "m"))
    damping = _positive(damping, "damping", "N·s/m", allow_zero=True)
    amplitude = _positive(amplitude, "amplitude", "m", allow_zero=True)
    g = float(np.linalg.norm(as_gravity(gravity)))
    if not g > 0.0:
        raise InputError("gravity is zero: the payload has no static hang and no "
                         "pendulum mode", name="gravity")
    if ea is None and damping:
        raise InputError(f"damping = {damping:g} N·s/m is the elastic cable's axial "
                         "damping: give ea too", name="damping")
    extra = 4.0 * float(robot.hybrid.drag) * amplitude / (3.0 * math.pi * m)
    ell = L if ea is None else L * (1.0 + m * g / _positive(ea, "ea", "N"))
    w = math.sqrt(g / ell)
    out = [Mode(f"sway {name}", w, float(c) / (2.0 * m * ell ** 2 * w) + extra)
           for name, c in zip(("phi1", "phi2"), robot.hybrid.sway_damping)]
    if ea is not None:
        k = float(ea) / L
        out.append(Mode("axial", math.sqrt(k / m), damping / (2.0 * math.sqrt(k * m))
                        + extra))
    return tuple(out)
