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

A controller may also be any Python callable ``law(t, q, qd, q_ref, qd_ref, qdd_ref) ->
X (9,)`` [s, m, rad, ... → N·m, N]: the same RK4 then runs in Python, one forward-dynamics
call and one call of the law per stage (slower than the compiled built-in laws; X clipped
to the robot description's capacities, the time saturated reported).

The simulation stops at the first sample that leaves the workspace, reaches a singular
configuration (the mass matrix at the attitude singularity) or diverges (a non-finite
state): :class:`~offshore_crane.errors.SimulationError` names the time and the cause and
carries the :class:`SimulationResult` up to that sample (``error.result``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from offshore_crane.simulation.control import LAW_CODES, Controller
from offshore_crane import progress
from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError, SimulationError
from offshore_crane.validation import as_gravity
from offshore_crane.simulation.record import (LawParameters, Packed, Recording, SimulationResult,
                                              StageGrid, divergence, diverging, finite_rows,
                                              initial_state, reference_grid, steps, stopped)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from offshore_crane.robot import Robot

#: A reference motion: ``reference(t (n,) [s]) -> (q, qd, qdd)``, each ``(n, 9)``.
Reference = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
#: A Python control law ``law(t [s], q, qd, q_ref, qd_ref, qdd_ref (9,)) -> X (9,)``.
Law = Callable[..., np.ndarray]

INTEGRATORS = ("rk4", "dop853")
#: Stop codes of the compiled loop.
OK, WORKSPACE, SINGULAR, DIVERGED = 0, 1, 2, 3


# --------------------------------------------------------------------------- compiled
def _loop():
    """The compiled RK4 loop, its control law and accelerations (:mod:`.rk4`, which
    imports Numba: loaded on first use)."""
    from offshore_crane.simulation import rk4 as _rk4

    return _rk4.run, _rk4.law, _rk4.accel, _rk4.SHARED


# --------------------------------------------------------------------------- public
def simulate(robot: Robot, duration: float, reference: Reference, q0: ArrayLike | None = None,
             qd0: ArrayLike | None = None, controller: Controller | Law | None = None, *,
             gravity: ArrayLike = GRAVITY, step: float = 1e-3, rate: float | None = None,
             integrator: str = "rk4", limits: bool = True, rtol: float = 1e-10,
             atol: float = 1e-12, t0: float = 0.0, **cable) -> SimulationResult:
    """Simulate the robot from ``(q0, q̇0)`` for ``duration`` seconds.

    Args:
        robot: From :func:`offshore_crane.load_robot` (the plant).
        duration: [s] > 0.
        reference: A callable ``reference(t (n,)) -> (q, qd, qdd)`` each ``(n, 9)``
            (e.g. :func:`offshore_crane.motion.trajectories.table1`), evaluated at every stage.
        q0, qd0: ``(9,)`` initial state (default: the reference at ``t0``).
        controller: :class:`~offshore_crane.simulation.control.Controller` (default computed torque).
        gravity: ``(3,)`` [m/s²].
        step: Integration step [s] (RK4).
        rate: Output sampling rate [Hz] (default every step); 1/rate must be a multiple
            of ``step``.
        integrator: ``"rk4"`` or ``"dop853"``.
        limits: Stop at the first sample outside the workspace.
        rtol, atol: Tolerances of DOP853.
        t0: Start time [s].
        **cable: With a payload on a cable: ``initial``, ``initial_rate`` (2,) of the
            sway [rad, rad/s] (:func:`offshore_crane.simulation.swing.simulate_swing`,
            which then runs).

    Returns:
        :class:`SimulationResult`.

    Raises:
        InputError: bad arguments (one-line message).
        SimulationError: the run stopped early (``error.result`` holds what was computed).
    """
    controller = controller or Controller()
    if not isinstance(controller, Controller):
        if not callable(controller):
            raise InputError(f"controller must be a Controller or a callable law(t, q, qd, "
                             f"q_ref, qd_ref, qdd_ref) -> X, got {controller!r}",
                             name="controller")
        if integrator != "rk4" or robot.hybrid.cable is not None or cable:
            raise InputError("a Python controller runs with RK4 on a robot without a "
                             "hanging load", name="controller")
        return _python_law(robot, duration, reference, q0, qd0, controller, gravity, step,
                           rate, limits, t0)
    if robot.hybrid.cable is not None or cable:
        if integrator != "rk4":
            raise InputError(f"integrator {integrator!r}: with a payload on a cable the "
                             "simulation runs RK4", name="integrator")
        from offshore_crane.simulation.swing import simulate_swing

        return simulate_swing(robot, duration, reference, q0, qd0, controller,
                              gravity=gravity, step=step, rate=rate, limits=limits, t0=t0,
                              **cable)
    if controller.anti_sway:
        raise InputError("anti_sway damps the swing of a payload on a cable, but this "
                         "robot's payload is welded (payload.cable_length = 0)",
                         name="anti_sway")
    if integrator not in INTEGRATORS:
        raise InputError(f"unknown integrator {integrator!r}: use one of "
                         f"{', '.join(INTEGRATORS)}", name="integrator")
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
    kind = LAW_CODES[controller.law]
    if (controller.law == "computed-torque" and hold == 0 and all(
            np.array_equal(a, b) for a, b in ((plant.flat, model.flat), (plant.layout,
                                              model.layout), (plant.prismatic,
                                                              model.prismatic)))):
        kind = _loop()[3]                          # one explicit pass a stage serves both
    rec = Recording.empty(n_out)
    health = ws.new_health()
    status = np.zeros(3, dtype=np.int64)
    stop = progress.stop_flag()
    progress.run_polled(
        lambda: run(Packed(plant.flat, plant.layout, plant.prismatic),
                    Packed(model.flat, model.layout, model.prismatic), g, step, n_steps,
                    out_every, StageGrid(qr, qdr, qddr),
                    LawParameters(kind, kp, kd, hold, nq, nqd, lo, hi),
                    limits, q0, qd0, rec, health, status, stop),
        lambda: status[2], n_out, "sample", "simulate", stop)
    n_done = int(status[2])
    t_out = tt[::2][::out_every][:n_out]
    res = SimulationResult(t=t_out, **rec._asdict(), integrator="rk4", step=step)
    if status[0] != OK:
        k = int(status[1])
        when = t0 + k * step
        res = res.truncated(n_done)
        if status[0] == WORKSPACE:
            try:
                ws.check_limits(health, plant.limits, res.q[-1:], None)
                cause = "left the workspace"
            except Exception as exc:          # the WorkspaceError's text names the limit
                cause = str(exc).split(" at sample")[0] + " (outside its limits)"
        diverged = status[0] == DIVERGED or diverging(res)
        res = res.truncated(finite_rows(res))
        if diverged:
            cause = divergence(res)
        elif status[0] == SINGULAR:
            cause = ("the mass matrix became singular (attitude singularity, "
                     f"q5 = {res.q[-1, 4]:.4g} rad)")
        raise stopped(res, when, cause)
    return res


def _python_law(robot, duration, reference, q0, qd0, law, gravity, step, rate, limits, t0):
    """RK4 with a Python controller (module docstring): the law and Kane's forward
    dynamics (:func:`offshore_crane.forward_dynamics`, its one-sample path) at every stage."""
    from offshore_crane.dynamics.forward import forward_dynamics
    from offshore_crane.dynamics.integrator import rk4_step
    from offshore_crane.simulation.record import actuator_power
    from offshore_crane.validation import as_samples

    n_steps, out_every, _ = steps(duration, step, rate, None)
    g = as_gravity(gravity)
    tt, qr, qdr, qddr = reference_grid(reference, t0, step, n_steps)
    y = np.concatenate(initial_state(q0, qd0, qr[0], qdr[0]))
    lo, hi = Controller().bounds(robot)

    def f(i, y):
        q, qd = y[:9].copy(), y[9:].copy()
        X_cmd = as_samples("X returned by the controller", law(tt[i], q, qd, qr[i], qdr[i],
                                                                qddr[i]))[0][0]
        X = np.clip(X_cmd, lo, hi)
        return np.concatenate([qd, forward_dynamics(robot, q, qd, X, gravity=g)]), X_cmd, X

    n_out = n_steps // out_every + 1
    rec = {k: np.full((n_out, 9), np.nan) for k in ("q", "qd", "qdd", "q_ref", "qd_ref",
                                                    "X_cmd", "X")}
    for s in range(n_steps + 1):
        k1, X_cmd, X = f(2 * s, y)
        if s % out_every == 0:
            k = s // out_every
            rec["q"][k], rec["qd"][k], rec["qdd"][k] = y[:9], y[9:], k1[9:]
            rec["q_ref"][k], rec["qd_ref"][k] = qr[2 * s], qdr[2 * s]
            rec["X_cmd"][k], rec["X"][k] = X_cmd, X
        if s == n_steps:
            break
        y = rk4_step(lambda i, x: f(i, x)[0], 2 * s, y, k1, step)
    res = SimulationResult(t=tt[::2][::out_every][:n_out], **rec,
                           saturated=(rec["X_cmd"] < lo) | (rec["X_cmd"] > hi),
                           energy=np.full(n_out, np.nan), power=np.full(n_out, np.nan),
                           integrator="rk4", step=step, info={"controller": "python"})
    res.power = actuator_power(robot, res.q, res.qd, res.X)
    if limits:
        from offshore_crane.robot.kinematics import check_workspace

        check_workspace(robot, res.q, res.t)
    return res


def _dop853(robot, t_out, reference, q0, qd0, controller, g, limits, rtol, atol, out_every):
    """The adaptive reference integrator (continuous controller, driven from Python)."""
    from offshore_crane.errors import require

    integrate = require("scipy.integrate", "scipy", "The DOP853 integrator")
    _, law, accel, _ = _loop()
    from offshore_crane.dynamics.constants import robot_arrays

    plant = robot_arrays(robot)
    from offshore_crane.dynamics import compiled as c

    C = plant.kane
    Cc_arrays = robot_arrays(controller.model or robot)
    Cc = Cc_arrays.kane
    kp, kd = controller.gains
    lo, hi = controller.bounds(robot)
    n = 6 + C.n_arm
    ws = (np.zeros(9), np.empty((6, 6)), np.zeros((9, 9)), np.zeros((9, 9)),
          np.empty((max(C.n_arm, 1), 27)), np.empty((9, 3)), np.empty((9, 3)),
          np.empty((9, 3)), np.zeros((7, 6)), np.empty((1, 3)), np.empty(9), np.empty(9),
          np.zeros(9))
    na = C.n_arm
    wl = (np.zeros(9), np.empty((6, 6)), np.zeros((9, 9)), np.empty((max(na, 1), 27)),
          np.empty((9, 3)), np.empty((9, 3)), np.empty((9, 3)), np.zeros((7, 6)),
          np.empty((1, 3)), np.empty((6, 6)), np.empty(6), np.empty(6), np.empty((6, 13)),
          np.zeros(9), np.empty(9), np.empty(9), np.empty(9), np.empty(9), np.empty(9))
    gt = tuple(float(x) for x in g)
    X = np.empty(9)
    qdd = np.empty(9)
    kind = LAW_CODES[controller.law]
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
