"""Actuator envelopes of one run: peak push and pull, RMS, speed, power and stroke per
actuator, against the description's capacities (:class:`Envelope`, the unit of a sweep's
results table).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from offshore_crane.robot.kinematics import actuator_motion
from offshore_crane.conventions import ACTUATORS, GRAVITY
from offshore_crane.errors import InputError
from offshore_crane.studies.sizing.loads import LIFT, load_row, utilisation


#: Capacities judged, in the order of the utilisation columns.
CAPACITIES = ("push", "pull", "speed", "power", "stroke")
#: Per-actuator quantities of an envelope (``(9,)`` arrays), in row-column order.
QUANTITIES = ("peak_push", "t_push", "peak_pull", "t_pull", "rms", "peak_speed",
              "peak_power", "mean_abs_power", "stroke_min", "stroke_max")
#: Condition-number kinds of a run (:class:`offshore_crane.dynamics.Result`).
KINDS = ("leg", "gimbal", "attitude")


#: Units of the joint positions (stroke) and speeds per actuator.
POSITION_UNITS = ("rad", "rad", "m", "m", "m", "m", "m", "m", "m")
SPEED_UNITS = ("rad/s", "rad/s", "m/s", "m/s", "m/s", "m/s", "m/s", "m/s", "m/s")


@dataclass(frozen=True)
class Envelope:
    """The envelope of one run (see the module docstring). Per-actuator arrays are
    ``(9,)`` in the order of X, NaN for an actuator the run does not have.

    Attributes:
        duration: Span of the record ``t[-1] − t[0]`` [s] (model scale).
        samples: N.
        peak_push, peak_pull: ``max(X, 0)``, ``max(−X, 0)`` [N·m, N].
        t_push, t_pull: Their times [s] (NaN when the actuator never pushes / pulls).
        rms: RMS of X [N·m, N].
        peak_speed: ``max |v|`` [rad/s, m/s].
        peak_power, mean_abs_power: ``max |X v|``, ``mean |X v|`` [W].
        stroke_min, stroke_max: Joint position range used [rad, m].
        stroke_range: ``(9, 2)`` the joint's allowed range [rad, m] (inf when unknown).
        capacities: ``{"push_max", "pull_max", "speed_max", "power_max"}`` → ``(9,)``.
        utilisation: ``(9, 5)`` utilisation of :data:`CAPACITIES` (1 = 100 %; NaN: no
            capacity given or no such actuator).
        kappa: ``{kind: worst condition number}`` over :data:`KINDS` (NaN: not measured).
        t_kappa: ``{kind: its time [s]}``.
        sway_max: Largest angle of the cable from the tip's vertical [rad] (NaN: no cable).
        tension_min, tension_max: The cable's tension range [N] (NaN: no cable; an
            elastic cable's largest refined between samples, its snap's peak).
        time_slack: Time the cable spent slack [s] (NaN: no cable).
        static_tension: The cable's tension at rest, m·|g| [N] (NaN: no cable).
        winch: ``{"pull" [N], "speed" [m/s], "acceleration" [m/s²], "power" [W]}`` the
            winch's largest demands (empty without a winch).
        winch_capacities: The robot's
            :class:`~offshore_crane.robot.description.WinchCapacities` (with a winch).
        load_limits: The robot's :class:`~offshore_crane.robot.description.LoadLimits`
            (None: no cable).
    """

    duration: float
    samples: int
    peak_push: np.ndarray
    t_push: np.ndarray
    peak_pull: np.ndarray
    t_pull: np.ndarray
    rms: np.ndarray
    peak_speed: np.ndarray
    peak_power: np.ndarray
    mean_abs_power: np.ndarray
    stroke_min: np.ndarray
    stroke_max: np.ndarray
    stroke_range: np.ndarray
    capacities: dict
    utilisation: np.ndarray
    kappa: dict = field(default_factory=dict)
    t_kappa: dict = field(default_factory=dict)
    sway_max: float = math.nan
    tension_min: float = math.nan
    tension_max: float = math.nan
    time_slack: float = math.nan
    static_tension: float = math.nan
    load_limits: object = None
    winch: dict = field(default_factory=dict)
    winch_capacities: object = None

    @property
    def present(self) -> np.ndarray:
        """``(9,)`` bool: the actuators the run has."""
        return ~np.isnan(self.rms)

    @property
    def stroke_excursion(self) -> np.ndarray:
        """``(9,)`` ``max |p − mid|`` [rad, m] over the record."""
        mid = self.stroke_range.mean(axis=1)
        return np.maximum(np.abs(self.stroke_max - mid), np.abs(self.stroke_min - mid))

    def worst(self) -> tuple[float, str | None, str | None]:
        """``(utilisation, actuator, capacity)`` of the largest utilisation (NaN, None,
        None when no capacity is given)."""
        return worst_utilisation(self.utilisation)

    def row(self) -> dict:
        """One flat row: ``{actuator}_{quantity}`` and ``{actuator}_util_{capacity}``
        for the 9 actuators (NaN where absent), ``{actuator}_util`` (its worst),
        ``kappa_{kind}``, ``duration_s``, ``samples``, ``worst_util``, ``governing``,
        ``governing_capacity`` (``""`` when none), and the hanging load's
        :data:`~offshore_crane.studies.sizing.loads.LIFT` columns."""
        out: dict = {"duration_s": float(self.duration), "samples": int(self.samples)}
        for k, name in enumerate(ACTUATORS):
            for q in QUANTITIES:
                out[f"{name}_{q}"] = float(getattr(self, q)[k])
            for c, cap in enumerate(CAPACITIES):
                out[f"{name}_util_{cap}"] = float(self.utilisation[k, c])
            u = self.utilisation[k]
            out[f"{name}_util"] = float(np.nanmax(u)) if not np.isnan(u).all() else math.nan
        for kind in KINDS:
            out[f"kappa_{kind}"] = float(self.kappa.get(kind, math.nan))
        worst, who, cap = self.worst()
        out.update(worst_util=float(worst), governing=who or "", governing_capacity=cap or "")
        out.update(load_row(self))
        return out


def row_columns() -> list[tuple[str, str]]:
    """``[(column, "float64" | "int64" | "string"), ...]`` of :meth:`Envelope.row`, in
    order (the fixed schema of a sweep's results)."""
    cols = [("duration_s", "float64"), ("samples", "int64")]
    for name in ACTUATORS:
        cols += [(f"{name}_{q}", "float64") for q in QUANTITIES]
        cols += [(f"{name}_util_{c}", "float64") for c in CAPACITIES]
        cols.append((f"{name}_util", "float64"))
    cols += [(f"kappa_{k}", "float64") for k in KINDS]
    cols += [("worst_util", "float64"), ("governing", "string"),
             ("governing_capacity", "string")]
    cols += [(k, "float64") for k in LIFT]
    return cols


def worst_utilisation(util: np.ndarray):
    """``(value, actuator, capacity)`` of the largest utilisation in ``util`` ``(9, 5)``
    (actuators × :data:`CAPACITIES`); ``(nan, None, None)`` when nothing is measured."""
    if np.isnan(util).all():
        return math.nan, None, None
    k, c = np.unravel_index(np.nanargmax(util), util.shape)
    return float(util[k, c]), ACTUATORS[k], CAPACITIES[c]


def stroke_ranges(robot) -> np.ndarray:
    """``(9, 2)`` the allowed range of each actuator's joint [rad, m]: the arm joints'
    limits (q7, q8, q9) and the legs' stroke, as the robot's URDF gives them; ``±inf``
    for a joint the robot does not have."""
    from offshore_crane.dynamics.constants import robot_arrays

    limits = robot_arrays(robot.without_hanging_payload()).limits   # kinematic: no payload
    out = np.full((9, 2), np.nan)
    out[:, 0], out[:, 1] = -np.inf, np.inf
    arm = np.asarray(limits.arm).reshape(-1, 2)
    out[:len(arm)] = arm
    out[3:] = np.asarray(limits.stroke).reshape(6, 2)
    return out


def _peak(x: np.ndarray, t: np.ndarray):
    """``max(x, 0)`` per column and its time (NaN when x never exceeds 0), over the
    rows; NaN columns give NaN."""
    k = np.argmax(np.where(np.isnan(x), -np.inf, x), axis=0)
    top = x[k, np.arange(x.shape[1])]
    peak = np.where(np.isnan(top), np.nan, np.maximum(top, 0.0))
    when = np.where(top > 0.0, t[k], np.nan)
    return peak, when


def envelope(robot, t, q, qd, X, condition=None, arm: bool | None = None,
             legs: bool | None = None, cable=None, gravity=GRAVITY) -> Envelope:
    """The envelope of one run against ``robot.capacities``.

    Args:
        robot: From :func:`offshore_crane.load_robot` (capacities, strokes, geometry).
        t: ``(N,)`` [s].
        q, qd: ``(N, 9)`` [m, rad], [m/s, rad/s].
        X: ``(N, 9)`` actuator forces [N·m, N]; a column that is all NaN is an actuator
            the run does not have (no arm, or leg forces not computed).
        condition: ``{kind: (N,) condition numbers}`` over :data:`KINDS`, or None.
        arm, legs: Whether the arm / leg actuators exist (default: their X columns are
            not all NaN).
        cable: The run's :class:`~offshore_crane.dynamics.cable.CableResult` (a payload on a
            cable), or None.
        gravity: ``(3,)`` the run's gravity [m/s²] (the static tension m·|g| of a cable).

    Returns:
        :class:`Envelope`.

    Raises:
        InputError: shapes that do not agree, non-finite t, q, qd or X values in an
            actuator that exists (naming the column and the sample).
    """
    t = np.asarray(t, dtype=float)
    q, qd, X = (np.asarray(a, dtype=float) for a in (q, qd, X))
    N = t.shape[0] if t.ndim == 1 else -1
    for name, a in (("q", q), ("qd", qd), ("X", X)):
        if a.shape != (N, 9):
            raise InputError(f"envelope: {name} has shape {a.shape}; expected ({N}, 9) "
                             f"like t ({t.shape})", name=name)
    if N < 1:
        raise InputError("envelope: the run has no sample", name="t")
    for name, a in (("t", t[:, None]), ("q", q), ("qd", qd)):
        bad = ~np.isfinite(a)
        if bad.any():
            i, j = np.argwhere(bad)[0]
            raise InputError(f"envelope: {name}[{i}, {j}] = {float(a[i, j])!r} is not "
                             "finite", name=name, index=int(i))
    if arm is None:
        arm = not np.isnan(X[:, :3]).all()
    if legs is None:
        legs = not np.isnan(X[:, 3:]).all()
    present = np.array([arm] * 3 + [legs] * 6)
    F = np.where(present, X, np.nan)
    bad = np.isnan(F[:, present]) | np.isinf(F[:, present])
    if bad.any():
        i, j = np.argwhere(bad)[0]
        col = np.flatnonzero(present)[j]
        raise InputError(f"envelope: X[{i}, {col}] ({ACTUATORS[col]}) = "
                         f"{float(F[i, col])!r} is not finite", name=ACTUATORS[col],
                         index=int(i))
    p, v = actuator_motion(robot, q, qd, legs=bool(legs))
    p[:, ~present], v[:, ~present] = np.nan, np.nan
    power = F * v
    peak_push, t_push = _peak(F, t)
    peak_pull, t_pull = _peak(-F, t)
    with np.errstate(invalid="ignore"):
        rms = np.sqrt(np.mean(F * F, axis=0))
        peak_speed = np.max(np.abs(v), axis=0)
        peak_power = np.max(np.abs(power), axis=0)
        mean_abs_power = np.mean(np.abs(power), axis=0)
        stroke_min, stroke_max = p.min(axis=0), p.max(axis=0)
    caps = robot.capacities
    capacities = {k: np.asarray(getattr(caps, k), dtype=float)
                  for k in ("push_max", "pull_max", "speed_max", "power_max")}
    rng = stroke_ranges(robot)
    mid, half = rng.mean(axis=1), 0.5 * (rng[:, 1] - rng[:, 0])
    with np.errstate(invalid="ignore"):
        excursion = np.maximum(np.abs(stroke_max - mid), np.abs(stroke_min - mid))
    util = np.column_stack([utilisation(peak_push, capacities["push_max"]),
                            utilisation(peak_pull, capacities["pull_max"]),
                            utilisation(peak_speed, capacities["speed_max"]),
                            utilisation(peak_power, capacities["power_max"]),
                            utilisation(excursion, half)])
    util[~present] = np.nan
    kappa, t_kappa = {}, {}
    for kind in KINDS:
        c = None if condition is None else condition.get(kind)
        if c is None or np.isnan(c).all():
            kappa[kind], t_kappa[kind] = math.nan, math.nan
        else:
            k = int(np.nanargmax(c))
            kappa[kind], t_kappa[kind] = float(c[k]), float(t[k])
    hanging = {} if cable is None else _hanging(cable, robot, gravity)
    return Envelope(duration=float(t[-1] - t[0]), samples=N, peak_push=peak_push,
                    t_push=t_push, peak_pull=peak_pull, t_pull=t_pull, rms=rms,
                    peak_speed=peak_speed, peak_power=peak_power,
                    mean_abs_power=mean_abs_power, stroke_min=stroke_min,
                    stroke_max=stroke_max, stroke_range=rng, capacities=capacities,
                    utilisation=util, kappa=kappa, t_kappa=t_kappa, **hanging)


def _hanging(cable, robot, gravity) -> dict:
    """The envelope's hanging-load fields of a cable's result
    (:func:`~offshore_crane.dynamics.cable.lift_metrics`)."""
    from offshore_crane.dynamics.cable import lift_metrics
    from offshore_crane.dynamics.cable.tip import sway_angle

    m = lift_metrics(cable, gravity)
    out = dict(sway_max=float(np.max(sway_angle(robot, cable))), tension_min=m.tension_min,
               tension_max=m.tension_max, time_slack=m.time_slack,
               static_tension=m.static_tension, load_limits=robot.load_limits)
    if getattr(cable, "hoist", None) is not None:
        out.update(winch={"pull": m.winch_pull, "speed": m.winch_speed,
                          "acceleration": m.winch_acceleration, "power": m.winch_power},
                   winch_capacities=robot.winch)
    return out


def conditions(result) -> dict:
    """``{kind: (N,) condition numbers}`` of a :class:`offshore_crane.dynamics.Result`."""
    return {"leg": result.condition, "gimbal": result.gimbal, "attitude": result.attitude}
