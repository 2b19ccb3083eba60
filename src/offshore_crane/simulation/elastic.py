"""The forward simulation with the payload on an elastic cable, a winch and motion
compensation: the robot under a controller while its load flies on the cable (docs/cable.md,
"Forward simulation of the real lift").

The plant is the robot without its hanging payload, pulled at the tip by the cable, and
the payload a point mass with three free coordinates:

- the cable's tension ``T = EA s / L + c ṡ`` while taut and pulling, else 0 (the formulas
  of :func:`offshore_crane.dynamics.sway.cable_tension`, ``L(t)`` the winch's length);
- the payload: ``m p̈ = m g − T ρ̂ + F_s + F_d`` (``ρ`` from the tip to the payload; the
  sway damping ``F_s`` while the cable pulls and the air's drag ``F_d``, as the elastic
  cable's inverse dynamics, :mod:`offshore_crane.dynamics.cable.elastic`);
- the robot: its equations of motion with the cable's pull ``P = T ρ̂ − F_s`` on it at the
  payload's place (the damping's moment is the tip's), written as actuator forces:
  ``a = FD(q, q̇, X − ΔX(P))``, with ``ΔX(P)`` the forces the pull ``P`` alone asks of the
  actuators (the Kane pass with the pull,
  :func:`offshore_crane.dynamics.cable.forces.kane_forces`, at zero acceleration less the
  same without pull: exact, the pull enters the equations linearly).

Classical RK4 at a fixed step from Python, one compiled inverse and one forward dynamics
call per stage. The step must resolve the cable's axial period ``2π √(m L / EA)``: at
least :data:`STEPS_PER_PERIOD` steps in the shortest one, or the run is refused.

Controllers: ``"computed-torque"`` with the cable's pull measured at the tip (a load cell):
``X`` = the Kane pass with that pull at ``q̈_ref + Kd ė + Kp e``, so that with an exact
model the tracking error obeys ``ë + Kd ė + Kp e = 0`` however the load flies; ``"none"``:
X = 0.
"""

from __future__ import annotations

import math

import numpy as np

from offshore_crane import progress
from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError
from offshore_crane.validation import as_gravity

#: Fewest RK4 steps in the cable's shortest axial period (the elastic inverse dynamics
#: takes 50; RK4's phase error there is ~1e-7 a period).
STEPS_PER_PERIOD = 20


def simulate_elastic(robot, duration: float, reference, q0=None, qd0=None, controller=None,
                     *, ea: float, damping: float = 0.0, hoist=None, gravity=GRAVITY,
                     step: float = 1e-3, rate: float | None = None, initial=None,
                     initial_velocity=(0.0, 0.0, 0.0), limits: bool = True, t0: float = 0.0):
    """Simulate the robot with its payload on an elastic cable.

    Args:
        robot: With a payload on a cable (``payload.cable_length`` the unstretched length
            without a winch, ``payload.mass``).
        duration, reference, q0, qd0, gravity, step, rate, limits, t0: As
            :func:`offshore_crane.simulation.rigid.simulate`.
        controller: :class:`~offshore_crane.simulation.control.Controller`
            (``"computed-torque"`` or ``"none"``; no noise, no model mismatch, no
            anti-sway).
        ea, damping: The cable's EA [N] and axial damping [N·s/m] (the sway damping
            and the payload's drag are the robot description's: ``payload.sway_damping``,
            ``payload.drag_area``, ``payload.air_density``).
        hoist: The winch ``hoist(t) -> (L, L̇, L̈)`` [m, m/s, m/s²], or None.
        initial, initial_velocity: ``(3,)`` the payload from the tip [m] and relative to
            it [m/s] at ``t0``, base axes (default: hanging along g at its static
            stretch, at rest relative to the tip).

    Returns:
        :class:`~offshore_crane.simulation.rigid.SimulationResult` with ``tension``
        ``(N,)`` [N] and ``info["payload"]``, ``info["payload_velocity"]`` ``(N, 3)``
        (base frame), ``info["length"]`` ``(N,)`` the cable's length [m].

    Raises:
        InputError: bad arguments, a step too long for the cable's axial period, a law
            or option this simulation does not take.
        SimulationError: the run stopped (workspace, diverged); ``error.result`` keeps
            every sample computed before.
    """
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.cable.forces import kane_forces
    from offshore_crane.dynamics.cable.elastic import check_cable, drag_forces
    from offshore_crane.dynamics.constants import cable_arrays
    from offshore_crane.dynamics.cable.grid import cable_robot
    from offshore_crane.dynamics.cable.tip import tip_positions
    from offshore_crane.dynamics.forward import forward_dynamics
    from offshore_crane.dynamics.integrator import rk4_step
    from offshore_crane.robot.kinematics.workspace import Thresholds
    from offshore_crane.simulation.control import Controller
    from offshore_crane.simulation.record import (SimulationResult, actuator_power,
                                                  initial_state, reference_grid, steps,
                                                  workspace_stop)

    controller = controller or Controller()
    if controller.law not in ("computed-torque", "none"):
        raise InputError(f"controller {controller.law!r}: on an elastic cable the "
                         "simulation takes 'computed-torque' (with the cable's pull "
                         "measured at the tip) or 'none'", name="controller")
    if (any(np.any(n) for n in controller.noise) or controller.model is not None
            or controller.anti_sway):
        raise InputError("on an elastic cable the simulation takes an exact, noise-free "
                         "computed torque: leave noise_q, noise_qd, model and anti_sway "
                         "out", name="controller")
    check_cable(ea, damping)
    robot = cable_robot(robot)
    empty = robot.without_hanging_payload()
    m = float(robot.hybrid.cable.mass[-1])
    check_cable(ea, damping, m)
    g = as_gravity(gravity)
    gn = float(np.linalg.norm(g))
    n_steps, out_every, hold = steps(duration, step, rate, controller.rate)
    tt, qr, qdr, qddr = reference_grid(reference, t0, step, n_steps)
    L0 = float(robot.hybrid.cable_length)
    Lg = (np.column_stack([np.full(len(tt), L0), np.zeros(len(tt)), np.zeros(len(tt))])
          if hoist is None else np.column_stack([np.asarray(x, float).reshape(len(tt))
                                                 for x in hoist(tt)]))
    period = 2.0 * math.pi * math.sqrt(m * float(Lg[:, 0].min()) / ea)
    if step > period / STEPS_PER_PERIOD:
        raise InputError(f"step = {step:g} s is too long for the cable's axial period "
                         f"{period * 1e3:.3g} ms: give step <= "
                         f"{period / STEPS_PER_PERIOD:.3g} s ({STEPS_PER_PERIOD} steps a "
                         "period)", name="step")
    q0, qd0 = initial_state(q0, qd0, qr[0], qdr[0])
    p_tip, v_tip = (x[0] for x in tip_positions(robot, q0[None], qd0[None]))
    rho0 = (g / gn * Lg[0, 0] * (1.0 + m * gn / ea) if initial is None
            else np.asarray(initial, dtype=float).reshape(3))
    v0 = np.asarray(initial_velocity, dtype=float).reshape(3)
    kp, kd = controller.gains
    lo, hi = controller.bounds(robot)
    ct = controller.law == "computed-torque"
    B = backends.NUMPY
    zero6 = np.zeros((1, 6))
    thr = Thresholds()

    C, one = cable_arrays(robot).kane, backends.PYTHON     # one sample: Python floats
    c1, c2 = (float(c) for c in robot.hybrid.sway_damping)
    drag, still = float(robot.hybrid.drag), [0.0] * 9

    def pulled(q, qd, qdd, pull, at):
        """X of the robot moving at qdd with ``pull`` [N] on it at ``at`` [m] from the tip
        (the Kane pass)."""
        return kane_forces(robot, np.zeros(1), q[None], qd[None], qdd[None], zero6, g,
                           False, False, thr, P=pull[None], at=at[None])[0][0]

    def cable(i, y):
        """``(pull on the robot (3,), where it acts (ρ, 3,), tension, the cable's, the
        damping's and the air's force on the payload (3,))`` at stage point i, state y."""
        pt, vt = (x[0] for x in tip_positions(robot, y[None, :9], y[None, 12:21]))
        rho, rhod = y[9:12] - pt, y[21:24] - vt
        with np.errstate(divide="ignore", invalid="ignore"):
            T, s, _ = B.cable_tension(tuple(rho[:, None]), tuple(rhod[:, None]),
                                      Lg[i:i + 1, 0], Lg[i:i + 1, 1], float(ea),
                                      float(damping))
        T = float(T[0]) if (s[0] > 0 and T[0] > 0) else 0.0
        pull = T * rho / np.linalg.norm(rho)
        if T > 0.0 and c1 + c2 > 0.0:       # the sway damping, carried by the cable
            Rt, w = one.tip_motion(C, y[:9].tolist(), y[12:21].tolist(), still)[:2]
            pull = pull - np.array(one.sway_damping_force(Rt, w, tuple(rho.tolist()),
                                                          tuple(rhod.tolist()), c1, c2),
                                   dtype=float)
        return pull, rho, T, drag_forces(y[None, 21:24], drag)[0] - pull

    def law(i, y, pull, at):
        if not ct:
            return np.zeros(9)
        cmd = qddr[i] + kd * (qdr[i] - y[12:21]) + kp * (qr[i] - y[:9])
        return pulled(y[:9], y[12:21], cmd, pull, at)

    def f(i, y, X_held):
        pull, at, T, force = cable(i, y)
        X_cmd = law(i, y, pull, at) if X_held is None else X_held
        X = np.clip(X_cmd, lo, hi)
        rest = np.zeros(9)
        shift = (pulled(y[:9], y[12:21], rest, pull, at)
                 - pulled(y[:9], y[12:21], rest, 0 * pull, at))
        a = forward_dynamics(empty, y[:9], y[12:21], X - shift, g)
        a_p = g + force / m
        return np.concatenate([y[12:21], y[21:24], a, a_p]), X_cmd, X, T

    y = np.concatenate([q0, p_tip + rho0, qd0, v_tip + v0])
    n_out = n_steps // out_every + 1
    rec = {k: np.full((n_out, 9), np.nan) for k in ("q", "qd", "qdd", "q_ref", "qd_ref",
                                                    "X_cmd", "X")}
    payload, payload_v = np.full((n_out, 3), np.nan), np.full((n_out, 3), np.nan)
    tension, length = np.full(n_out, np.nan), np.full(n_out, np.nan)
    sat = np.zeros((n_out, 9), dtype=bool)
    held, done, stop = None, 0, None
    with progress.bar(n_out, "sample", "simulate") as shown:
        for s_ in range(n_steps + 1):
            if hold and s_ % hold == 0:
                held = law(2 * s_, y, *cable(2 * s_, y)[:2])
            k1, X_cmd, X, T = f(2 * s_, y, held)
            if s_ % out_every == 0:
                k = s_ // out_every
                rec["q"][k], rec["qd"][k], rec["qdd"][k] = y[:9], y[12:21], k1[12:21]
                payload[k], payload_v[k] = y[9:12], y[21:24]
                rec["q_ref"][k], rec["qd_ref"][k] = qr[2 * s_], qdr[2 * s_]
                rec["X_cmd"][k], rec["X"][k] = X_cmd, X
                sat[k] = (X_cmd < lo) | (X_cmd > hi)
                tension[k], length[k] = T, Lg[2 * s_, 0]
                done = k + 1
                shown.update()
                if not (np.isfinite(y).all() and np.isfinite(k1).all()):
                    stop = (k, "the state is not finite")
                    break
            if s_ == n_steps:
                break
            y = rk4_step(lambda i, x: f(i, x, held)[0], 2 * s_, y, k1, step)
    t_out = tt[::2][::out_every][:n_out]
    res = SimulationResult(t=t_out, **rec, saturated=sat, energy=np.full(n_out, np.nan),
                           power=np.full(n_out, np.nan), integrator="rk4", step=step,
                           tension=tension,
                           info={"payload": payload, "payload_velocity": payload_v,
                                 "length": length, "axial_period": period})
    res = res.truncated(done)
    for key in ("payload", "payload_velocity", "length"):
        res.info[key] = res.info[key][:done]
    res.power = actuator_power(robot, res.q, res.qd, res.X)
    first = workspace_stop(robot, res, limits)
    if first is not None and (stop is None or first[0] < stop[0]):
        stop = first
    if stop is not None:
        from offshore_crane.simulation.record import stopped

        k, cause = stop
        res = res.truncated(k)
        raise stopped(res, t0 + k * step * out_every, cause)
    return res
