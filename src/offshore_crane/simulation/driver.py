"""The RK4 driver: one loop that runs any plant (:mod:`offshore_crane.simulation.plants`)
under any law (:mod:`offshore_crane.simulation.laws`) with the sensors and actuators
between them (:mod:`offshore_crane.simulation.instruments`), and records the run.

The loop is one text (:mod:`offshore_crane.simulation.loop`), compiled with the plant's
kernels and a built-in law's templates, or run as Python with a user's Python law. The
integrated state is ``y = (plant state, law state, actuator lag state)``. Classical RK4 at
a fixed step on the grid of half steps (:mod:`offshore_crane.dynamics.integrator`, the
one text of the tableau), the reference evaluated at every stage time.

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
(the plant's compiled ``check``); the plant's ``finish`` finds
those seen on the record (a workspace violation, a slack cable). A stop raises
:class:`~offshore_crane.errors.SimulationError` carrying every sample before it.
"""

from __future__ import annotations

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


#: Compiled (or Python) loops made in this process, their namespaces:
#: ``{(plant, templates, compiled): namespace}``.
_LOOPS: dict = {}


def namespace_for(plant, law) -> dict:
    """The driver's loop for ``plant`` under ``law`` in its namespace (``["loop"]``,
    ``["sense"]``: the sensors' model it runs; made once per process, a compiled one
    cached on disk)."""
    templates = law.templates()
    parts = " ".join(f"{name}={f.__module__}.{f.__qualname__}"
                     for name, f in sorted(templates.items()))
    name = f"{plant.name} ({plant.variant})" if plant.variant else plant.name
    key = (name, parts, law.compiled)
    if key not in _LOOPS:
        from offshore_crane.simulation.loop import instantiate

        _LOOPS[key] = instantiate(plant.kernels(), templates,
                                  {"IQ": plant.Q.start, "IQD": plant.QD.start},
                                  law.compiled, f"{name} {parts}")
    return _LOOPS[key]


def loop_for(plant, law):
    """The driver's loop for ``plant`` under ``law`` (:func:`namespace_for`)."""
    return namespace_for(plant, law)["loop"]


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
        lower, upper: ``(plant.nx,)`` actuator capacities [N·m, N] (±inf: none): the
            robot's 9, and a commanded winch's line pull last.
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
    pieces = Pieces(plant, law, grid, y0, timing, lower, upper, sensors=sensors,
                    actuators=actuators)
    follow = plant.follower(limits)     # on this core while the loop runs on another

    def meanwhile(n):       # the rows before the last recorded one are written for sure
        follow.feed(pieces.rec, n - 1)
    pieces.run(0, timing.n_steps, True, meanwhile)
    return pieces.result(limits, follow, info)


class Pieces:
    """The driver's loop set up for one run (its arrays, scratch and record), run over
    the whole span (:func:`drive`) or piece by piece (a stepper: :meth:`run` from any
    step, the record filled in order); :meth:`result` makes the run's result of what
    is recorded. Arguments as :func:`drive`.

    Raises:
        InputError: sensors or a rate limit without a sampled law.
    """

    def __init__(self, plant, law, grid, y0, timing: Timing, lower, upper, *, sensors=None,
                 actuators=None):
        self.plant, self.law, self.grid, self.timing = plant, law, grid, timing
        step, n_steps, hold = timing.step, timing.n_steps, timing.hold
        sens = sensors if sensors is not None and sensors.active else None
        limit = actuators is not None and actuators.rate_limit is not None
        if (sens is not None or limit) and not hold:
            what = "sensor models" if sens is not None else "an actuator rate limit"
            raise InputError(f"{what} act at the control instants of a sampled law: give "
                             "a control rate ([control] rate, --control-rate)", name="rate")
        self.lag, self.rlim = (np.zeros(0), np.zeros(0)) if actuators is None else \
            actuators.for_forces(plant.nx)
        self.n_p, self.n_z = plant.size, law.state_size
        self.sens = sens is not None
        self.delay = sens.delay_steps(step) if sens is not None else 0
        self.nq, self.nqd = (sens.noise(n_steps // hold + 2) if sens is not None
                             else (np.zeros((1, 9)),) * 2)
        self.res = [np.zeros(9) if r is None else r for r in (
            (sens.resolution_q, sens.resolution_qd) if sens is not None else (None, None))]
        self.y = np.concatenate([np.asarray(y0, dtype=float), law.initial_state(),
                                 np.zeros(len(self.lag))])
        n_out = n_steps // timing.out_every + 1
        nx = plant.nx
        self.rec = [np.full((n_out, 9 if k < 5 else nx), np.nan) for k in range(7)]
        self.sat = np.zeros((n_out, nx), dtype=bool)
        self.extra = np.full((n_out, plant.extra_width()), np.nan)
        self.status = np.zeros(4, dtype=np.int64)
        self.halt = progress.stop_flag()
        self.loop = loop_for(plant, law)
        from offshore_crane.simulation.loop import scratch

        self.W = scratch(len(self.y), self.n_p, self.n_z, self.delay, nx)
        self.P, self.L = plant.params(), law.params()
        self.lo, self.hi = (np.ascontiguousarray(np.asarray(b, dtype=float))
                            for b in (lower, upper))
        #: Output samples recorded so far.
        self.done = 0

    def run(self, s0: int, n: int, finish: bool, meanwhile=None,
            inline: bool = False) -> None:
        """Steps ``s0 .. s0 + n`` (``s0`` on an output sample; ``finish``: the last
        step's sample evaluated and recorded too, else left to the next piece).
        ``inline``: in this thread, whatever its length (a stepper's control period:
        a thread of its own and its start cost more than the period's steps; a Ctrl-C
        then waits for the piece to end); else as :func:`~offshore_crane.progress.
        run_polled` runs a loop (in a thread from the main one, with its bar)."""
        k0 = s0 // self.timing.out_every
        tt, qr, qdr, qddr = self.grid          # read at the run's stage points
        rec = [r[k0:] for r in self.rec]
        status, t = self.status, self.timing
        status[2] = 0
        polled = progress.run_polled if not inline else (lambda job, *_: job())
        polled(
            lambda: self.loop(self.P, self.L, tt, qr, qdr, qddr, self.y, float(t.step),
                              int(n), int(t.out_every), int(t.hold), self.lo, self.hi,
                              np.asarray(self.lag, dtype=float),
                              np.asarray(self.rlim, dtype=float), int(self.delay), self.nq,
                              self.nqd, self.res[0], self.res[1], self.sens, self.n_p,
                              self.n_z, *rec, self.sat[k0:], self.extra[k0:], status,
                              self.halt, self.W, int(s0), bool(finish)),
            lambda: k0 + status[2], self.rec[0].shape[0], "sample", "simulate", self.halt,
            meanwhile)
        self.done = k0 + int(status[2])
        if status[0] != 0:              # the stop's sample counted from the run's start
            status[1] += k0

    def result(self, limits: bool, follow=None, info: dict | None = None,
               copy: bool = False):
        """The run's result from its samples recorded (:attr:`done`), its stops found;
        raises :class:`~offshore_crane.errors.SimulationError` as :func:`drive`.
        ``copy``: of the record's arrays (a run that goes on fills them further)."""
        from offshore_crane.simulation.record import (SimulationResult, divergence, diverging,
                                                      finite_rows, stopped)

        plant, law, timing, status = self.plant, self.law, self.timing, self.status
        step, out_every = timing.step, timing.out_every
        n_out = self.rec[0].shape[0]
        tt = self.grid[0]
        t_out = tt[::2][::out_every][:n_out]
        names = ("q", "qd", "qdd", "q_ref", "qd_ref", "X_cmd", "X")
        own = (lambda a: a.copy()) if copy else (lambda a: a)
        res = SimulationResult(t=t_out, **{k: own(r) for k, r in zip(names, self.rec)},
                               saturated=own(self.sat), energy=np.full(n_out, np.nan),
                               power=np.full(n_out, np.nan), integrator="rk4", step=step,
                               info=dict(info or {}, law=law.name, plant=plant.name))
        res = res.truncated(self.done)
        stop = None
        code = StopCause(int(status[0]))
        if code is not StopCause.NONE:
            stop = (int(status[1]), code, plant.words(code, res)
                    if code is StopCause.SINGULAR else "")
        early = plant.finish(res, plant.recorded(own(self.extra)), limits, follow)
        if early is not None and (stop is None or early[0] < stop[0]):
            stop = early
        if stop is None:
            return res
        k, cause, words = stop
        when = timing.t0 + (k if k < len(t_out) else len(t_out) - 1) * step * out_every
        # the stop's own sample tells a divergence apart (a singular mass matrix at q5 =
        # 1e15)
        diverged = cause is StopCause.DIVERGED or diverging(res.truncated(k + 1))
        res = res.truncated(min(k, finite_rows(res)))
        if diverged:
            res = res.truncated(finite_rows(res))
            cause, words = StopCause.DIVERGED, divergence(res)
        exc = stopped(res, when, words)
        exc.stop_cause = cause
        raise exc
