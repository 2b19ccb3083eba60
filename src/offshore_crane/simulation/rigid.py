"""Time simulation of the closed-loop robot under a controller.

The state ``(q, q̇)`` lives in the 9 independent coordinates of ``docs/conventions.md``:
the loops are closed by construction, there is no constraint drift. The accelerations come
from the equations of motion ``M q̈ + h = A X`` (:mod:`offshore_crane.dynamics.forward`),
the actuator forces X from a controller (:mod:`offshore_crane.simulation.control`) tracking a
reference motion.

Integrators:

- ``"rk4"`` (default): classical fixed-step Runge–Kutta at ``step`` [s], compiled whole
  (the built-in laws included): the reference is evaluated analytically at every stage time
  (t, t + h/2, t + h) beforehand; with a control rate the law is evaluated at the control
  instants and X held in between (sample-and-hold), otherwise at every stage.
- ``"dop853"``: SciPy's adaptive ``solve_ivp`` (DOP853, ``rtol``/``atol`` stated in the
  result), driven from Python: the accuracy reference for RK4.

The built-in laws with a code in the compiled loop (:mod:`.laws.codes`) run there. Any
other law of the registry (``"pid"``, ``"anti-sway"``), a Python callable ``law(t, q, qd,
q_ref, qd_ref, qdd_ref) -> X (9,)`` [s, m, rad, ... → N·m, N], sensors and actuator models
(:mod:`.instruments`) run on the RK4 driver (:mod:`.driver`) with the rigid plant
(:class:`~offshore_crane.simulation.plants.RigidPlant`): one forward-dynamics call and one
call of the law per stage (X clipped to the capacities, the time saturated reported).

The simulation stops at the first sample that leaves the workspace, reaches a singular
configuration (the mass matrix at the attitude singularity) or diverges (a non-finite
state): :class:`~offshore_crane.errors.SimulationError` names the time and the cause and
carries the :class:`SimulationResult` up to that sample (``error.result``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from offshore_crane.simulation.control import Controller
from offshore_crane import progress
from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError, SimulationError
from offshore_crane.stops import StopCause
from offshore_crane.validation import as_gravity
from offshore_crane.simulation.record import (LawParameters, Packed, Recording, SimulationResult,
                                              StageGrid, divergence, diverging, finite_rows,
                                              initial_state, reference_grid, steps, stopped)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from offshore_crane.robot import Robot
    from offshore_crane.simulation.instruments import Actuators, Sensors

#: A reference motion: ``reference(t (n,) [s]) -> (q, qd, qdd)``, each ``(n, 9)``.
Reference = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
#: A Python control law ``law(t [s], q, qd, q_ref, qd_ref, qdd_ref (9,)) -> X (9,)``.
Law = Callable[..., np.ndarray]

INTEGRATORS = ("rk4", "dop853")


# --------------------------------------------------------------------------- compiled
def _loop():
    """The compiled RK4 loop, its control law and accelerations (:mod:`.rk4`, which
    imports Numba: loaded on first use)."""
    from offshore_crane.simulation import rk4 as _rk4

    return _rk4.run, _rk4.law, _rk4.accel


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
    if not _compiled(controller, sensors, actuators):
        if integrator != "rk4":
            raise InputError("DOP853 runs the built-in laws without sensor or actuator "
                             "models: use integrator 'rk4'", name="integrator")
        return _driven(robot, duration, reference, q0, qd0, controller, gravity, step, rate,
                       limits, t0, sensors, actuators)
    from offshore_crane.simulation.laws import codes, law_class

    law_class(controller.law_name)
    if any(np.any(n) for n in controller.noise):
        if controller.rate is None:
            raise InputError("measurement noise (noise_q, noise_qd) acts at the control "
                             "instants of a sampled law: give a control rate",
                             name="noise_q")
    n_steps, out_every, hold = steps(duration, step, rate, controller.rate)
    g = as_gravity(gravity)
    tt, qr, qdr, qddr = reference_grid(reference, t0, step, n_steps)
    q0, qd0 = initial_state(q0, qd0, qr[0], qdr[0])
    if integrator == "dop853":
        return _dop853(robot, tt[::2], reference, q0, qd0, controller, g, limits, rtol, atol,
                       out_every)
    from offshore_crane.dynamics.constants import robot_arrays
    from offshore_crane.robot.kinematics import workspace as ws

    run = _loop()[0]
    from offshore_crane.simulation.rk4 import work_size
    plant = robot_arrays(robot)
    model = robot_arrays(controller.model or robot)
    kp, kd = controller.gains
    lo, hi = controller.bounds(robot)
    n_ctrl = n_steps // hold + 2 if hold else 1
    rng = np.random.default_rng(controller.seed)
    sq, sqd = controller.noise
    nq = rng.normal(size=(n_ctrl, 9)) * sq
    nqd = rng.normal(size=(n_ctrl, 9)) * sqd
    n_out = n_steps // out_every + 1
    kind = law_class(controller.law).code
    if (kind == codes.COMPUTED_TORQUE and hold == 0 and all(
            np.array_equal(a, b) for a, b in ((plant.flat, model.flat), (plant.layout,
                                              model.layout), (plant.prismatic,
                                                              model.prismatic)))):
        kind = codes.SHARED                        # one explicit pass a stage serves both
    rec = Recording.empty(n_out)
    health = ws.new_health()
    status = np.zeros(3, dtype=np.int64)
    stop = progress.stop_flag()
    progress.run_polled(
        lambda: run(Packed(plant.flat, plant.layout, plant.prismatic),
                    Packed(model.flat, model.layout, model.prismatic), g, step, n_steps,
                    out_every, StageGrid(qr, qdr, qddr),
                    LawParameters(kind, kp, kd, hold, nq, nqd, lo, hi),
                    limits, q0, qd0, rec, health, status, stop,
                    np.zeros(work_size(max(plant.kane.n_arm, model.kane.n_arm)))),
        lambda: status[2], n_out, "sample", "simulate", stop)
    n_done = int(status[2])
    t_out = tt[::2][::out_every][:n_out]
    res = SimulationResult(t=t_out, **rec._asdict(), integrator="rk4", step=step)
    if status[0] != StopCause.NONE:
        code = StopCause(int(status[0]))
        k = int(status[1])
        when = t0 + k * step
        res = res.truncated(n_done)
        if code is StopCause.WORKSPACE:
            try:
                ws.check_limits(health, plant.limits, res.q[-1:], None)
                cause = "left the workspace"
            except Exception as exc:          # the WorkspaceError's text names the limit
                cause = str(exc).split(" at sample")[0] + " (outside its limits)"
        diverged = code is StopCause.DIVERGED or diverging(res)
        res = res.truncated(finite_rows(res))
        if diverged:
            code, cause = StopCause.DIVERGED, divergence(res)
        elif code is StopCause.SINGULAR:
            cause = ("the mass matrix became singular (attitude singularity, "
                     f"q5 = {res.q[-1, 4]:.4g} rad)")
        exc = stopped(res, when, cause)
        exc.stop_cause = code
        raise exc
    return res


def _compiled(controller, sensors, actuators) -> bool:
    """True when the compiled loop runs this law: a controller whose law has a code in
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
    _, law, accel = _loop()
    from offshore_crane.dynamics.constants import robot_arrays

    plant = robot_arrays(robot)
    from offshore_crane.dynamics import compiled as c

    C = plant.kane
    Cc_arrays = robot_arrays(controller.model or robot)
    Cc = Cc_arrays.kane
    kp, kd = controller.gains
    lo, hi = controller.bounds(robot)
    n = 6 + C.n_arm
    from offshore_crane.simulation.rk4 import workspaces

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
    ``swing``, the hanging load's (:func:`offshore_crane.simulation.swing.warm_up`):
    ``[(name, seconds), ...]``."""
    import time

    from offshore_crane.robot import load_robot
    from offshore_crane.motion.trajectories import table1
    from offshore_crane.simulation.swing import warm_up as warm_up_swing

    robot = robot or load_robot()
    t0 = time.perf_counter()
    simulate(robot.without_hanging_payload(), 2e-3, table1, step=1e-3)
    return [("simulation loop", time.perf_counter() - t0)] + (
        warm_up_swing(robot) if swing else [])
