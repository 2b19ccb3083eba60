"""A scene's run as a simulation you step (:class:`~offshore_crane.simulation.stepper.
Stepper`), set up as ``offshore-crane simulate --scene`` sets its run up."""

from __future__ import annotations

import numpy as np

from offshore_crane.errors import InputError
from offshore_crane.scenes.assembly import controller, instruments, load_robot, load_trajectory
from offshore_crane.scenes.reading import load_scene
from offshore_crane.scenes.running import plant_options
from offshore_crane.scenes.scene import Scene


def stepper(scene, *, control_period: float, duration: float | None = None,
            limits: bool = True, action: str = "forces"):
    """A :class:`~offshore_crane.simulation.stepper.Stepper` on ``scene`` (a path or a
    :class:`~offshore_crane.scenes.Scene`): the scene's robot, reference (the compensated
    arm's commands under a compensation), cable and winch (:func:`plant_options`, as
    ``simulate --scene``), sensors and actuators, integration step (``[control] step``,
    else 1 ms), gravity and capacities (``saturation``), from the reference's start.

    Args:
        control_period: [s], a whole number of integration steps.
        duration: [s] (default: the scene's, cut to whole control periods).
        limits: As ``simulate``.
        action: ``"forces"`` or ``"reference"``: a reference for the scene's controller
            (``[control]``'s law, at the control period).

    Raises:
        InputError, SceneError: what the scene or the run's set-up refuses; a duration
            longer than the scene's reference.
    """
    from offshore_crane.simulation.stepper import Stepper

    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    robot = load_robot(scene)
    traj, elastic, swing = plant_options(scene, robot, load_trajectory(scene, robot))
    period = float(control_period)
    span = float(traj.t[-1] - traj.t[0])
    if duration is None:
        duration = float(np.floor(span / period + 1e-9)) * period
    elif duration > span + 1e-9:
        raise InputError(f"duration = {duration:g} s is longer than the scene's reference "
                         f"({span:g} s)", name="duration")
    law = controller(scene, robot)
    return Stepper(robot, duration, traj.reference, control_period=period,
                   saturation=law.saturation, action=action,
                   controller=law if action == "reference" else None,
                   step=float(scene.control.get("step", 1e-3)), gravity=scene.gravity,
                   t0=float(traj.t[0]), limits=limits, **(elastic or swing),
                   **instruments(scene))
