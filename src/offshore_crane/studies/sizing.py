"""Actuator sizing: the envelope of one run against the actuators' capacities, and the
most probable maximum of a random sea from several seeds (pure NumPy).

An **envelope** (:func:`envelope`) condenses one run ``(t, q, q̇, X)`` into, per actuator
of ``X = [T1, T2, Fs, Fl1..Fl6]`` (``docs/conventions.md``):

- the peak push ``max(X, 0)`` and the peak pull ``max(−X, 0)`` [N·m or N], each with its
  time [s]; the RMS of X;
- the peak speed ``max |v|`` of the actuator's joint: ``q̇7, q̇8`` [rad/s], ``q̇9`` [m/s],
  the leg rates ``l̇_i`` [m/s] (:func:`offshore_crane.robot.kinematics.legs`);
- the peak power ``max |X v|`` and the mean absolute power ``mean |X v|`` [W];
- the stroke used: min and max of the joint position (q7, q8 [rad], q9 [m], leg length
  l_i [m]);
- the utilisation of each capacity of :attr:`offshore_crane.robot.Robot.capacities`:
  ``push = peak push / push_max``, ``pull``, ``speed``, ``power`` likewise, and
  ``stroke = max |p − mid| / half`` over the joint's range ``[lo, hi]`` (the legs' stroke,
  the arm joints' limits, from the robot description): 1 means the motion reaches an end.
  A capacity the description does not give (``inf``) has utilisation NaN ("no limit"),
  never 0.

and for the run: the worst condition number of each singularity kind (leg Jacobian,
U-joint gimbal, attitude) with its time, the worst utilisation with the actuator and
the capacity that govern it, and with a payload on a cable (:mod:`offshore_crane.dynamics.cable`)
the largest sway from the tip's vertical [rad] and the smallest and largest cable
tension [N] (NaN without a cable).

For a random sea a single record's peak is itself random. :func:`verdict` takes the
envelopes of the same case under several seeds: with at least :data:`MIN_SEEDS` of them it
fits a Gumbel distribution to the per-record maxima of every peak quantity by maximum
likelihood (:func:`gumbel_fit`) and extrapolates to the exposure (3 hours full scale by
default): ``n = exposure / record``, with the record's full-scale duration ``T_model ·
√λ`` (Froude), and the most probable maximum of the exposure is the mode
``μ + β ln n`` of the fitted Gumbel(μ, β) (:func:`most_probable_maximum`). With fewer
seeds no fit is made: the verdict rests on the largest observed peak and says so (its
``basis``). ``docs/sizing.md`` has the formulas and the choices.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from offshore_crane.conventions import ACTUATOR_UNITS, ACTUATORS
from offshore_crane.errors import InputError, InsufficientSeedsError

#: Capacities judged, in the order of the utilisation columns.
CAPACITIES = ("push", "pull", "speed", "power", "stroke")
#: Per-actuator quantities of an envelope (``(9,)`` arrays), in row-column order.
QUANTITIES = ("peak_push", "t_push", "peak_pull", "t_pull", "rms", "peak_speed",
              "peak_power", "mean_abs_power", "stroke_min", "stroke_max")
#: The hanging load's columns of an envelope (NaN without a cable): [rad], [N], [N].
CABLE = ("sway_max", "tension_min", "tension_max")
#: Condition-number kinds of a run (:class:`offshore_crane.dynamics.Result`).
KINDS = ("leg", "gimbal", "attitude")
#: Fewest seeds a Gumbel fit is made on: with 5 per-record maxima the maximum-likelihood
#: scale is within about ±40 % (one standard deviation) of the true one; fewer give a fit
#: that says nothing (the verdict then rests on the observed maximum and says so).
MIN_SEEDS = 5
#: Default exposure of the most probable maximum, full scale [s]: 3 hours, the usual
#: duration of a stationary sea state (DNV-RP-C205).
EXPOSURE = 3 * 3600.0
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
        tension_min, tension_max: The cable's tension range [N] (NaN: no cable).
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
        return _worst(self.utilisation)

    def row(self) -> dict:
        """One flat row: ``{actuator}_{quantity}`` and ``{actuator}_util_{capacity}``
        for the 9 actuators (NaN where absent), ``{actuator}_util`` (its worst),
        ``kappa_{kind}``, ``duration_s``, ``samples``, ``worst_util``, ``governing``,
        ``governing_capacity`` (``""`` when none)."""
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
        out.update({k: float(getattr(self, k)) for k in CABLE})
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
    cols += [(k, "float64") for k in CABLE]
    return cols


def _worst(util: np.ndarray):
    if np.isnan(util).all():
        return math.nan, None, None
    k, c = np.unravel_index(np.nanargmax(util), util.shape)
    return float(util[k, c]), ACTUATORS[k], CAPACITIES[c]


def _ratio(value, capacity):
    """``value / capacity``; NaN where the capacity is infinite (not given)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.asarray(value, dtype=float) / capacity
    return np.where(np.isinf(capacity), np.nan, out)


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


def actuator_motion(robot, q, qd, legs: bool = True):
    """Position and rate of each actuator's joint.

    The leg lengths and rates are evaluated by the kinematics' one text
    (:mod:`offshore_crane.robot.kinematics.formulas`: ``attitude``, ``platform_rates``,
    ``leg_geometry``, ``point_velocity``) on NumPy arrays, vectorised over the samples:
    ``l_i = |O2 + R s_i − P_i|``, ``l̇_i = u_i · (v + ω × R s_i)``; the same values as
    :func:`offshore_crane.robot.kinematics.legs` without its partial velocities and frames.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q, qd: ``(N, 9)`` [m, rad], [m/s, rad/s].
        legs: False: leave the leg columns NaN (the legs not evaluated).

    Returns:
        ``(p, v)`` each ``(N, 9)``: ``p = [q7, q8, q9, l1..l6]`` [rad, m] and its rate
        ``v = [q̇7, q̇8, q̇9, l̇1..l̇6]`` [rad/s, m/s].
    """
    N = len(q)
    p, v = np.full((N, 9), np.nan), np.full((N, 9), np.nan)
    p[:, :3], v[:, :3] = q[:, 6:9], qd[:, 6:9]
    if legs:
        from offshore_crane.robot.kinematics import formulas as F

        m = robot.hybrid
        qT, qdT = q.T, qd.T
        R, w4, w5, _ = F.attitude(qT)
        omega, _ = F.platform_rates(w4, w5, qdT, qdT)
        origin, velocity = (qT[0], qT[1], qT[2]), (qdT[0], qdT[1], qdT[2])
        for i in range(len(m.R_base_U)):
            U = m.R_base_U[i]
            r, _, length, _, u, *_ = F.leg_geometry(origin, R, m.p_platform_S[i],
                                                    m.p_base_P[i], U[:, 0], U[:, 1],
                                                    U[:, 2])
            p[:, 3 + i] = length
            v[:, 3 + i] = F.dot(u, F.point_velocity(velocity, omega, r))
    return p, v


def _peak(x: np.ndarray, t: np.ndarray):
    """``max(x, 0)`` per column and its time (NaN when x never exceeds 0), over the
    rows; NaN columns give NaN."""
    k = np.argmax(np.where(np.isnan(x), -np.inf, x), axis=0)
    top = x[k, np.arange(x.shape[1])]
    peak = np.where(np.isnan(top), np.nan, np.maximum(top, 0.0))
    when = np.where(top > 0.0, t[k], np.nan)
    return peak, when


def envelope(robot, t, q, qd, X, condition=None, arm: bool | None = None,
             legs: bool | None = None, cable=None) -> Envelope:
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
    util = np.column_stack([_ratio(peak_push, capacities["push_max"]),
                            _ratio(peak_pull, capacities["pull_max"]),
                            _ratio(peak_speed, capacities["speed_max"]),
                            _ratio(peak_power, capacities["power_max"]),
                            _ratio(excursion, half)])
    util[~present] = np.nan
    kappa, t_kappa = {}, {}
    for kind in KINDS:
        c = None if condition is None else condition.get(kind)
        if c is None or np.isnan(c).all():
            kappa[kind], t_kappa[kind] = math.nan, math.nan
        else:
            k = int(np.nanargmax(c))
            kappa[kind], t_kappa[kind] = float(c[k]), float(t[k])
    hanging = {} if cable is None else dict(
        sway_max=float(cable.sway_angle.max()), tension_min=float(cable.tension.min()),
        tension_max=float(cable.tension.max()))
    return Envelope(duration=float(t[-1] - t[0]), samples=N, peak_push=peak_push,
                    t_push=t_push, peak_pull=peak_pull, t_pull=t_pull, rms=rms,
                    peak_speed=peak_speed, peak_power=peak_power,
                    mean_abs_power=mean_abs_power, stroke_min=stroke_min,
                    stroke_max=stroke_max, stroke_range=rng, capacities=capacities,
                    utilisation=util, kappa=kappa, t_kappa=t_kappa, **hanging)


def conditions(result) -> dict:
    """``{kind: (N,) condition numbers}`` of a :class:`offshore_crane.dynamics.Result`."""
    return {"leg": result.condition, "gimbal": result.gimbal, "attitude": result.attitude}


# --------------------------------------------------------------------------- Gumbel
def gumbel_fit(maxima) -> tuple[float, float]:
    """Maximum-likelihood Gumbel (largest values) fit ``(μ, β)`` of per-record maxima.

    The likelihood equations of Gumbel(μ, β), ``F(x) = exp(−exp(−(x − μ)/β))``, reduce to
    one equation in β, ``β = x̄ − Σ x e^{−x/β} / Σ e^{−x/β}``, solved here by bisection
    (its left side minus its right side increases with β), then
    ``μ = −β ln(mean e^{−x/β})``. Identical maxima give ``(x, 0)``.

    Args:
        maxima: ``(n,)`` finite values, n ≥ :data:`MIN_SEEDS`.

    Returns:
        ``(μ, β)``: location and scale, in the unit of the maxima.

    Raises:
        InsufficientSeedsError: fewer than :data:`MIN_SEEDS` values.
        InputError: a non-finite value.
    """
    x = np.asarray(maxima, dtype=float).ravel()
    if x.size < MIN_SEEDS:
        raise InsufficientSeedsError(
            f"a Gumbel fit needs at least {MIN_SEEDS} per-record maxima (seeds), got "
            f"{x.size}: run more seeds", seeds=int(x.size), minimum=MIN_SEEDS)
    if not np.isfinite(x).all():
        i = int(np.flatnonzero(~np.isfinite(x))[0])
        raise InputError(f"gumbel_fit: maxima[{i}] = {float(x[i])!r} is not finite",
                         name="maxima", index=i)
    m, s = float(x.mean()), float(x.std())
    if s == 0.0 or s <= 1e-14 * abs(m):
        return m, 0.0
    z = (x - m) / s                        # the fit is location-scale equivariant

    def excess(b):                         # increasing in b; its root is the ML scale
        w = -z / b
        w = np.exp(w - w.max())
        return b - (0.0 - float((z * w).sum() / w.sum()))

    lo, hi = 1e-3, 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if excess(mid) > 0.0:
            hi = mid
        else:
            lo = mid
        if hi - lo <= 1e-15 * hi:
            break
    b = 0.5 * (lo + hi)
    w = -z / b
    mu = -b * (float(w.max()) + math.log(float(np.exp(w - w.max()).mean())))
    return m + s * mu, s * b


def most_probable_maximum(maxima, record: float, exposure: float = EXPOSURE) -> float:
    """Most probable maximum over ``exposure`` of a process whose per-record maxima are
    ``maxima``: the mode ``μ + β ln n`` of the Gumbel fit (:func:`gumbel_fit`) raised to
    ``n = exposure / record`` independent records.

    Args:
        maxima: ``(n_seeds,)`` maxima of records of equal duration.
        record: Full-scale duration of one record [s].
        exposure: Full-scale exposure [s], ≥ ``record``.

    Raises:
        InsufficientSeedsError: fewer than :data:`MIN_SEEDS` maxima.
        InputError: ``record`` or ``exposure`` not positive and finite, or an exposure
            shorter than one record.
    """
    for name, v in (("record", record), ("exposure", exposure)):
        if not (isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v > 0):
            raise InputError(f"most_probable_maximum: {name} = {v!r} must be a positive "
                             "duration [s]", name=name)
    if exposure < record:
        raise InputError(f"most_probable_maximum: exposure {exposure:g} s is shorter than "
                         f"one record ({record:g} s, full scale): give an exposure of at "
                         "least one record", name="exposure")
    mu, beta = gumbel_fit(maxima)
    return mu + beta * math.log(exposure / record)


@dataclass(frozen=True)
class Verdict:
    """Utilisation of the capacities that a case's records support.

    Attributes:
        seeds: How many records (seeds) it rests on.
        basis: ``"gumbel"`` (most probable maximum over ``exposure``), ``"observed"``
            (the largest observed peak: fewer than :data:`MIN_SEEDS` seeds, or a
            deterministic motion).
        exposure: Full-scale exposure [s] (``"gumbel"``), else NaN.
        record: Full-scale duration of one record [s] (NaN when not a sea).
        peaks: ``{quantity: (9,)}`` the peak push, pull, speed, power and stroke
            excursion the verdict uses (MPM or observed) [N·m, N, rad/s, m/s, W, rad, m].
        observed: The same, the largest observed over the seeds.
        utilisation: ``(9, 5)`` over :data:`CAPACITIES` (NaN: no capacity, no actuator).
    """

    seeds: int
    basis: str
    exposure: float
    record: float
    peaks: dict
    observed: dict
    utilisation: np.ndarray

    def worst(self):
        """``(utilisation, actuator, capacity)`` (see :meth:`Envelope.worst`)."""
        return _worst(self.utilisation)

    @property
    def exceeded(self) -> bool:
        """True when some utilisation exceeds 1 (100 %)."""
        return bool(np.nan_to_num(self.utilisation, nan=0.0).max(initial=0.0) > 1.0)

    def describe(self) -> str:
        """One line: what the verdict rests on."""
        if self.basis == "gumbel":
            return (f"most probable maximum over {self.exposure / 3600:g} h full scale "
                    f"(Gumbel, maximum likelihood, {self.seeds} seeds of "
                    f"{self.record:.4g} s full scale each)")
        if math.isnan(self.record):
            return "observed peaks of one deterministic run"
        return (f"largest observed peak of {self.seeds} seed{'s' * (self.seeds != 1)} "
                f"({self.record:.4g} s full scale each): fewer than {MIN_SEEDS} seeds, no "
                "Gumbel fit; the extreme over a longer exposure is likely higher")


#: Quantities the verdict extrapolates, with the envelope attribute and the capacity.
_PEAKS = (("push", "peak_push"), ("pull", "peak_pull"), ("speed", "peak_speed"),
          ("power", "peak_power"), ("stroke", "stroke_excursion"))


def verdict(envelopes, scale: float | None = None, exposure: float = EXPOSURE) -> Verdict:
    """The verdict of a case from the envelopes of its seeds.

    Args:
        envelopes: One :class:`Envelope` per seed (same case, same record duration), or
            one for a deterministic motion.
        scale: Froude scale λ of a sea case (record full-scale duration ``T · √λ``), or
            None for a deterministic motion (the observed peaks decide).
        exposure: Full-scale exposure [s] of the most probable maximum.

    Returns:
        :class:`Verdict`; the Gumbel fit with ≥ :data:`MIN_SEEDS` envelopes and a scale,
        else the observed maximum.
    """
    envelopes = list(envelopes)
    if not envelopes:
        raise InputError("verdict: no envelope given", name="envelopes")
    first = envelopes[0]
    record = math.nan if scale is None else first.duration * math.sqrt(scale)
    observed, peaks = {}, {}
    for cap, attr in _PEAKS:
        values = np.array([getattr(e, attr) for e in envelopes])      # (seeds, 9)
        with np.errstate(invalid="ignore"):
            observed[cap] = values.max(axis=0)
        if scale is None or len(envelopes) < MIN_SEEDS:
            peaks[cap] = observed[cap]
            continue
        out = np.full(9, np.nan)
        for k in range(9):
            column = values[:, k]
            if not np.isnan(column).any():
                out[k] = most_probable_maximum(column, record, exposure)
        peaks[cap] = out
    gumbel = scale is not None and len(envelopes) >= MIN_SEEDS
    caps = first.capacities
    half = 0.5 * (first.stroke_range[:, 1] - first.stroke_range[:, 0])
    util = np.column_stack([_ratio(peaks["push"], caps["push_max"]),
                            _ratio(peaks["pull"], caps["pull_max"]),
                            _ratio(peaks["speed"], caps["speed_max"]),
                            _ratio(peaks["power"], caps["power_max"]),
                            _ratio(peaks["stroke"], half)])
    util[~first.present] = np.nan
    return Verdict(seeds=len(envelopes), basis="gumbel" if gumbel else "observed",
                   exposure=exposure if gumbel else math.nan, record=record, peaks=peaks,
                   observed=observed, utilisation=util)


# --------------------------------------------------------------------------- report
def _fmt(x: float, spec: str = ".4g") -> str:
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def _pct(x: float) -> str:
    return "—" if math.isnan(x) else f"{100 * x:.1f}"


def format_envelope(env: Envelope) -> str:
    """The envelope as a fixed-width table (one line per actuator the run has)."""
    lines = [f"{'actuator':<9}{'unit':<5}{'peak push':>11}{'at t [s]':>9}{'peak pull':>11}"
             f"{'at t [s]':>9}{'RMS':>10}{'peak speed':>12}{'peak |P| W':>12}"
             f"{'mean |P| W':>12}{'stroke used':>22}"]
    for k, name in enumerate(ACTUATORS):
        if not env.present[k]:
            continue
        stroke = f"{env.stroke_min[k]:.4g}..{env.stroke_max[k]:.4g} {POSITION_UNITS[k]}"
        lines.append(f"{name:<9}{ACTUATOR_UNITS[k]:<5}{env.peak_push[k]:>11.4g}"
                     f"{_fmt(env.t_push[k], '.2f'):>9}{env.peak_pull[k]:>11.4g}"
                     f"{_fmt(env.t_pull[k], '.2f'):>9}{env.rms[k]:>10.4g}"
                     f"{env.peak_speed[k]:>8.4g} {SPEED_UNITS[k]:<3}"
                     f"{env.peak_power[k]:>12.4g}{env.mean_abs_power[k]:>12.4g}"
                     f"{stroke:>22}")
    for kind in KINDS:
        if not math.isnan(env.kappa[kind]):
            lines.append(f"worst {kind} condition number: {env.kappa[kind]:.4g} at "
                         f"t = {env.t_kappa[kind]:.2f} s")
    if not math.isnan(env.sway_max):
        lines.append(f"hanging load: max sway {env.sway_max:.4g} rad from the tip's "
                     f"vertical, cable tension {env.tension_min:.4g}..{env.tension_max:.4g} N")
    return "\n".join(lines)


def format_verdict(v: Verdict, present) -> str:
    """The utilisation table of a verdict, in percent ('—': no capacity given)."""
    lines = [f"utilisation [%]: {v.describe()}",
             f"{'actuator':<9}" + "".join(f"{c:>9}" for c in CAPACITIES) + f"{'worst':>9}"]
    for k, name in enumerate(ACTUATORS):
        if not present[k]:
            continue
        u = v.utilisation[k]
        worst = math.nan if np.isnan(u).all() else float(np.nanmax(u))
        flag = "  EXCEEDED" if worst > 1.0 else ""
        lines.append(f"{name:<9}" + "".join(f"{_pct(x):>9}" for x in u)
                     + f"{_pct(worst):>9}{flag}")
    worst, who, cap = v.worst()
    if who is None:
        lines.append("no capacity is given for these actuators: nothing to judge")
    else:
        lines.append(f"worst: {who} {cap} at {100 * worst:.1f} % "
                     f"({'EXCEEDS its capacity' if worst > 1.0 else 'within capacity'})")
    return "\n".join(lines)
