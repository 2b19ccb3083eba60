"""The records a sea scene's extremes are judged on: stationary, as long as the exposure.

A random sea's extreme over an exposure (3 hours full scale by default) is a statistic of
a *stationary* process. A run started from rest is not stationary until its slowest mode
has forgotten the start, and a record shorter than the exposure says little about the
exposure's extreme (docs/sizing.md, "Extremes"). So ``size``, a sweep's cases and
``compensate`` run each seed of a sea scene as an **exposure record**
(:func:`exposure_plan`):

- **modes** (:func:`scene_modes`): the scene's dynamic modes with their natural frequency
  ω [rad/s] and damping ratio ζ [-], linearised about the static hang — the hanging
  load's pendulum (sway), an elastic cable's axial mode, a computed-torque law's tracking
  error; a prescribed rigid robot has none (its forces follow the sea's motion at once);
- **spin-up**: :data:`SPIN_UP_DECAYS` decay times ``1/(ζ ω)`` of the slowest damped mode
  (a transient then keeps ``e⁻⁵ < 1 %`` of its start), rounded up to whole cycles of the
  scene, run and discarded;
- **cycle**: the scene's own duration is one cycle of its ``[operation]``; the record
  repeats the operation cycle after cycle (a closed operation: it ends where it starts)
  under one continuous sea;
- **judged window**: the exposure at model scale, ``exposure / √λ`` (Froude), after the
  spin-up (and a compensation's measurement delay).

A mode with ζ below :data:`LIGHT_DAMPING` draws a :class:`LightlyDampedWarning`: its
decay time is many periods, and where ζ = 0 no record is stationary (its extremes grow
with the record's length). A scene may instead be judged on its own record (``[extremes]
record = "scene"``): observed extremes only, with a :class:`ShortRecordWarning` when that
record is shorter than :data:`SPIN_UP_DECAYS` decay times.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

from offshore_crane.errors import SceneError
from offshore_crane.robot.kinematics.workspace import OffshoreCraneWarning
from offshore_crane.scenes.keys import EXTREMES_DEFAULTS, SEA_DURATION
from offshore_crane.scenes.scene import Scene

#: Decay times of the slowest mode a record spins up for (and a scene's own record should
#: last): a transient keeps ``e⁻⁵ = 0.67 %`` of its amplitude after them.
SPIN_UP_DECAYS = 5.0
#: Damping ratio below which a mode is lightly damped [-]: its decay time ``1/(ζ ω)``
#: exceeds 100/(2π) ≈ 16 of its periods, so a record's extreme depends on the record's
#: length and start far more than on the sea (the issue's threshold, offshore practice's
#: "lightly damped" resonance).
LIGHT_DAMPING = 0.01


class LightlyDampedWarning(OffshoreCraneWarning):
    """A mode of the scene is damped below :data:`LIGHT_DAMPING`: its extremes depend on
    the record's length (and grow without bound where ζ = 0)."""


class ShortRecordWarning(OffshoreCraneWarning):
    """A scene judged on its own record, shorter than :data:`SPIN_UP_DECAYS` decay times
    of its slowest mode: the record's extremes depend on its length and start."""


def scene_modes(scene: Scene, robot) -> tuple:
    """The scene's dynamic modes (:class:`~offshore_crane.dynamics.cable.Mode`, see the
    module docstring): the hanging load's (:func:`offshore_crane.dynamics.cable.modes` at
    the cable's longest length, where its sway decays slowest), and a computed-torque
    law's error dynamics ``ë + Kd ė + Kp e = 0`` per coordinate (ω = √Kp,
    ζ = Kd / (2 √Kp)) when the scene is simulated under one. A prescribed rigid robot has
    none."""
    from offshore_crane.dynamics.cable import Mode, modes
    from offshore_crane.scenes.scene import hoist_waypoints

    out = []
    if robot.hybrid.cable is not None:
        hoist = hoist_waypoints(scene)
        length = None if hoist is None else max(row[-1] for row in hoist)
        elastic = ({"ea": scene.cable["ea"], "damping": scene.cable.get("damping", 0.0)}
                   if "ea" in scene.cable else {})
        out += modes(robot, length=length, gravity=scene.gravity, **elastic)
    if scene.simulated and scene.control.get("law", "computed-torque") == "computed-torque":
        from offshore_crane.simulation.control import Controller

        law = Controller(**{k: v for k, v in scene.control.items() if k in ("kp", "kd")})
        for kp, kd in sorted({(float(a), float(b)) for a, b in zip(*law.gains)}):
            if kp > 0.0:
                out.append(Mode("tracking", math.sqrt(kp), kd / (2.0 * math.sqrt(kp))))
    return tuple(out)


def kind(mode) -> str:
    """What moves in a mode: ``"sway"`` of ``"sway phi1"``, ``"axial"``, ``"tracking"``."""
    return mode.name.split()[0]


def slowest(modes):
    """The damped mode with the longest decay time, or None (no damped mode)."""
    damped = [m for m in modes if math.isfinite(m.decay_time)]
    return max(damped, key=lambda m: m.decay_time) if damped else None


def warn_light_damping(modes, where: str) -> None:
    """A :class:`LightlyDampedWarning` naming the modes damped below
    :data:`LIGHT_DAMPING` (one warning for modes of the same frequency and damping, such
    as the two sway angles')."""
    light: dict = {}
    for m in modes:
        if m.zeta < LIGHT_DAMPING:
            light.setdefault((m.omega, m.zeta), []).append(m)
    for group in light.values():
        m = group[0]
        names = " and ".join(x.name for x in group)
        grow = ("no record of it is stationary: its extremes grow with the record's "
                "length" if m.zeta <= 0.0 else "a record's extremes depend on its length")
        warnings.warn(LightlyDampedWarning(
            f"{where}: {names} {'is' if len(group) == 1 else 'are'} lightly damped "
            f"({m.describe().split(': ', 1)[1]}, below {100 * LIGHT_DAMPING:g} % of "
            f"critical): {grow}; add damping (payload.sway_damping, [cable] damping) where "
            "the real system has it"), stacklevel=3)


def check_own_record(scene: Scene, robot) -> None:
    """Warnings for a sea scene judged on its own record (``[extremes] record =
    "scene"``): a :class:`LightlyDampedWarning` per lightly damped mode, a
    :class:`ShortRecordWarning` when the record is shorter than :data:`SPIN_UP_DECAYS`
    decay times of its slowest damped mode."""
    modes = scene_modes(scene, robot)
    warn_light_damping(modes, scene.where())
    slow = slowest(modes)
    duration = SEA_DURATION if scene.duration is None else float(scene.duration)
    if slow is not None and duration < SPIN_UP_DECAYS * slow.decay_time:
        warnings.warn(ShortRecordWarning(
            f"{scene.where()}: the record ({duration:g} s) is shorter than "
            f"{SPIN_UP_DECAYS:g} decay times of the {kind(slow)} mode ({slow.describe()}): "
            "it starts from rest and its extremes depend on its length; judge exposure "
            "records instead ([extremes] record = \"exposure\")"), stacklevel=2)


@dataclass(frozen=True)
class ExposurePlan:
    """One seed's exposure record (:func:`exposure_plan`).

    Attributes:
        scene: The scene to run: its duration the spin-up, the delay and the exposure;
            its operation repeated every cycle.
        start: Model time where the judged window begins [s] (the spin-up and a
            compensation's delay).
        length: The judged window's length, the exposure at model scale [s].
        exposure: The exposure, full scale [s].
        spin_up: The spin-up, model scale [s] (whole cycles).
        cycle: The scene's own duration, one cycle of its operation [s].
        modes: :func:`scene_modes`.
        scale: Froude scale λ.
    """

    scene: Scene
    start: float
    length: float
    exposure: float
    spin_up: float
    cycle: float
    modes: tuple
    scale: float

    def describe(self) -> str:
        """One line: what the record is and why its spin-up is what it is."""
        slow = slowest(self.modes)
        why = ("no dynamic mode: the forces follow the sea at once" if slow is None else
               f"{SPIN_UP_DECAYS:g} decay times of the {kind(slow)} mode, "
               f"{slow.decay_time:.3g} s each, rounded up to whole {self.cycle:g} s cycles")
        given = self.scene.extremes.get("spin_up")
        if given is not None:
            why = "[extremes] spin_up, rounded up to whole cycles"
        rows = self.scene.operation
        arm = ("the arm held" if rows is None or len(rows) == 1 else
               f"the {self.cycle:g} s operation repeated")
        return (f"stationary records of {self.length:.6g} s model scale "
                f"({self.exposure / 3600:g} h full scale at 1:{self.scale:g}), {arm}, each "
                f"after a {self.spin_up:g} s spin-up ({why}), discarded")


def extremes_option(scene: Scene, key: str):
    """The scene's ``[extremes]`` value of ``key``, or its default
    (:data:`~offshore_crane.scenes.keys.EXTREMES_DEFAULTS`)."""
    return scene.extremes.get(key, EXTREMES_DEFAULTS[key])


def judged_on_exposure(scene: Scene) -> bool:
    """True when the scene's extremes are judged on exposure records: a sea scene, not a
    lift event (one event, not a stationary process), not ``[extremes] record =
    "scene"``."""
    return (scene.trajectory == "sea" and not scene.lift
            and extremes_option(scene, "record") == "exposure")


def exposure_plan(scene: Scene, robot) -> ExposurePlan:
    """The exposure record of a sea scene (module docstring), its modes' warnings issued.

    Raises:
        SceneError: the scene is not judged on exposure records
            (:func:`judged_on_exposure`); an operation that does not end where it starts,
            or that outlasts the scene's duration (it cannot be repeated).
    """
    if not judged_on_exposure(scene):
        raise SceneError(f"{scene.where()}: exposure records apply to a sea scene without "
                         "[lift] and with [extremes] record = \"exposure\"",
                         path=scene.path, name="extremes.record")
    modes = scene_modes(scene, robot)
    warn_light_damping(modes, scene.where())
    scale = float(scene.sea["scale"])
    cycle = SEA_DURATION if scene.duration is None else float(scene.duration)
    exposure = 3600.0 * float(extremes_option(scene, "exposure"))
    length = exposure / math.sqrt(scale)
    given = scene.extremes.get("spin_up")
    slow = slowest(modes)
    spin = float(given) if given is not None else (
        0.0 if slow is None else SPIN_UP_DECAYS * slow.decay_time)
    spin_up = math.ceil(spin / cycle - 1e-9) * cycle          # whole cycles
    delay = float(scene.control.get("delay", 0.0)) if "compensation" in scene.control else 0.0
    total = spin_up + delay + length
    operation = _repeated(scene, cycle, total)
    run = replace(scene, duration=total, operation=operation,
                  origin=f"{scene.where()} (exposure record)")
    return ExposurePlan(run, spin_up + delay, length, exposure, spin_up, cycle, modes, scale)


def _repeated(scene: Scene, cycle: float, total: float):
    """The scene's ``[operation]`` waypoints repeated every ``cycle`` [s] up to ``total``
    [s] (None and a single held pose stay as they are).

    Raises:
        SceneError: the operation does not end where it starts, or its last waypoint
            lies beyond ``cycle``.
    """
    rows = scene.operation
    if rows is None or len(rows) == 1:
        return rows
    where = scene.where()
    if tuple(rows[0][1:]) != tuple(rows[-1][1:]):
        raise SceneError(
            f"{where}: [operation] ends at {list(rows[-1][1:])} but starts at "
            f"{list(rows[0][1:])}: an exposure record repeats the operation every "
            f"{cycle:g} s (the scene's duration) under one sea, so it must end where it "
            "starts; close the cycle, or judge the scene's own record with [extremes] "
            "record = \"scene\" (observed extremes only)", path=scene.path,
            name="operation.waypoints")
    if rows[-1][0] > cycle or rows[0][0] < 0.0:
        raise SceneError(
            f"{where}: [operation] runs from t = {rows[0][0]:g} to {rows[-1][0]:g} s, "
            f"outside the scene's {cycle:g} s: an exposure record repeats the operation "
            "every duration; lengthen [trajectory] duration to hold one whole cycle",
            path=scene.path, name="operation.waypoints")
    out = []
    for k in range(int(total // cycle) + 1):
        for row in rows:
            t = row[0] + k * cycle
            if out and t <= out[-1][0]:          # the next cycle's start on the last end
                continue
            out.append((t, *row[1:]))
    return tuple(out)
