"""The forward simulation with the payload on an elastic cable, a winch and motion
compensation: the robot under a controller while its load flies on the cable (docs/cable.md,
"Forward simulation of the real lift").

The elastic plant (:class:`~offshore_crane.simulation.plants.ElasticPlant`: the robot
without its hanging payload, pulled at the tip by the cable, and the payload a point mass
with three free coordinates) on the RK4 driver (:mod:`.driver`), under any law that runs on
it (computed torque reads the cable's pull measured at the tip, a load cell, so that with
an exact model the tracking error obeys ``ë + Kd ė + Kp e = 0`` however the load flies).
The step must resolve the cable's axial period ``2π √(m L / EA)``: at least
:data:`STEPS_PER_PERIOD` steps in the shortest one, or the run is refused.

A winch whose description gives a reflected mass (``actuators.winch.reflected_mass``
> 0) is a commanded actuator: its length and rate join the state, ``m_w L̈ = T − Fw``,
and its line pull ``Fw`` is the 10th force. Its drive makes the length follow the
profile (``hoist``, or the fixed length) with the computed-torque law's default
closed-loop frequency (:data:`~offshore_crane.simulation.control.CT_OMEGA`, critically
damped) from the measured tension; a law that returns 10 forces commands the pull itself.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError
from offshore_crane.validation import as_gravity

#: Fewest RK4 steps in the cable's shortest axial period (the elastic inverse dynamics
#: takes 50; RK4's phase error there is ~1e-7 a period).
STEPS_PER_PERIOD = 20


def simulate_elastic(robot, duration: float, reference, q0=None, qd0=None, controller=None,
                     *, ea: float, damping: float = 0.0, hoist=None, gravity=GRAVITY,
                     step: float = 1e-3, rate: float | None = None, initial=None,
                     initial_velocity=None, limits: bool = True, t0: float = 0.0,
                     sensors=None, actuators=None):
    """Simulate the robot with its payload on an elastic cable.

    Args:
        robot: With a payload on a cable (``payload.cable_length`` the unstretched length
            without a winch, ``payload.mass``).
        duration, reference, q0, qd0, gravity, step, rate, limits, t0: As
            :func:`offshore_crane.simulation.rigid.simulate`.
        controller: :class:`~offshore_crane.simulation.control.Controller` (any law
            that runs on the elastic plant; its model is the plant's own) or a Python law.
        sensors, actuators: As :func:`offshore_crane.simulation.rigid.simulate`.
        ea, damping: The cable's EA [N] and axial damping [N·s/m] (the sway damping
            and the payload's drag are the robot description's: ``payload.sway_damping``,
            ``payload.drag_area``, ``payload.air_density``).
        hoist: The winch ``hoist(t) -> (L, L̇, L̈)`` [m, m/s, m/s²], or None.
        initial, initial_velocity: ``(3,)`` the payload from the tip [m] and relative to
            it [m/s] at ``t0``, base axes (default: hanging along g at its static
            stretch, at rest relative to the tip; with a commanded winch, moving along g
            at the winch's starting rate L̇).

    Returns:
        :class:`~offshore_crane.simulation.rigid.SimulationResult` with ``tension``
        ``(N,)`` [N] and ``info["payload"]``, ``info["payload_velocity"]`` ``(N, 3)``
        (base frame), ``info["length"]``, ``info["length_rate"]`` ``(N,)`` the cable's
        length [m] and its rate [m/s]; with a commanded winch ``info["winch_force"]``
        (applied), ``info["winch_force_cmd"]`` [N], ``info["winch_saturated"]`` and
        ``info["winch_power"]`` ``−Fw L̇`` [W] ``(N,)``.

    Raises:
        InputError: bad arguments, a step too long for the cable's axial period, a law
            or option this simulation does not take.
        SimulationError: the run stopped (workspace, diverged); ``error.result`` keeps
            every sample computed before.
    """
    from offshore_crane.dynamics.cable.elastic import check_cable
    from offshore_crane.dynamics.cable.grid import cable_robot
    from offshore_crane.dynamics.cable.tip import tip_positions
    from offshore_crane.simulation.control import CT_OMEGA, Controller
    from offshore_crane.simulation.plants import ElasticPlant
    from offshore_crane.simulation.runs import prepare

    controller = Controller() if controller is None else controller
    if isinstance(controller, Controller) and controller.model is not None:
        raise InputError("on an elastic cable the controller's model is the plant's own "
                         "(the pull is measured at the tip): leave model out",
                         name="model")
    check_cable(ea, damping)
    robot = cable_robot(robot)
    m = float(robot.hybrid.cable.mass[-1])
    check_cable(ea, damping, m)
    g = as_gravity(gravity)
    gn = float(np.linalg.norm(g))
    L0 = float(robot.hybrid.cable_length)

    def plant(model, g, tt):
        """The elastic plant with the winch's length at every stage time ``tt``; refused
        when the step cannot resolve the cable's shortest axial period."""
        Lg = (np.column_stack([np.full(len(tt), L0), np.zeros(len(tt)), np.zeros(len(tt))])
              if hoist is None else np.column_stack([np.asarray(x, float).reshape(len(tt))
                                                     for x in hoist(tt)]))
        p = ElasticPlant(robot, model, g, ea=ea, damping=damping, lengths=Lg,
                         winch_mass=robot.winch.reflected_mass,
                         winch_gains=(CT_OMEGA ** 2, 2.0 * CT_OMEGA))
        if step > p.axial_period / STEPS_PER_PERIOD:
            raise InputError(f"step = {step:g} s is too long for the cable's axial period "
                             f"{p.axial_period * 1e3:.3g} ms: give step <= "
                             f"{p.axial_period / STEPS_PER_PERIOD:.3g} s ({STEPS_PER_PERIOD} "
                             "steps a period)", name="step")
        return p

    run = prepare(robot, duration, reference, q0, qd0, controller, gravity=gravity,
                  step=step, rate=rate, t0=t0, sensors=sensors, actuators=actuators,
                  plant=plant)
    Lg = run.plant.Lg
    run.info["axial_period"] = run.plant.axial_period
    p_tip, v_tip = (x[0] for x in tip_positions(robot, run.q0[None], run.qd0[None]))
    winch = []
    if run.plant.commanded:               # where the law starts the winch, else its profile
        start = run.law.winch_start(run.q0, run.qd0)
        winch = np.array(Lg[0, :2] if start is None else start, dtype=float)
    rho0 = (g / gn * (winch[0] if len(winch) else Lg[0, 0]) * (1.0 + m * gn / ea)
            if initial is None else np.asarray(initial, dtype=float).reshape(3))
    v0 = (np.asarray(initial_velocity, dtype=float).reshape(3) if initial_velocity is not None
          else g / gn * (winch[1] if len(winch) else 0.0))
    return run.drive(np.concatenate([run.q0, p_tip + rho0, run.qd0, v_tip + v0, winch]),
                     limits)


def warm_up(robot=None) -> list[tuple[str, float]]:
    """Compile (or load from the cache) the elastic plant's kernels and the driver's loop
    on it under computed torque, and the interpolation of a sampled reference (a scene's
    compensated lift, a CSV file: :func:`~offshore_crane.motion.trajectories.hermite`):
    ``[(name, seconds)]``."""
    import time

    from offshore_crane.dynamics.cable.grid import cable_robot
    from offshore_crane.motion.trajectories import hermite
    from offshore_crane.robot import load_robot

    t0 = time.perf_counter()
    robot = robot or load_robot()
    if robot.hybrid.cable is None:
        robot = cable_robot(robot, length=1.0, mass=1.0)
    from offshore_crane.simulation.record import held

    rest = held(robot.home_pose())
    simulate_elastic(robot, 2e-3, rest, ea=1e4, step=1e-3, limits=False)
    t1 = time.perf_counter()
    hermite(np.arange(2.0), np.zeros((2, 9)), np.zeros((2, 9)), np.array([0.5]))
    return [("elastic-cable simulation loop", t1 - t0),
            ("trajectory interpolation", time.perf_counter() - t1)]
