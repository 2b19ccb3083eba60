"""The forward simulation with the hanging load: the robot under a controller while its
payload swings (docs/cable.md, "Simulation and anti-sway"): the hanging plant
(:class:`~offshore_crane.simulation.plants.HangingPlant`: 11 coordinates, q1..q9 and the
sway angles φ1, φ2, and their rates) on the RK4 driver (:mod:`.driver`), and what its
record is completed with (the tension, the actuators' power, the slack and workspace
stops). Every law runs on it where it makes sense: computed torque reads the sway
(:func:`~offshore_crane.dynamics.cable.kernels.computed_torque`), so that with an exact
model the tracking error obeys ``ë + Kd ė + Kp e = 0`` however the load swings; the
anti-sway law (:mod:`offshore_crane.simulation.laws.anti_sway`) damps the swing.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.control import Controller
from offshore_crane.conventions import GRAVITY

def simulate_swing(robot, duration: float, reference, q0=None, qd0=None, controller=None, *,
                   gravity=GRAVITY, step: float = 1e-3, rate: float | None = None,
                   initial=(0.0, 0.0), initial_rate=(0.0, 0.0), limits: bool = True,
                   t0: float = 0.0, sensors=None, actuators=None, hoist=None):
    """Simulate the robot with its payload swinging on its cable (the hanging plant,
    :class:`~offshore_crane.simulation.plants.HangingPlant`, on the RK4 driver).

    Args:
        robot: With a payload on a cable (``payload.cable_length > 0``).
        duration, reference, q0, qd0, gravity, step, rate, limits, t0, sensors,
            actuators: As :func:`offshore_crane.simulation.rigid.simulate`.
        controller: :class:`~offshore_crane.simulation.control.Controller` (any law that
            runs on the hanging plant, ``anti_sway``, a control rate, saturation, a
            model that differs from the plant (with a cable too)), or a Python law.
        initial, initial_rate: ``(2,)`` sway φ1, φ2 [rad] and rates [rad/s] at ``t0``.
        hoist: A winch ``hoist(t (n,)) -> (L, L̇, L̈)`` [m, m/s, m/s²], each ``(n,)``
            (:func:`~offshore_crane.dynamics.cable.hoist_profile`, a compensation's
            ``hoist_function``), read at every stage time: the cable's length follows it
            (the plant's and the controller's model's); None: the fixed length.

    Returns:
        :class:`~offshore_crane.simulation.rigid.SimulationResult` with ``sway``, ``sway_rate``
        ``(N, 2)`` and ``tension`` ``(N,)`` [N]; with a winch, ``info["length"]``
        ``(N,)`` [m].

    Raises:
        InputError: bad arguments, a law or option the hanging load does not take.
        SimulationError: the run stopped (workspace, singular, diverged, slack cable);
            ``error.result`` keeps every sample computed before.
    """
    from offshore_crane.errors import InputError
    from offshore_crane.simulation.plants import HangingPlant
    from offshore_crane.simulation.runs import prepare
    from offshore_crane.validation import as_pair

    sway0, rate0 = as_pair(initial, "initial", "rad"), as_pair(initial_rate, "initial_rate",
                                                            "rad/s")
    m_w = robot.winch.reflected_mass
    if hoist is not None and m_w > 0.0:
        raise InputError(f"actuators.winch.reflected_mass = {m_w:g} kg makes the winch a "
                         "commanded actuator, which runs on an elastic cable only: give the "
                         "cable's EA ([cable] ea, simulate_elastic) or drop the reflected "
                         "mass (the winch then follows its length profile)",
                         name="actuators.winch.reflected_mass")
    run = prepare(robot, duration, reference, q0, qd0, controller, gravity=gravity,
                  step=step, rate=rate, t0=t0, sensors=sensors, actuators=actuators,
                  plant=lambda model, g, tt: HangingPlant(robot, model, g, hoist, tt))
    y0 = np.concatenate([run.q0, sway0, run.qd0, rate0])
    return run.drive(y0, limits)


def warm_up(robot=None) -> list[tuple[str, float]]:
    """Compile (or load from the cache) the driver's loop with a hanging load under
    computed torque (``simulate --scene`` of a hanging load; another law's loop compiles
    on its first use, some 7 s): ``[(name, seconds)]``."""
    import time

    from offshore_crane.dynamics.cable import cable_robot
    from offshore_crane.robot import load_robot

    t0 = time.perf_counter()
    robot = robot or load_robot()
    if robot.hybrid.cable is None:
        robot = cable_robot(robot, length=1.0, mass=1.0)
    from offshore_crane.simulation.record import held

    rest = held(robot.home_pose())
    simulate_swing(robot, 2e-3, rest, controller=Controller(), step=1e-3, limits=False)
    return [("hanging-load simulation loop", time.perf_counter() - t0)]
