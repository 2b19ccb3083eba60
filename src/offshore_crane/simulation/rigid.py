"""Time simulation of the closed-loop robot under a controller.

The state ``(q, q̇)`` lives in the 9 independent coordinates of ``docs/conventions.md``:
the loops are closed by construction, there is no constraint drift. The accelerations come
from the equations of motion ``M q̈ + h = A X`` (:mod:`offshore_crane.dynamics.forward`),
the actuator forces X from a controller (:mod:`offshore_crane.simulation.control`) tracking a
reference motion.

Integrators:

- ``"rk4"`` (default): classical fixed-step Runge–Kutta at ``step`` [s] on the RK4 driver
  (:mod:`.driver`) with the rigid plant
  (:class:`~offshore_crane.simulation.plants.RigidPlant`), compiled whole with a built-in
  law: the reference is evaluated analytically at every stage time (t, t + h/2, t + h)
  beforehand; with a control rate the law is evaluated at the control instants and X held
  in between (sample-and-hold), otherwise at every stage. Every law of the registry, a
  Python callable ``law(t, q, qd, q_ref, qd_ref, qdd_ref) -> X (9,)`` [s, m, rad, ... →
  N·m, N], sensors and actuator models (:mod:`.instruments`) run there: one
  forward-dynamics pass and one call of the law per stage (the pass shared by a computed
  torque on the plant's own model; X clipped to the capacities, the time saturated
  reported).
- ``"dop853"``: SciPy's adaptive ``solve_ivp`` (DOP853, ``rtol``/``atol`` stated in the
  result), driven from Python: the accuracy reference for RK4, for the built-in laws with
  a code (:mod:`.laws.codes`), continuous, without sensor or actuator models.

The simulation stops at the first sample that leaves the workspace, reaches a singular
configuration (the mass matrix at the attitude singularity) or diverges (a non-finite
state): :class:`~offshore_crane.errors.SimulationError` names the time and the cause and
carries the :class:`SimulationResult` up to that sample (``error.result``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from offshore_crane.simulation.control import Controller
from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError, SimulationError
from offshore_crane.validation import as_gravity
from offshore_crane.simulation.record import (SimulationResult, initial_state,
                                              reference_grid, steps)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from offshore_crane.robot import Robot
    from offshore_crane.simulation.instruments import Actuators, Sensors

#: A reference motion: ``reference(t (n,) [s]) -> (q, qd, qdd)``, each ``(n, 9)``.
Reference = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
#: A Python control law ``law(t [s], q, qd, q_ref, qd_ref, qdd_ref (9,)) -> X (9,)``.
Law = Callable[..., np.ndarray]

INTEGRATORS = ("rk4", "dop853")


# --------------------------------------------------------------------------- public
def simulate(robot: Robot, duration: float, reference: Reference, q0: ArrayLike | None = None,
             qd0: ArrayLike | None = None, controller: Controller | Law | None = None, *,
             gravity: ArrayLike = GRAVITY, step: float = 1e-3, rate: float | None = None,
             integrator: str = "rk4", limits: bool = True, rtol: float = 1e-10,
             atol: float = 1e-12, t0: float = 0.0, sensors: Sensors | None = None,
             actuators: Actuators | None = None, **cable) -> SimulationResult:
    """Simulate the robot from ``(q0, q̇0)`` for ``duration`` seconds.

    Args:
        robot: From :func:`offshore_crane.load_robot` (the plant).
        duration: [s] > 0.
        reference: A callable ``reference(t (n,)) -> (q, qd, qdd)`` each ``(n, 9)``
            (e.g. :func:`offshore_crane.motion.trajectories.table1`), evaluated at every stage.
        q0, qd0: ``(9,)`` initial state (default: the reference at ``t0``).
        controller: :class:`~offshore_crane.simulation.control.Controller` (default
            computed torque) or a Python law ``law(t, q, qd, q_ref, qd_ref, qdd_ref) -> X``
            (:mod:`offshore_crane.simulation.laws.python`).
        gravity: ``(3,)`` [m/s²].
        step: Integration step [s] (RK4).
        rate: Output sampling rate [Hz] (default every step); 1/rate must be a multiple
            of ``step``.
        integrator: ``"rk4"`` or ``"dop853"``.
        limits: Stop at the first sample outside the workspace.
        rtol, atol: Tolerances of DOP853.
        t0: Start time [s].
        sensors: :class:`~offshore_crane.simulation.instruments.Sensors` (noise, delay,
            quantisation of the measured q, q̇; with a control rate).
        actuators: :class:`~offshore_crane.simulation.instruments.Actuators` (rate limit,
            first-order lag).
        **cable: With a payload on a cable: ``initial``, ``initial_rate`` (2,) of the
            sway [rad, rad/s] (:func:`offshore_crane.simulation.swing.simulate_swing`,
            which then runs).

    Returns:
        :class:`SimulationResult`.

    Raises:
        InputError: bad arguments (one-line message).
        SimulationError: the run stopped early (``error.result`` holds what was computed).
    """
    controller = Controller() if controller is None else controller
    if robot.hybrid.cable is not None or cable:
        if integrator != "rk4":
            raise InputError(f"integrator {integrator!r}: with a payload on a cable the "
                             "simulation runs RK4", name="integrator")
        from offshore_crane.simulation.swing import simulate_swing

        return simulate_swing(robot, duration, reference, q0, qd0, controller,
                              gravity=gravity, step=step, rate=rate, limits=limits, t0=t0,
                              sensors=sensors, actuators=actuators, **cable)
    if integrator not in INTEGRATORS:
        raise InputError(f"unknown integrator {integrator!r}: use one of "
                         f"{', '.join(INTEGRATORS)}", name="integrator")
    if integrator == "rk4":
        return _driven(robot, duration, reference, q0, qd0, controller, gravity, step, rate,
                       limits, t0, sensors, actuators)
    if not _dop853_runs(controller, sensors, actuators):
        raise InputError("DOP853 runs the built-in laws without sensor or actuator "
                         "models: use integrator 'rk4'", name="integrator")
    if any(np.any(n) for n in controller.noise) or controller.rate is not None:
        raise InputError("DOP853 runs a continuous law without measurement noise: drop the "
                         "control rate and the noise, or use integrator 'rk4'",
                         name="integrator")
    n_steps, out_every, _ = steps(duration, step, rate, controller.rate)
    g = as_gravity(gravity)
    tt, qr, qdr, _ = reference_grid(reference, t0, step, n_steps)
    q0, qd0 = initial_state(q0, qd0, qr[0], qdr[0])
    return _dop853(robot, tt[::2], reference, q0, qd0, controller, g, limits, rtol, atol,
                   out_every)


def _dop853_runs(controller, sensors, actuators) -> bool:
    """True when the DOP853 path runs this law: a controller whose law has a code in
    it (:mod:`.laws.codes`), without sensor models or actuator dynamics."""
    if not isinstance(controller, Controller) or controller.function is not None:
        return False
    from offshore_crane.simulation.laws import law_class

    return (law_class(controller.law_name).code is not None
            and not (sensors is not None and sensors.active)
            and not (actuators is not None and actuators.active))


def _driven(robot, duration, reference, q0, qd0, controller, gravity, step, rate, limits, t0,
            sensors, actuators):
    """The rigid plant on the RK4 driver (module docstring)."""
    from offshore_crane.simulation.plants import RigidPlant
    from offshore_crane.simulation.runs import prepare

    if isinstance(controller, Controller) and controller.anti_sway:
        raise InputError("anti_sway damps the swing of a payload on a cable, but this "
                         "robot's payload is welded (payload.cable_length = 0)",
                         name="anti_sway")
    run = prepare(robot, duration, reference, q0, qd0, controller, gravity=gravity,
                  step=step, rate=rate, t0=t0, sensors=sensors, actuators=actuators,
                  plant=lambda model, g, tt: RigidPlant(robot, model, g))
    return run.drive(np.concatenate([run.q0, run.qd0]), limits)


def _dop853(robot, t_out, reference, q0, qd0, controller, g, limits, rtol, atol, out_every):
    """The adaptive reference integrator (continuous controller, driven from Python)."""
    from offshore_crane.errors import require

    integrate = require("scipy.integrate", "scipy", "The DOP853 integrator")
    from offshore_crane.simulation.rigid_equations import accel, law, workspaces
    from offshore_crane.dynamics.constants import robot_arrays

    plant = robot_arrays(robot)
    from offshore_crane.dynamics import compiled as c

    C = plant.kane
    Cc_arrays = robot_arrays(controller.model or robot)
    Cc = Cc_arrays.kane
    kp, kd = controller.gains
    lo, hi = controller.bounds(robot)
    n = 6 + C.n_arm
    ws, wl = workspaces(max(C.n_arm, Cc.n_arm))
    gt = tuple(float(x) for x in g)
    X = np.empty(9)
    qdd = np.empty(9)
    from offshore_crane.simulation.laws import law_class

    kind = law_class(controller.law).code
    del c

    def rhs(t, x):
        q, qd = x[:9].copy(), x[9:].copy()
        r = reference(np.array([t]))
        law(Cc, gt, kind, kp, kd, q, qd, r[0][0], r[1][0], r[2][0], X, wl)
        np.clip(X, lo, hi, out=X)
        accel(C, gt, n, q, qd, X, qdd, ws)
        return np.concatenate([qd, qdd])

    sol = integrate.solve_ivp(rhs, (t_out[0], t_out[-1]), np.concatenate([q0, qd0]),
                              method="DOP853", t_eval=t_out[::out_every], rtol=rtol, atol=atol)
    N = sol.t.size
    q, qd = sol.y[:9].T.copy(), sol.y[9:].T.copy()
    rq, rqd, _ = reference(sol.t)
    qdd_all = np.array([rhs(t, x)[9:] for t, x in zip(sol.t, sol.y.T)])
    Xa = np.empty((N, 9))
    for k in range(N):
        rr = reference(sol.t[k:k + 1])
        law(Cc, gt, kind, kp, kd, q[k], qd[k], rr[0][0], rr[1][0], rr[2][0], X, wl)
        Xa[k] = X
    Xapp = np.clip(Xa, lo, hi)
    res = SimulationResult(t=sol.t, q=q, qd=qd, qdd=qdd_all, q_ref=rq, qd_ref=rqd, X_cmd=Xa,
                           X=Xapp, saturated=(Xa < lo) | (Xa > hi), energy=np.full(N, np.nan),
                           power=np.full(N, np.nan), integrator="dop853", step=0.0,
                           info=dict(rtol=rtol, atol=atol, nfev=sol.nfev))
    if not sol.success:
        res.stop = f"DOP853 stopped: {sol.message}"
        raise SimulationError(f"simulation {res.stop}", time=float(sol.t[-1]) if N else 0.0,
                              cause=sol.message, result=res)
    return res


def warm_up(robot=None, swing: bool = True) -> list[tuple[str, float]]:
    """Compile (or load from the cache) the simulation loops, the rigid robot's and, with
    ``swing``, the hanging load's (:func:`offshore_crane.simulation.swing.warm_up`), and
    a stepper's workspace check (:mod:`offshore_crane.dynamics.outside`):
    ``[(name, seconds), ...]``."""
    import time

    from offshore_crane.dynamics import outside
    from offshore_crane.robot import load_robot
    from offshore_crane.motion.trajectories import table1
    from offshore_crane.simulation.swing import warm_up as warm_up_swing

    robot = robot or load_robot()
    t0 = time.perf_counter()
    simulate(robot.without_hanging_payload(), 2e-3, table1, step=1e-3)
    t1 = time.perf_counter()
    outside.first_outside(robot.home_pose()[None, :], 0, 1, *outside.geometry(robot))
    return [("simulation loop", t1 - t0),
            ("stepper's workspace check", time.perf_counter() - t1)] + (
        warm_up_swing(robot) if swing else [])
