"""The RK4 driver: one loop that runs any plant (:mod:`offshore_crane.simulation.plants`)
under any law (:mod:`offshore_crane.simulation.laws`) with the sensors and actuators
between them (:mod:`offshore_crane.simulation.instruments`), and records the run.

The integrated state is ``y = (plant state, law state, actuator lag state)``. Classical
RK4 at a fixed step on the grid of half steps (:func:`offshore_crane.dynamics.integrator.
rk4_step`, the one text of the tableau), the reference evaluated at every stage time.

- Continuous control (no control rate): the law is evaluated at every stage from the
  plant's state, and its own state integrated with its rate at every stage.
- Sampled control (a rate; ``hold`` steps a period): at each control instant the sensors
  measure (delay, noise, quantisation), the law is evaluated once, the rate limit applied,
  and the command held over the period (zero-order hold); a law's state advances by its
  rate at the instant held over the period (forward Euler: the discrete controller).
- The actuators' lag integrates ``τ Ẋ_a = X_held − X_a`` at every stage; the capacities
  clip what reaches the plant.

At every output sample it records q, q̇, q̈, the reference, the commanded and applied
forces (saturation flagged) and the plant's own arrays, and checks the stops: a
non-finite state (:attr:`~offshore_crane.stops.StopCause.DIVERGED`) and the plant's own
(:meth:`~offshore_crane.simulation.plants.Plant.check`); the plant's ``finish`` finds
those seen on the record (a workspace violation, a slack cable). A stop raises
:class:`~offshore_crane.errors.SimulationError` carrying every sample before it.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np

from offshore_crane import progress
from offshore_crane.errors import InputError
from offshore_crane.stops import StopCause


@dataclass(frozen=True)
class Timing:
    """The run's time grid: ``step`` [s], ``n_steps``, ``out_every`` (steps per output
    sample), ``hold`` (steps per control period; 0: continuous) and ``t0`` [s]."""

    step: float
    n_steps: int
    out_every: int
    hold: int
    t0: float = 0.0


def drive(plant, law, grid, y0, timing: Timing, lower, upper, *, sensors=None,
          actuators=None, limits: bool = True, info: dict | None = None):
    """Run ``plant`` under ``law`` from ``y0`` (the plant's state, ``(plant.size,)``).

    Args:
        plant: A :class:`~offshore_crane.simulation.plants.Plant`.
        law: A bound :class:`~offshore_crane.simulation.laws.Law`.
        grid: ``(tt, q_ref, qd_ref, qdd_ref)`` at every stage time
            (:func:`~offshore_crane.simulation.record.reference_grid`).
        y0: The plant's initial state.
        timing: :class:`Timing`.
        lower, upper: ``(9,)`` actuator capacities [N·m, N] (±inf: none).
        sensors, actuators: :class:`~offshore_crane.simulation.instruments.Sensors`,
            :class:`~offshore_crane.simulation.instruments.Actuators` or None.
        limits: Stop at the first sample outside the workspace.
        info: Put into the result's ``info``.

    Returns:
        :class:`~offshore_crane.simulation.record.SimulationResult`.

    Raises:
        InputError: sensors or a rate limit without a sampled law.
        SimulationError: the run stopped (its cause a :class:`~offshore_crane.stops.
            StopCause`); ``error.result`` keeps every sample before it.
    """
    from offshore_crane.dynamics.integrator import rk4_step
    from offshore_crane.simulation.record import (SimulationResult, divergence, diverging,
                                                  finite_rows, stopped)

    tt, qr, qdr, qddr = grid
    step, n_steps, out_every, hold = timing.step, timing.n_steps, timing.out_every, timing.hold
    sens = sensors if sensors is not None and sensors.active else None
    limit = actuators is not None and actuators.rate_limit is not None
    if (sens is not None or limit) and not hold:
        what = "sensor models" if sens is not None else "an actuator rate limit"
        raise InputError(f"{what} act at the control instants of a sampled law: give a "
                         "control rate ([control] rate, --control-rate)", name="rate")
    lag = None if actuators is None else actuators.lag
    n_p, n_z, n_l = plant.size, law.state_size, 0 if lag is None else 9
    delay = sens.delay_steps(step) if sens is not None else 0
    nq, nqd = sens.noise(n_steps // hold + 2) if sens is not None else (None, None)
    history = deque(maxlen=delay + 1)
    period = hold * step

    def ref(i):
        return qr[i], qdr[i], qddr[i]

    def f(i, y, held):
        yp, z, xl = y[:n_p], y[n_p:n_p + n_z], y[n_p + n_z:]
        if held is None:
            r = ref(i)
            X_cmd = X_in = law.command(i, tt[i], yp, z, r)
        else:
            X_cmd, X_in, dz = held
        X = np.clip(xl if n_l else X_in, lower, upper)
        dyp, aux = plant.derivative(i, yp, X)
        if not (n_z or n_l):
            return dyp, X_cmd, X, aux
        parts = [dyp]
        if n_z:
            parts.append(law.state_rate(i, tt[i], yp, z, r, X_cmd, X) if held is None
                         else dz)
        if n_l:
            parts.append((X_in - xl) / lag)
        return np.concatenate(parts), X_cmd, X, aux

    def sample(s, y, ctrl, last):
        """The held ``(X_cmd, X_in, ż)`` at control instant ``s``."""
        yp, z = y[:n_p], y[n_p:n_p + n_z]
        if sens is not None:
            meas = history[0].copy()
            Q, QD = plant.Q, plant.QD
            meas[Q] = sens.quantised(meas[Q] + nq[ctrl], sens.resolution_q)
            meas[QD] = sens.quantised(meas[QD] + nqd[ctrl], sens.resolution_qd)
        else:
            meas = yp
        r = ref(2 * s)
        X_cmd = law.command(2 * s, tt[2 * s], meas, z, r)
        X_in = actuators.limited(X_cmd, last, period) if limit else X_cmd
        dz = law.state_rate(2 * s, tt[2 * s], meas, z, r, X_cmd,
                            np.clip(X_in, lower, upper)) if n_z else None
        return X_cmd, X_in, dz

    parts = [np.asarray(y0, dtype=float), law.initial_state()]
    y = np.concatenate(parts + [np.zeros(n_l)]) if n_l else np.concatenate(parts)
    n_out = n_steps // out_every + 1
    rec = {k: np.full((n_out, 9), np.nan) for k in ("q", "qd", "qdd", "q_ref", "qd_ref",
                                                    "X_cmd", "X")}
    own = {k: np.full((n_out, w) if w else n_out, np.nan) for k, w in plant.RECORDED.items()}
    sat = np.zeros((n_out, 9), dtype=bool)
    held, last, ctrl, stop, done = None, None, 0, None, 0
    with progress.bar(n_out, "sample", "simulate") as shown:
        for s in range(n_steps + 1):
            if sens is not None:
                history.append(y[:n_p].copy())
            if hold and s % hold == 0:
                held = sample(s, y, ctrl, last)
                last, ctrl = held[1], ctrl + 1
                if n_l and s == 0:
                    y[n_p + n_z:] = held[1]
            elif n_l and s == 0:
                y[n_p + n_z:] = law.command(0, tt[0], y[:n_p], y[n_p:n_p + n_z], ref(0))
            k1, X_cmd, X, aux = f(2 * s, y, held)
            if s % out_every == 0:
                k = s // out_every
                yp, dyp = y[:n_p], k1[:n_p]
                rec["q"][k], rec["qd"][k], rec["qdd"][k] = plant.q(yp), plant.qd(yp), dyp[
                    plant.QD]
                rec["q_ref"][k], rec["qd_ref"][k] = qr[2 * s], qdr[2 * s]
                rec["X_cmd"][k], rec["X"][k] = X_cmd, X
                sat[k] = (X_cmd < lower) | (X_cmd > upper)
                plant.record(own, k, yp, dyp, aux)
                done = k + 1
                shown.update()
                found = plant.check(yp, aux)
                if found is not None:
                    stop = (k, *found)
                elif not (np.isfinite(y).all() and np.isfinite(k1).all()):
                    stop = (k, StopCause.DIVERGED, "")
                if stop is not None:
                    break
            if s == n_steps:
                break
            y = rk4_step(lambda i, x: f(i, x, held)[0], 2 * s, y, k1, step)
    t_out = tt[::2][::out_every][:n_out]
    res = SimulationResult(t=t_out, **rec, saturated=sat, energy=np.full(n_out, np.nan),
                           power=np.full(n_out, np.nan), integrator="rk4", step=step,
                           info=dict(info or {}, law=law.name, plant=plant.name))
    res = res.truncated(done)
    early = plant.finish(res, own, limits)           # what only the record shows
    if early is not None and (stop is None or early[0] < stop[0]):
        stop = early
    if stop is None:
        return res
    k, cause, words = stop
    when = timing.t0 + (k if k < len(t_out) else len(t_out) - 1) * step * out_every
    res = res.truncated(min(k, finite_rows(res)))
    if cause is StopCause.DIVERGED or diverging(res):
        res = res.truncated(finite_rows(res))
        cause, words = StopCause.DIVERGED, divergence(res)
    exc = stopped(res, when, words)
    exc.stop_cause = cause
    raise exc
