"""What a simulation run records and the time grid it steps on: :class:`SimulationResult`,
the step counts (:func:`steps`) and the reference at every RK4 stage (:func:`reference_grid`).
Shared by the RK4 driver (:mod:`.driver`), every plant on it, and the DOP853 path (:mod:`.rigid`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from offshore_crane.errors import InputError, SimulationError
from offshore_crane.validation import check_memory


@dataclass
class SimulationResult:
    """A simulated run, sampled at the output times (every sample kept on a stop).

    Attributes:
        t: ``(N,)`` [s].
        q, qd, qdd: ``(N, 9)`` state and accelerations [m, rad, /s, /s²].
        q_ref, qd_ref: ``(N, 9)`` the reference.
        X_cmd, X: ``(N, 9)`` commanded and applied (saturated) actuator forces [N·m, N]
            at the start of each output interval.
        saturated: ``(N, 9)`` True where the command exceeded a limit.
        energy: ``(N,)`` mechanical energy T + V [J] (V of gravity, zero at the base).
        power: ``(N,)`` actuators' power Σ X_k · (rate of joint k) [W].
        integrator, step: What integrated it and its step [s] (RK4) or tolerances.
        stop: None, or the reason the run stopped early.
        sway, sway_rate: ``(N, 2)`` with a payload on a cable: φ1, φ2 [rad] and their
            rates [rad/s] (docs/cable.md); None otherwise.
        tension: ``(N,)`` the cable's tension [N], or None.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    q_ref: np.ndarray
    qd_ref: np.ndarray
    X_cmd: np.ndarray
    X: np.ndarray
    saturated: np.ndarray
    energy: np.ndarray
    power: np.ndarray
    integrator: str = "rk4"
    step: float = 0.0
    stop: str | None = None
    info: dict = field(default_factory=dict)
    sway: np.ndarray | None = None
    sway_rate: np.ndarray | None = None
    tension: np.ndarray | None = None

    @property
    def error(self) -> np.ndarray:
        """Tracking error ``q − q_ref`` ``(N, 9)``."""
        return self.q - self.q_ref

    def __len__(self) -> int:
        return len(self.t)

    def truncated(self, n: int) -> "SimulationResult":
        """The first ``n`` samples (the plants' per-sample arrays in ``info`` too,
        :data:`PER_SAMPLE_INFO`)."""
        arrays = {k: getattr(self, k)[:n] for k in ("t", "q", "qd", "qdd", "q_ref", "qd_ref",
                                                     "X_cmd", "X", "saturated", "energy",
                                                     "power")}
        cable = {k: None if getattr(self, k) is None else getattr(self, k)[:n]
                 for k in ("sway", "sway_rate", "tension")}
        info = {k: v[:n] if k in PER_SAMPLE_INFO and isinstance(v, np.ndarray) else v
                for k, v in self.info.items()}
        return SimulationResult(**arrays, integrator=self.integrator, step=self.step,
                                stop=self.stop, info=info, **cable)


#: The per-sample arrays a plant puts into a result's ``info`` (the elastic cable's
#: payload and winch, a winch's length): cut with the samples when a run stops.
PER_SAMPLE_INFO = frozenset(("payload", "payload_velocity", "length", "length_rate",
                             "winch_force", "winch_force_cmd", "winch_saturated",
                             "winch_power"))


def stage_times(t0: float, h: float, n_steps: int) -> np.ndarray:
    """Every RK4 stage time ``(2 n_steps + 1,)`` = t0 + k·h/2 [s]."""
    return t0 + np.arange(2 * n_steps + 1) * (0.5 * h)


def reference_grid(reference, t0: float, h: float, n_steps: int):
    """The reference at every RK4 stage time: ``(tt, q, qd, qdd)``, ``tt``
    (:func:`stage_times`) and ``(2 n_steps + 1, 9)`` C-contiguous arrays from
    ``reference(tt)`` [m, rad, /s, /s²]."""
    tt = stage_times(t0, h, n_steps)
    q, qd, qdd = reference(tt)
    return tt, np.ascontiguousarray(q), np.ascontiguousarray(qd), np.ascontiguousarray(qdd)


def held(q: np.ndarray):
    """A reference that holds the pose ``q`` ``(9,)`` [m, rad]: ``reference(t) -> (q, 0, 0)``
    each ``(n, 9)`` (the warm-ups' motion)."""
    q = np.asarray(q, dtype=float)

    def reference(t):
        n = len(np.atleast_1d(t))
        return np.tile(q, (n, 1)), np.zeros((n, 9)), np.zeros((n, 9))

    return reference


def steps(duration, step, rate, control_rate) -> tuple[int, int, int]:
    """``(n_steps, out_every, hold)``: integration steps in ``duration`` [s] at ``step``
    [s], steps per output sample (output ``rate`` [Hz], None: every step) and per control
    period (``control_rate`` [Hz], None: 0, the law at every stage).

    A duration that is not a whole number of steps (to 1e-9 relative) runs the whole
    steps it holds and warns (:class:`~offshore_crane.robot.kinematics.workspace.
    OffshoreCraneWarning`) with the time the run ends at: it never ends early silently.

    Raises:
        InputError: a non-positive or non-finite duration or step, a duration shorter
            than a step, a rate whose period is not a whole number of steps, a control
            rate above the integration rate.
    """
    for name, value, unit in (("duration", duration, "s"), ("step", step, "s"),
                              ("rate", rate, "Hz"), ("control_rate", control_rate, "Hz")):
        if value is None and name in ("rate", "control_rate"):
            continue
        if not (isinstance(value, (int, float)) and not isinstance(value, bool)
                and np.isfinite(value) and value > 0):
            raise InputError(f"{name} = {value!r} {unit}: must be positive and finite",
                             name=name)
    ratio = duration / step
    whole = round(ratio)
    if abs(ratio - whole) <= 1e-9 * max(1.0, ratio):
        n_steps = int(whole)
    else:
        import warnings

        from offshore_crane.robot.kinematics.workspace import OffshoreCraneWarning

        n_steps = int(ratio)
        warnings.warn(OffshoreCraneWarning(
            f"duration {duration:g} s is not a whole number of steps of {step:g} s "
            f"({ratio:.6g}): the run ends at {n_steps * step:.9g} s, after {n_steps} steps; "
            "give a duration that is a multiple of the step to end exactly there"),
            stacklevel=3)
    check_memory(8.0 * 27 * (2 * n_steps + 1) + 8.0 * 70 * (n_steps + 1),
                 f"a simulation of {duration:g} s at a step of {step:g} s ({n_steps} steps)",
                 "shorten the duration or lengthen the step (--step), or lower the output "
                 "rate", "step")
    if n_steps < 1:
        raise InputError(f"duration {duration} s is shorter than one step {step} s",
                         name="duration")
    out_every = 1
    if rate is not None:
        ratio = 1.0 / (rate * step)
        if not (np.isfinite(ratio) and abs(ratio - round(ratio)) < 1e-9 and round(ratio) >= 1):
            raise InputError(f"output rate {rate} Hz: 1/rate must be a multiple of the step "
                             f"{step} s", name="rate")
        out_every = int(round(ratio))
    hold = 0
    if control_rate is not None:
        ratio = 1.0 / (control_rate * step)
        if ratio < 1.0 - 1e-9:
            raise InputError(f"control rate {control_rate} Hz is above the integration "
                             f"rate {1.0 / step:g} Hz: lower it or shorten the step",
                             name="control_rate")
        if abs(ratio - round(ratio)) > 1e-9:
            raise InputError(f"control rate {control_rate} Hz: its period must be a "
                             f"multiple of the step {step} s", name="control_rate")
        hold = int(round(ratio))
    return n_steps, out_every, hold


def actuator_power(robot, q: np.ndarray, qd: np.ndarray, X: np.ndarray) -> np.ndarray:
    """The actuators' power ``Σ X_k · (rate of actuator k)`` ``(N,)`` [W] along ``q, qd``
    ``(N, 9)`` [m, rad, /s] under forces ``X`` ``(N, 9)`` [N·m, N]: the arm joints' rates
    and the legs' length rates (:func:`offshore_crane.robot.kinematics.actuator_motion`)."""
    from offshore_crane.robot.kinematics import actuator_motion

    v = actuator_motion(robot, q, qd)[1]
    return (X[:, :3] * v[:, :3]).sum(axis=1) + (X[:, 3:] * v[:, 3:]).sum(1)


class Follower:
    """What the driver works out from a run's record on this core while the loop fills
    it on another (:func:`~offshore_crane.progress.run_polled`'s ``meanwhile``): the
    workspace check (a :class:`~offshore_crane.robot.kinematics.WorkspaceWatch`) and,
    for a plant that forms it from the record, the actuators' power
    (:func:`actuator_power`, row by row: the same numbers in blocks), block by block of
    :data:`~offshore_crane.robot.kinematics.CHECK_BLOCK` samples; the plant's ``finish``
    completes both from where they are.

    Args:
        robot: The simulated robot.
        limits: Check the workspace.
        power: Form the actuators' power.
    """

    def __init__(self, robot, limits: bool, power: bool):
        from offshore_crane.robot.kinematics import CHECK_BLOCK, WorkspaceWatch

        self.robot, self.block = robot, CHECK_BLOCK
        self.workspace = WorkspaceWatch(robot) if limits else None
        self._power: list | None = [] if power else None
        self._done = 0

    def feed(self, rec: list, ready: int) -> None:
        """Take the whole blocks among the first ``ready`` rows of the driver's record
        ``rec`` (q, q̇, q̈, q_ref, q̇_ref, X_cmd, X) not taken yet."""
        if self.workspace is not None:
            self.workspace.feed(rec[0], ready)
        while self._power is not None and self._done + self.block <= ready:
            a, b = self._done, self._done + self.block
            self._power.append(actuator_power(self.robot, rec[0][a:b], rec[1][a:b],
                                              rec[6][a:b, :9]))
            self._done = b

    def power(self, q: np.ndarray, qd: np.ndarray, X: np.ndarray) -> np.ndarray:
        """:func:`actuator_power` of the run's record ``(N,)`` [W] (its first blocks
        those fed)."""
        if not self._power or self._done > len(q):
            return actuator_power(self.robot, q, qd, X)
        k = self._done
        return np.concatenate([*self._power, actuator_power(self.robot, q[k:], qd[k:],
                                                            X[k:])])


#: A coordinate beyond this [m or rad] is a diverging state, whatever stopped the run: no
#: platform moves a million metres or turns a million radians (an integration blowing up
#: reaches the attitude "singularity" with q5 ~ 1e15 rad on its way to overflow).
DIVERGED_STATE = 1e6


def finite_rows(res: "SimulationResult") -> int:
    """How many leading samples of ``res`` are finite in q, q̇, q̈ and X (a stopped run
    keeps those, never a row of NaN or inf)."""
    ok = np.ones(len(res), dtype=bool)
    for x in (res.q, res.qd, res.qdd, res.X):
        ok &= np.isfinite(x).all(axis=1)
    return len(res) if ok.all() else int(np.argmin(ok))


def diverging(res: "SimulationResult") -> bool:
    """True when the state of ``res`` stopped being a robot's: a non-finite value or a
    coordinate beyond :data:`DIVERGED_STATE`."""
    return finite_rows(res) < len(res) or bool((np.abs(res.q) > DIVERGED_STATE).any())


def divergence(res: "SimulationResult") -> str:
    """The cause of a diverged run, for its :class:`~offshore_crane.errors.SimulationError`:
    the last finite sample's |q̇| [m/s, rad/s mixed, Euclidean] and time [s], and what to do.
    ``res`` holds the finite rows only (:func:`finite_rows`)."""
    last = (f"|q̇| = {np.linalg.norm(res.qd[-1]):.3g} at t = {res.t[-1]:.6g} s, the last "
            "finite sample" if len(res) else "no finite sample")
    return f"the state diverged ({last}): shorten the step or soften the gains"


def stopped(res: "SimulationResult", when: float, cause: str) -> "SimulationError":
    """The :class:`~offshore_crane.errors.SimulationError` of a run that stopped at ``when``
    [s] for ``cause``, carrying ``res`` (the samples kept); ``res.stop`` is set."""
    res.stop = f"stopped at t = {when:.6g} s: {cause}"
    kept = (f"the {len(res)} samples computed before are kept" if len(res) else
            "no sample was computed before it")
    return SimulationError(f"simulation {res.stop}; {kept}", time=when, cause=cause,
                           result=res)


def initial_state(q0, qd0, reference_q: np.ndarray, reference_qd: np.ndarray):
    """The run's initial state ``(q0, qd0)`` ``(9,)`` each [m, rad, /s]: the reference's
    first sample where not given.

    Raises:
        InputError: a given state that is not 9 finite real numbers.
    """
    from offshore_crane.validation import as_samples

    out = []
    for name, given, default in (("q0", q0, reference_q), ("qd0", qd0, reference_qd)):
        if given is None:
            out.append(default.copy())
            continue
        x, single = as_samples(name, given)
        if not single:
            raise InputError(f"{name} must be one state (9,), got shape {np.shape(given)}",
                             name=name)
        out.append(x[0].copy())
    return out[0], out[1]


def workspace_stop(robot, res, limits: bool, watch=None):
    """``(sample, cause)`` of a recorded run's first workspace violation (the cause in
    the words of :func:`~offshore_crane.robot.kinematics.check_workspace`), or None;
    None too without ``limits`` or without a finite sample (the run's own stop says
    why). ``watch``: a :class:`~offshore_crane.robot.kinematics.WorkspaceWatch` fed with
    the record's first blocks while the run was computing them, or None."""
    if not limits or len(res) == 0:
        return None
    from offshore_crane.errors import WorkspaceError
    from offshore_crane.robot.kinematics import check_workspace

    try:
        check_workspace(robot, res.q, res.t, watch=watch)
    except WorkspaceError as exc:
        return exc.index, str(exc).split(" at sample")[0] + " (outside its limits)"
    return None
