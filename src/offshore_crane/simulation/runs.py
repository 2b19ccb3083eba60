"""A run set up for the RK4 driver: the controller turned into a bound law of the
registry on a plant, the time grid, the reference at every stage, the initial state, the
capacities, the sensors and actuators — checked once, here, for every plant
(:func:`prepare`)."""

from __future__ import annotations

import contextvars
from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError


@dataclass
class Run:
    """A prepared run (:func:`prepare`): ``plant``, bound ``law``, ``grid`` (the reference
    at every stage), ``timing`` (:class:`~offshore_crane.simulation.driver.Timing`),
    ``q0``, ``qd0`` ``(9,)``, capacities ``lower``, ``upper`` ``(plant.nx,)``, ``sensors``,
    ``actuators``, ``info``."""

    plant: object
    law: object
    grid: tuple
    timing: object
    q0: np.ndarray
    qd0: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    sensors: object
    actuators: object
    info: dict

    def drive(self, y0, limits: bool = True):
        """Run the driver from the plant's state ``y0`` (within :func:`opened`: hand the
        run over instead)."""
        from offshore_crane.simulation.driver import drive

        if _OPENING.get():
            raise _Opened(self, np.asarray(y0, dtype=float), limits)

        return drive(self.plant, self.law, self.grid, y0, self.timing, self.lower,
                     self.upper, sensors=self.sensors, actuators=self.actuators,
                     limits=limits, info=self.info)


#: True while :func:`opened` runs a simulate function up to its driver.
_OPENING = contextvars.ContextVar("offshore_crane_opening", default=False)


class _Opened(Exception):
    """A run handed over at :meth:`Run.drive` (:func:`opened`)."""

    def __init__(self, run, y0, limits):
        super().__init__("a run handed over before it was driven")
        self.run, self.y0, self.limits = run, y0, limits


def opened(call) -> tuple:
    """Run ``call()`` (a simulate function with its arguments: it checks them and sets
    its plant's run up, the initial state included) up to the driver, which it does not
    run: ``(run, y0, limits)`` of :meth:`Run.drive` (a stepper drives it piece by
    piece). Raises what ``call`` raises before that."""
    token = _OPENING.set(True)
    try:
        call()
    except _Opened as handed:
        return handed.run, handed.y0, handed.limits
    finally:
        _OPENING.reset(token)
    raise RuntimeError("the simulation returned without reaching its driver: report this "
                       "as a bug")


def bind_law(controller, plant):
    """The law of ``controller`` (a :class:`~offshore_crane.simulation.control.Controller`
    or a Python callable) bound to ``plant``.

    Raises:
        InputError: not a controller, a law the plant does not run.
    """
    from offshore_crane.simulation.control import Controller
    from offshore_crane.simulation.laws import check_plant, law_class
    from offshore_crane.simulation.laws.python import PythonLaw

    if isinstance(controller, Controller) and controller.function is not None:
        return PythonLaw(controller, plant, controller.function)
    if isinstance(controller, Controller):
        cls = law_class(controller.law_name)
        check_plant(cls, plant.name)
        return cls(controller, plant)
    if not callable(controller):
        raise InputError(f"controller must be a Controller or a callable law(t, q, qd, "
                         f"q_ref, qd_ref, qdd_ref) -> X, got {controller!r}",
                         name="controller")
    return PythonLaw(Controller(), plant, controller)


def sensors_of(controller, sensors):
    """The run's :class:`~offshore_crane.simulation.instruments.Sensors`: ``sensors``, or
    the controller's shorthand ``noise_q``/``noise_qd``/``seed`` (one of the two).

    Raises:
        InputError: both given.
    """
    from offshore_crane.simulation.control import Controller
    from offshore_crane.simulation.instruments import Sensors

    noisy = isinstance(controller, Controller) and any(np.any(n) for n in controller.noise)
    if noisy and sensors is not None:
        raise InputError("measurement noise given twice: in the controller (noise_q, "
                         "noise_qd) and in the sensors; give it in the sensors only",
                         name="noise_q")
    if noisy:
        nq, nqd = controller.noise
        return Sensors(noise_q=nq, noise_qd=nqd, seed=controller.seed)
    return sensors


def prepare(robot, duration, reference, q0, qd0, controller, *, gravity=GRAVITY,
            step: float = 1e-3, rate=None, t0: float = 0.0, sensors=None, actuators=None,
            plant=None, info=None) -> Run:
    """Check and set up a run of ``plant(model, g, tt)`` (a factory: the controller's
    model, the gravity and every stage time [s]) under ``controller`` (arguments as
    :func:`offshore_crane.simulation.rigid.simulate`).

    Raises:
        InputError: bad arguments; a law the plant does not run; sensors or a rate limit
            without a control rate; a sensor delay that is not a whole number of steps.
    """
    from offshore_crane.simulation.control import Controller
    from offshore_crane.simulation.driver import Timing
    from offshore_crane.simulation.record import (initial_state, reference_grid, stage_times,
                                                  steps)
    from offshore_crane.validation import as_gravity

    controller = Controller() if controller is None else controller
    is_controller = isinstance(controller, Controller)
    n_steps, out_every, hold = steps(duration, step, rate,
                                     controller.rate if is_controller else None)
    g = as_gravity(gravity)
    p = plant((controller.model if is_controller else None) or robot, g,
              stage_times(t0, step, n_steps))
    law = bind_law(controller, p)
    sensors = sensors_of(controller, sensors)
    if sensors is not None and sensors.active:
        sensors.delay_steps(step)
    tt, qr, qdr, qddr = reference_grid(reference, t0, step, n_steps)
    law.grid = (tt, qr, qdr, qddr)
    given = q0 is not None
    q0, qd0 = initial_state(q0, qd0, qr[0], qdr[0])
    if not given:
        q0, qd0 = law.start(q0, qd0)
    ctrl = controller if is_controller else Controller()
    lo, hi = ctrl.bounds(p.robot)
    if p.nx > 9:            # a commanded winch: its pull within ±pull_max (or none)
        cap = p.robot.winch.pull_max if ctrl.saturation else np.inf
        lo, hi = np.append(lo, -cap), np.append(hi, cap)
    info = dict(info or {}, **({} if is_controller else {"controller": "python"}))
    return Run(p, law, (tt, qr, qdr, qddr), Timing(step, n_steps, out_every, hold, t0),
               q0, qd0, lo, hi, sensors, actuators, info)
