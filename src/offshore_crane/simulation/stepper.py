"""A simulation you step (issue 38, item 1): a controller outside the simulation gives
the actuator forces (or, ``action="reference"``, a reference for a built-in law) for one
control period at a time and reads the measured state, what the plant forms of it and the
reference back. The Gymnasium environment (:mod:`offshore_crane.gym`) and the FMU
(:mod:`offshore_crane.fmu`) run on it.

>>> import numpy as np
>>> import offshore_crane as oc
>>> from offshore_crane.motion.trajectories import table1
>>> from offshore_crane.simulation.stepper import Stepper
>>> robot = oc.load_robot()
>>> sim = Stepper(robot, 0.05, table1, control_period=0.01)
>>> y = sim.reset()
>>> X = oc.inverse_dynamics(robot, y[:9], y[9:18], np.zeros(9))  # the robot held still
>>> y = sim.step(X)
>>> round(sim.time, 6), sim.observation_names[:2]
(0.01, ('q1_m', 'q2_m'))

The run is set up by the simulate function of its plant, with every check it makes
(the rigid robot, a payload on a rigid cable: :func:`~offshore_crane.simulation.rigid.
simulate`; on an elastic cable, given ``ea``: :func:`~offshore_crane.simulation.elastic.
simulate_elastic`), and driven by the same compiled loop piece by piece: one period a
:meth:`Stepper.step`, the action held over it as a sampled law's command is (the
sensors, the rate limit, the lag and the capacities between them as for every law:
:mod:`offshore_crane.simulation.laws.held_action`). The run's record is the result
``simulate`` returns (:meth:`Stepper.record`): a sampled Python law stepped from outside
gives ``simulate``'s run of that law bit for bit (tested), but for the last sample's
forces and accelerations (the last action held: nothing acts after the end).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError, SimulationError


class Stepper:
    """A run of ``duration`` seconds driven one control period at a time.

    Args:
        robot: From :func:`offshore_crane.load_robot` (with a payload on a cable: the
            hanging load, or with ``ea`` the elastic cable).
        duration: [s], a whole number of control periods.
        reference: ``reference(t) -> (q, qd, qdd)`` as :func:`~offshore_crane.simulation.
            rigid.simulate`'s (what the record's reference columns hold; the initial state
            is its first sample unless given).
        control_period: [s], a whole number of integration steps.
        saturation: True: forces beyond the actuators' capacities are clipped to them
            (flagged in the record's ``saturated``); False: such an action is refused.
        action: ``"forces"`` (the default): an action is the actuators' forces
            (:attr:`action_names`). ``"reference"``: it is a reference for the built-in
            law of ``controller``, ``(q_ref (9,), q̇_ref (9,))`` [m, rad, /s] held as a
            first-order hold over the period (``q_ref + (t − t_k) q̇_ref``, q̈_ref = 0):
            the caller replaces the outer loop only.
        controller: With ``action="reference"``: the
            :class:`~offshore_crane.simulation.control.Controller` whose law tracks it
            (default: computed torque at the control period; its rate is the control
            period's whatever it says). Not with forces.
        q0, qd0, step, gravity, t0, sensors, actuators, limits: As ``simulate``.
        **plant: The plant's own options (``initial``, ``initial_rate`` of a hanging
            load's sway; ``ea``, ``damping``, ``hoist``, ... of an elastic cable:
            :func:`~offshore_crane.simulation.elastic.simulate_elastic`).

    Attributes:
        observation_names: The names of :meth:`step`'s observation, the CSV's columns:
            the plant's state as the sensors measure it (``q1_m`` ... ``qd9_m_s``;
            ``phi1_rad`` ... of a hanging load; ``payload_x_m`` ... of an elastic cable),
            what the plant forms of it (a hanging load's position ``payload_x_m`` ...; the
            cable's tension ``tension_N``, a rigid cable's under the forces
            :meth:`acting`; the cable's length ``L_m``:
            :meth:`~offshore_crane.simulation.plants.Plant.observe`), then the scene's
            reference at
            the instant, ``q1_ref_m`` ... ``qd9_ref_m_s`` (exact: the vessel's motion in
            q1..q6, the arm's plan in q7..q9).
        action_names: What an action gives, in order: the forces (``T1`` ... ``Fl6``, and
            ``Fw`` with a commanded winch), or with ``action="reference"`` the reference
            commanded, ``q1_cmd_m`` ... ``qd9_cmd_m_s``.
        capacities: ``(lower, upper)`` ``(nx,)`` each: the actuators' capacities [N·m,
            N] (the description's, ±inf where it gives none; a winch's pull last).
        action_bounds: ``(lower, upper)`` ``(len(action_names),)`` each: the
            capacities for forces, ±inf for a reference.
        slack_tension: [N] a tension below which the run is :attr:`terminated` (the
            description's ``payload.limits.tension_ratio_min`` × m|g|; 0 without it: a
            slack cable), or None without a cable.

    Raises:
        InputError: what the simulate function refuses; a control period that is not a
            whole number of steps, or a duration not of periods; an unknown ``action``, a
            ``controller`` with forces, a law that forms its reference once (the arm
            compensations) given references.
    """

    def __init__(self, robot, duration: float, reference, *, control_period: float,
                 saturation: bool = True, q0=None, qd0=None, step: float = 1e-3,
                 gravity=GRAVITY, t0: float = 0.0, sensors=None, actuators=None,
                 limits: bool = True, action: str = "forces", controller=None,
                 **plant):
        from offshore_crane.conventions import ACTUATORS, N_COORDINATES, coordinate_column
        from offshore_crane.simulation.control import Controller
        from offshore_crane.simulation.laws.held_action import HeldAction
        from offshore_crane.simulation.runs import opened

        period = float(control_period)
        if not (np.isfinite(period) and period > 0.0):
            raise InputError(f"control_period = {control_period!r} s: give a positive "
                             "period, a whole number of steps", name="control_period")
        steps = period / float(step)
        if not (round(steps) >= 1 and abs(steps - round(steps)) <= 1e-9 * steps):
            raise InputError(f"control_period = {period:g} s is not a whole number of "
                             f"integration steps of {float(step):g} s: give a multiple of "
                             "the step", name="control_period")
        if action not in ("forces", "reference"):
            raise InputError(f"action = {action!r}: give 'forces' or 'reference'",
                             name="action")
        if controller is not None and action != "reference":
            raise InputError("a controller drives the run only with action='reference' "
                             "(an action of forces is the controller)", name="controller")
        controller = dataclasses.replace(
            controller if controller is not None else Controller(),
            rate=1.0 / period, saturation=bool(saturation))

        def simulate():
            if "ea" in plant:
                from offshore_crane.simulation.elastic import simulate_elastic

                return simulate_elastic(robot, duration, reference, q0, qd0, controller,
                                        gravity=gravity, step=step, t0=t0, limits=limits,
                                        sensors=sensors, actuators=actuators, **plant)
            from offshore_crane.simulation.rigid import simulate as rigid

            return rigid(robot, duration, reference, q0, qd0, controller, gravity=gravity,
                         step=step, t0=t0, limits=limits, sensors=sensors,
                         actuators=actuators, **plant)

        run, self._y0, self.limits = opened(simulate)
        timing = run.timing
        if timing.n_steps % timing.hold:
            raise InputError(f"duration = {duration!r} s is not a whole number of control "
                             f"periods of {period:g} s: give {timing.n_steps // timing.hold}"
                             f" or {timing.n_steps // timing.hold + 1} periods' worth",
                             name="duration")
        if timing.hold % timing.out_every:
            raise InputError("the output rate must divide the control period",
                             name="rate")
        self.reference_action = action == "reference"
        # the scene's reference (q, q̇, q̈ at every stage): the grid itself, or a copy of
        # it where the actions write the law's reference into the grid
        self._scene = tuple(a.copy() if self.reference_action else a for a in run.grid[1:])
        if self.reference_action:
            if type(run.law).reference_once:
                raise InputError(f"the law {run.law.name!r} forms its reference once from "
                                 "the scene's: it cannot take one as an action; give "
                                 "another controller", name="controller")
        else:
            run.law = HeldAction(controller, run.plant)
        self._run = run
        lo, hi = dataclasses.replace(controller, saturation=True).bounds(run.plant.robot)
        if run.plant.nx > 9:
            pull = run.plant.robot.winch.pull_max
            lo, hi = np.append(lo, -pull), np.append(hi, pull)
        self.capacities = lo, hi
        self.saturation = bool(saturation)
        plant_ = run.plant
        self._observed = np.zeros(len(plant_.observed_names()))
        reference = tuple(coordinate_column(k, d, "_ref") for d in (0, 1)
                          for k in range(N_COORDINATES))
        self.observation_names = (plant_.state_names() + plant_.observed_names()
                                  + reference)
        if self.reference_action:
            self.action_names = tuple(coordinate_column(k, d, "_cmd") for d in (0, 1)
                                      for k in range(N_COORDINATES))
            self.action_bounds = (np.full(18, -np.inf), np.full(18, np.inf))
        else:
            self.action_names = ACTUATORS + (("Fw",) if plant_.nx > 9 else ())
            self.action_bounds = (lo.copy(), hi.copy())
        self.slack_tension = None
        if "tension" in plant_.RECORDED:
            ratio = plant_.robot.load_limits.tension_ratio_min
            m = float(plant_.robot.hybrid.cable.mass[-1])
            self.slack_tension = (0.0 if np.isnan(ratio) else
                                  ratio * m * float(np.linalg.norm(run.plant.g)))
        self._pieces = None
        self._geometry = None                   # the workspace check's (on first use)
        self._k = 0
        #: The run stopped (the workspace left, a singular or diverged state).
        self.terminated = False
        #: The run reached its duration.
        self.truncated = False

    # --------------------------------------------------------------- the run
    def reset(self, seed: int | None = None) -> np.ndarray:
        """Start again at ``t0`` from the run's initial state; ``seed`` (given) seeds the
        sensors' noise. Returns the first observation (:attr:`observation_names`)."""
        from offshore_crane.simulation.driver import Pieces, namespace_for

        run = self._run
        sensors = run.sensors
        if seed is not None and sensors is not None:
            sensors = dataclasses.replace(sensors, seed=int(seed))
        self._pieces = Pieces(run.plant, run.law, run.grid, self._y0, run.timing, run.lower,
                              run.upper, sensors=sensors, actuators=run.actuators)
        self._sense = namespace_for(run.plant, run.law)["sense"]
        self._k = 0
        self.terminated = self.truncated = False
        first = self._pieces.W[-1]
        first[:] = self._pieces.y[:run.plant.size]
        if self.slack_tension is not None:      # the record's tension column, a view
            self._tension = run.plant.recorded(self._pieces.extra)["tension"]
        return self._observe()

    def step(self, action) -> np.ndarray:
        """Apply ``action`` (:attr:`action_names`: ``(nx,)`` forces [N·m, N], or a
        reference ``(18,)``) over one control period; returns the observation at its end.
        :attr:`terminated` (the run stopped: the workspace left, a singular or diverged
        state, the cable's tension below :attr:`slack_tension`) and :attr:`truncated`
        (the duration reached) say whether it can go on.

        Raises:
            InputError: no :meth:`reset`, a run that ended, an action of the wrong shape,
                not finite, or beyond the actuators' capacities without ``saturation``.
        """
        pieces = self._check(action)
        t = self._run.timing
        pieces.run(self._k * t.hold, t.hold, False, inline=True)
        self._k += 1
        if pieces.status[0] != 0:
            self.terminated = True
        elif self._k * t.hold >= t.n_steps:
            pieces.run(t.n_steps, 0, True, inline=True)   # the last sample, action held
            self.truncated = True
        if self.limits and not self.terminated and self._outside():
            self.terminated = True
        if self.slack_tension is not None and not self.terminated and self._slack():
            self.terminated = True
        return self._observe()

    def record(self):
        """The run so far: a :class:`~offshore_crane.simulation.record.SimulationResult`
        as ``simulate`` returns (plots, CSV and ``size`` read it); a stopped run's with
        its samples before the stop and ``stop`` saying why."""
        if self._pieces is None:
            raise InputError("no run yet: call reset() first", name="reset")
        try:
            return self._pieces.result(self.limits, info={"controller": "stepper"},
                                       copy=True)
        except SimulationError as exc:
            return exc.result

    @property
    def time(self) -> float:
        """The run's time now [s]."""
        t = self._run.timing
        return t.t0 + self._k * t.hold * t.step

    def applied(self) -> np.ndarray:
        """``(nx,)`` [N·m, N]: the forces the actuators applied over the last period (the
        mean of its recorded samples: after the capacities and the lag); zeros before a
        step."""
        p, t = self._pieces, self._run.timing
        if p is None or self._k == 0:
            return np.zeros(self._run.plant.nx)
        a = (self._k - 1) * t.hold // t.out_every
        return p.rec[6][a:max(p.done, a + 1)].mean(axis=0)

    def holding(self) -> np.ndarray:
        """``(nx,)`` [N·m, N]: the forces that hold the robot still where it is now, on
        the plant's model (its law's static forces: the robot's weight and the cable's
        pull at the state as simulated; a commanded winch's pull the cable's tension).
        What a controller starts from (the FMU's inputs' start values).

        Raises:
            InputError: before :meth:`reset`."""
        plant, y = self._run.plant, self.state
        X = np.zeros(plant.nx)
        i = 2 * self._k * self._run.timing.hold
        plant.kernels().gravity(plant.params(), i, y, X)
        if plant.nx > 9:
            seen = np.zeros(len(plant.observed_names()))
            plant.observe(i, y, X, seen)
            X[9] = seen[plant.observed_names().index("tension_N")]
        return X

    def acting(self) -> np.ndarray:
        """``(nx,)`` [N·m, N]: the forces acting on the plant at this instant, before
        the next action takes over (the last period's, after the capacities and the
        lag; at the start, :meth:`holding`'s: none has acted yet).

        Raises:
            InputError: before :meth:`reset`."""
        p = self._pieces
        if p is None:
            raise InputError("no run yet: call reset() first", name="reset")
        if self._k == 0:
            return self.holding()
        if len(p.lag):                 # the lag's state, clipped as the loop clips it
            a = self._run.plant.size + p.n_z
            return np.clip(p.y[a:a + self._run.plant.nx], p.lo, p.hi)
        return p.rec[6][p.done - 1].copy()     # held over the period: its last sample's

    def plan(self) -> tuple:
        """``(t (n + 1,) [s], q_ref, q̇_ref (n + 1, 9))``: the scene's reference at every
        control instant of the run's ``n`` periods (what the observation's reference
        channels hold there)."""
        t = self._run.timing
        rows = slice(0, 2 * t.n_steps + 1, 2 * t.hold)
        qr, qdr, _ = self._scene
        return self._run.grid[0][rows].copy(), qr[rows].copy(), qdr[rows].copy()

    @property
    def plant(self):
        """The run's :class:`~offshore_crane.simulation.plants.Plant` (its robot, state
        layout and kernels)."""
        return self._run.plant

    @property
    def control_steps(self) -> int:
        """Integration steps in a control period."""
        return self._run.timing.hold

    @property
    def periods_done(self) -> int:
        """Control periods stepped since :meth:`reset`."""
        return self._k

    @property
    def reference_now(self) -> tuple:
        """``(t [s], q_ref, qd_ref, qdd_ref (9,) each)``: the reference at this control
        instant, the numbers a built-in or Python law reads there (the run's grid)."""
        i = 2 * self._k * self._run.timing.hold
        qr, qdr, qddr = self._scene
        return float(self._run.grid[0][i]), qr[i].copy(), qdr[i].copy(), qddr[i].copy()

    @property
    def state(self) -> np.ndarray:
        """The plant's state now, as simulated (no sensor model) ``(plant.size,)``: the
        observation's first entries without the sensors.

        Raises:
            InputError: before :meth:`reset`."""
        if self._pieces is None:
            raise InputError("no run yet: call reset() first", name="reset")
        return self._pieces.y[:self._run.plant.size].copy()

    # --------------------------------------------------------------- inside
    def _check(self, action):
        if self._pieces is None:
            raise InputError("step() before reset(): call reset() first", name="reset")
        if self.terminated or self.truncated:
            why = "stopped" if self.terminated else "reached its duration"
            raise InputError(f"step() after the run {why} at t = {self.time:g} s: call "
                             "reset() to start again", name="step")
        nx = len(self.action_names)
        try:
            a = np.asarray(action, dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"action {action!r} is not numbers: give {nx} of them "
                             f"({', '.join(self.action_names)})", name="action") from None
        if a.shape != (nx,):
            what = "forces" if not self.reference_action else "reference values"
            raise InputError(f"action of shape {a.shape}: give {nx} {what} "
                             f"({', '.join(self.action_names)})", name="action")
        if not np.isfinite(a).all():
            j = int(np.flatnonzero(~np.isfinite(a))[0])
            raise InputError(f"action {self.action_names[j]} = {float(a[j])} at t = "
                             f"{self.time:g} s: give finite numbers", name="action")
        if self.reference_action:
            self._hold_reference(a)
            return self._pieces
        lo, hi = self.capacities
        if not self.saturation and ((a < lo) | (a > hi)).any():
            j = int(np.flatnonzero((a < lo) | (a > hi))[0])
            raise InputError(f"action {self.action_names[j]} = {a[j]:.6g} at t = "
                             f"{self.time:g} s is beyond its capacity [{lo[j]:.6g}, "
                             f"{hi[j]:.6g}]: give a force within it, or open the stepper "
                             "with saturation=True to have it clipped", name="action")
        self._run.law.action[:] = a
        return self._pieces

    def _hold_reference(self, a: np.ndarray) -> None:
        """The law's reference over the coming period's stage points: ``a[:9] + (t −
        t_k) a[9:]``, rate ``a[9:]``, no acceleration (the grid's rows the loop reads)."""
        t = self._run.timing
        i0 = 2 * self._k * t.hold
        rows = slice(i0, i0 + 2 * t.hold + 1)
        tt, qr, qdr, qddr = self._run.grid
        qr[rows] = a[:9] + (tt[rows] - tt[i0])[:, None] * a[9:]
        qdr[rows] = a[9:]
        qddr[rows] = 0.0

    def _observe(self) -> np.ndarray:
        """The measured state at this control instant (the loop's own sensor model, the
        numbers its next piece measures), what the plant forms of it and the scene's
        reference there."""
        p, plant = self._pieces, self._run.plant
        n_p = plant.size
        g = self._k * self._run.timing.hold
        hist, ym = p.W[-2], p.W[5]
        if p.sens:
            hist[g % (p.delay + 1)] = p.y[:n_p]
        self._sense(p.y, ym, hist, p.W[-1], g, p.delay, p.nq, p.nqd, p.res[0], p.res[1],
                    p.sens, int(p.status[3]), n_p)
        plant.observe(2 * g, ym[:n_p], self.acting(), self._observed)
        qr, qdr, _ = self._scene
        return np.concatenate([ym[:n_p], self._observed, qr[2 * g], qdr[2 * g]])

    def _slack(self) -> bool:
        """Whether a sample the last period recorded has the cable's tension below
        :attr:`slack_tension`; where the record forms the tension after the run (a
        hoisted rigid cable's: NaN in the loop's record), the tension at this instant,
        as simulated, under the forces acting."""
        p, t, plant = self._pieces, self._run.timing, self._run.plant
        a = max(0, (self._k - 1) * t.hold // t.out_every)
        T = self._tension[a:p.done]
        if np.isnan(T).all():
            seen = np.zeros(len(plant.observed_names()))
            plant.observe(2 * self._k * t.hold, self.state, self.acting(), seen)
            T = seen[plant.observed_names().index("tension_N")]
        return bool(np.any(T < self.slack_tension))

    def _outside(self) -> bool:
        """Whether the last period's samples left the workspace (the compiled check of
        :mod:`offshore_crane.dynamics.outside`: ``check_workspace``'s tests, without
        its NumPy passes' cost on a period's few samples; :meth:`record` says which
        limit)."""
        from offshore_crane.dynamics import outside

        if self._geometry is None:
            self._geometry = outside.geometry(self._run.plant.robot)
        p, t = self._pieces, self._run.timing
        a = max(0, (self._k - 1) * t.hold // t.out_every)
        return outside.first_outside(p.rec[0], a, p.done, *self._geometry) >= 0
