"""The forward simulation with the hanging load: the robot under a controller while its
payload swings (docs/cable.md, "Simulation and anti-sway").

The state has 11 coordinates, q1..q9 and the sway angles φ1, φ2 (``docs/cable.md``),
and their rates: the loops stay closed by construction and the cable is a rigid,
inextensible link. The accelerations solve ``M a + h = [A X; −c φ̇] + Jᵀ f``, where M and h
come from the explicit Kane pass on the arm chain continued by the sway joints and the
payload (:func:`offshore_crane.dynamics.cable.kernels.accelerations`, the same formulas
as the 9-coordinate equations of motion) and ``Jᵀ f`` is the payload's air drag
(``payload.drag_area``; J its velocity's partials). Classical RK4 at a fixed step, driven from Python (one
compiled call per stage), the reference evaluated at every stage time.

Controllers (:class:`~offshore_crane.simulation.control.Controller`):

- ``"computed-torque"`` reads the sway: ``X`` makes the robot's accelerations
  ``q̈_ref + Kd ė + Kp e`` at the measured state, with the sway's accelerations from the
  pendulum's equations under that motion and the cable's pull in X
  (:func:`~offshore_crane.dynamics.cable.kernels.computed_torque`); with an exact model
  the tracking error obeys ``ë + Kd ė + Kp e = 0`` however the load swings;
- ``"none"``: X = 0.

Anti-sway (``Controller(anti_sway=ζ)``): suspension-point velocity feedback, the classic
law that damps a pendulum by moving its pivot along the load's relative velocity
(Abdel-Rahman, Nayfeh & Masoud, "Dynamics and control of cranes: a review", Journal of
Vibration and Control 9(7), 2003, Sec. on open- and closed-loop pendulation control). For
a pendulum of length L on a pivot accelerated by ``a``, the load's horizontal offset d
obeys ``d̈ + ω0² d = −a`` (small sway, ω0 = √(g/L)); with ``a = k ḋ`` it becomes
``d̈ + k ḋ + ω0² d = 0``, a damping ratio ``ζ = k / (2 ω0)``. The law shifts the platform's
horizontal reference by δ (x, y), ``δ̈ = 2 ζ ω0 ḋ − ω_c² δ − 2 ω_c δ̇``, which the
computed-torque loop tracks (its bandwidth, 20 rad/s by default, is well above ω0); the
centring term (ω_c = ω0 / 10, critically damped) brings the platform back to its
reference once the swing has died out.
"""

from __future__ import annotations

import numpy as np

from offshore_crane import progress
from offshore_crane.simulation.control import Controller
from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError
from offshore_crane.validation import as_gravity
from offshore_crane.simulation.record import (DIVERGED_STATE, divergence, diverging,
                                              finite_rows, stopped)

#: Centring frequency of the anti-sway reference shift, as a fraction of ω0 = √(g/L).
CENTRING = 0.1


def simulate_swing(robot, duration: float, reference, q0=None, qd0=None, controller=None, *,
                   gravity=GRAVITY, step: float = 1e-3, rate: float | None = None,
                   initial=(0.0, 0.0), initial_rate=(0.0, 0.0), limits: bool = True,
                   t0: float = 0.0):
    """Simulate the robot with its payload swinging on its cable.

    Args:
        robot: With a payload on a cable (``payload.cable_length > 0``).
        duration, reference, q0, qd0, gravity, step, rate, limits, t0: As
            :func:`offshore_crane.simulation.rigid.simulate`.
        controller: :class:`~offshore_crane.simulation.control.Controller` (``"computed-torque"``
            or ``"none"``; optional ``anti_sway``, control rate, saturation, a model
            that differs from the plant (with a cable too)).
        initial, initial_rate: ``(2,)`` sway φ1, φ2 [rad] and rates [rad/s] at ``t0``.

    Returns:
        :class:`~offshore_crane.simulation.rigid.SimulationResult` with ``sway``, ``sway_rate``
        ``(N, 2)`` and ``tension`` ``(N,)`` [N].

    Raises:
        InputError: bad arguments, a law or option the hanging load does not take.
        SimulationError: the run stopped (workspace, singular, diverged, slack cable);
            ``error.result`` keeps every sample computed before.
    """
    from offshore_crane.dynamics.cable import cable_robot
    from offshore_crane.validation import as_pair
    from offshore_crane.dynamics.runtime import compiled_kernels
    from offshore_crane.dynamics.cable import kernels as ck
    from offshore_crane.dynamics.constants import cable_arrays
    from offshore_crane.dynamics.integrator import rk4_step
    from offshore_crane.simulation.record import (SimulationResult, initial_state,
                                                  reference_grid, steps)

    controller = controller or Controller()
    robot = cable_robot(robot)
    model = cable_robot(controller.model) if controller.model is not None else robot
    if controller.law not in ("computed-torque", "none"):
        raise InputError(f"controller {controller.law!r}: with a payload on a cable the "
                         "simulation takes 'computed-torque' (which reads the sway) or "
                         "'none'", name="controller")
    if any(np.any(n) for n in controller.noise):
        raise InputError("measurement noise is not simulated with a payload on a cable: "
                         "leave noise_q, noise_qd at zero", name="noise_q")
    n_steps, out_every, hold = steps(duration, step, rate, controller.rate)
    g = as_gravity(gravity)
    tt, qr, qdr, qddr = reference_grid(reference, t0, step, n_steps)
    q0, qd0 = initial_state(q0, qd0, qr[0], qdr[0])
    sway0, rate0 = as_pair(initial, "initial", "rad"), as_pair(initial_rate, "initial_rate",
                                                            "rad/s")
    compiled_kernels()
    plant, ctrl = cable_arrays(robot), cable_arrays(model)
    damp_p, damp_c = robot.hybrid.sway_damping, model.hybrid.sway_damping
    drag_p, drag_c = float(robot.hybrid.drag), float(model.hybrid.drag)
    kp, kd = controller.gains
    lo, hi = controller.bounds(robot)
    w0 = np.sqrt(np.linalg.norm(g) / model.hybrid.cable_length)
    k_as = 2.0 * controller.anti_sway * w0 if controller.anti_sway else 0.0
    wc = CENTRING * w0
    ct = controller.law == "computed-torque"
    a = np.empty(11)
    en = np.empty(2)
    pay = np.empty(6)

    def law(i, y, delta_dd):
        """X commanded at stage-grid point i and state y (the shifted reference)."""
        if not ct:
            return np.zeros(9)
        qref, qdref, qddref = qr[i].copy(), qdr[i].copy(), qddr[i].copy()
        qref[:2] += y[22:24]
        qdref[:2] += y[24:26]
        qddref[:2] += delta_dd
        cmd = qddref + kd * (qdref - y[11:20]) + kp * (qref - y[:9])
        X = np.empty(9)
        ck.computed_torque(ctrl.flat, ctrl.layout, ctrl.prismatic, damp_c, drag_c, y[:11],
                           y[11:22], cmd, g, X)
        return X

    def shift_dd(y):
        """δ̈ of the anti-sway reference shift (zeros without anti-sway)."""
        if not k_as:
            return np.zeros(2)
        ck.payload(ctrl.flat, ctrl.layout, ctrl.prismatic, y[:11], y[11:22], pay)
        return k_as * pay[:2] - wc * wc * y[22:24] - 2.0 * wc * y[24:26]

    def f(i, y, X_held):
        dd = shift_dd(y)
        X_cmd = law(i, y, dd) if X_held is None else X_held
        X = np.clip(X_cmd, lo, hi)
        ok = ck.accelerations(plant.flat, plant.layout, plant.prismatic, damp_p, drag_p,
                              y[:11], y[11:22], X, g, a, en)
        return np.concatenate([y[11:22], a, y[24:26], dd]), X_cmd, X, ok

    y = np.concatenate([q0, sway0, qd0, rate0, np.zeros(4)])
    n_out = n_steps // out_every + 1
    rec = {k: np.full((n_out, 9), np.nan) for k in ("q", "qd", "qdd", "q_ref", "qd_ref",
                                                    "X_cmd", "X")}
    sway, sway_rate = np.full((n_out, 2), np.nan), np.full((n_out, 2), np.nan)
    sway_acc = np.full((n_out, 2), np.nan)
    sat = np.zeros((n_out, 9), dtype=bool)
    E = np.full(n_out, np.nan)
    held = None
    stop, done = None, 0
    with progress.bar(n_out, "sample", "simulate") as shown:
        for s in range(n_steps + 1):
            if hold and s % hold == 0:
                held = law(2 * s, y, shift_dd(y))
            k1, X_cmd, X, ok = f(2 * s, y, held)
            if s % out_every == 0:
                k = s // out_every
                rec["q"][k], rec["qd"][k], rec["qdd"][k] = y[:9], y[11:20], k1[11:20]
                sway[k], sway_rate[k], sway_acc[k] = y[9:11], y[20:22], k1[20:22]
                rec["q_ref"][k], rec["qd_ref"][k] = qr[2 * s], qdr[2 * s]
                rec["X_cmd"][k], rec["X"][k] = X_cmd, X
                sat[k] = (X_cmd < lo) | (X_cmd > hi)
                E[k] = en.sum()
                done = k + 1
                shown.update()
                cause = _stop(ok, y, k1)
                if cause is not None:
                    stop = (k, cause)
                    break
            if s == n_steps:
                break
            y = rk4_step(lambda i, x: f(i, x, held)[0], 2 * s, y, k1, step)
    t_out = tt[::2][::out_every][:n_out]
    res = SimulationResult(t=t_out, **rec, saturated=sat, energy=E, power=np.full(n_out, 0.0),
                           integrator="rk4", step=step, sway=sway, sway_rate=sway_rate,
                           tension=np.full(n_out, np.nan))
    res = res.truncated(done)
    _finish(robot, res, sway_acc[:done], g, limits)
    early = _slack_or_workspace(robot, res.truncated(finite_rows(res)), limits)  # first wins
    if early is not None and (stop is None or early[0] < stop[0]):
        stop = early
    if stop is not None:
        k, cause = stop
        when = t0 + (k if k < len(t_out) else len(t_out) - 1) * step * out_every
        res = res.truncated(min(k, finite_rows(res)))
        if cause is DIVERGED or diverging(res):
            res = res.truncated(finite_rows(res))
            cause = divergence(res)
        raise stopped(res, when, cause)
    return res


DIVERGED = "diverged"   # _stop's mark for a non-finite state, worded by record.divergence


def _stop(ok, y, k1):
    """Why the run stops at this sample, or None: :data:`DIVERGED`, or a singular mass
    matrix. A coordinate beyond ``record.DIVERGED_STATE`` counts as diverged too."""
    if not (np.isfinite(y).all() and np.isfinite(k1).all()):
        return DIVERGED
    if (np.abs(y[:11]) > DIVERGED_STATE).any():
        return DIVERGED
    if not ok:
        return ("the mass matrix became singular (the attitude coordinates at q5 = ±π/2, "
                "or the sway at cos φ2 = 0)")
    return None


def _finish(robot, res, sway_acc, g, limits) -> None:
    """The tension, the actuators' power and the energy's gravitational part are filled in
    from the recorded samples (one pass of the cable's Kane kernel, on blocks of samples
    vectorised across them)."""
    from offshore_crane.dynamics.cable import kernels as ck
    from offshore_crane.dynamics.constants import cable_arrays
    from offshore_crane.dynamics.lanes import kane_kernel
    from offshore_crane.robot.kinematics.formulas import FULL
    from offshore_crane.simulation.record import actuator_power
    from offshore_crane.robot.kinematics import workspace as ws

    n = len(res)
    if n == 0:
        return
    arrays = cable_arrays(robot)
    q11 = np.ascontiguousarray(np.concatenate([res.q, res.sway], 1))
    qd11 = np.ascontiguousarray(np.concatenate([res.qd, res.sway_rate], 1))
    qdd11 = np.ascontiguousarray(np.concatenate([res.qdd, sway_acc], 1))
    F = np.full((n, 6), np.nan)              # a non-finite sample is skipped: NaN row
    kane = kane_kernel(arrays, FULL, cable=True) or ck.kane      # blocks of samples
    kane(arrays.flat, arrays.layout, arrays.prismatic, robot.hybrid.sway_damping, q11, qd11,
         qdd11, g, False, False, np.inf, np.inf, 0, n, np.empty((n, 9)), np.empty((3, 1)),
         ws.new_health(), F)
    if robot.hybrid.drag > 0.0:             # the pull along the cable takes the drag too
        from offshore_crane.dynamics.cable.forces import hanging_drag

        f, _, _, _, e = hanging_drag(robot, arrays.kane, res.q, res.qd, res.qdd,
                                     np.hstack([res.sway, res.sway_rate]), None)
        F[:, 3] += np.einsum("ij,ij->i", f, e)
    res.tension = F[:, 3]
    res.power = actuator_power(robot, res.q, res.qd, res.X)


def _slack_or_workspace(robot, res, limits):
    """``(sample, cause)`` of the first slack-cable sample or workspace violation."""
    from offshore_crane.simulation.record import workspace_stop

    slack = ~(res.tension > 0.0)
    first = None
    if slack.any():
        k = int(np.argmax(slack))
        first = (k, f"the cable went slack (tension {res.tension[k]:.4g} N: a cable cannot "
                    "push, the pendulum model no longer holds)")
    outside = workspace_stop(robot, res, limits)
    if outside is not None and (first is None or outside[0] < first[0]):
        first = outside
    return first


def warm_up(robot=None) -> list[tuple[str, float]]:
    """Compile (or load from the cache) the simulation loop with a hanging load (the
    anti-sway law included): ``[(name, seconds)]``."""
    import time

    from offshore_crane.dynamics.cable import cable_robot
    from offshore_crane.robot import load_robot

    t0 = time.perf_counter()
    robot = robot or load_robot()
    if robot.hybrid.cable is None:
        robot = cable_robot(robot, length=1.0, mass=1.0)
    home = robot.home_pose()

    def rest(tt):
        q = np.repeat(home[None, :], len(tt), axis=0)
        return q, 0 * q, 0 * q

    simulate_swing(robot, 2e-3, rest, controller=Controller(anti_sway=0.1), step=1e-3,
                   limits=False)
    return [("hanging-load simulation loop", time.perf_counter() - t0)]
