"""Sizing verdicts: every actuator's worst case over runs (or its most probable maximum over an
exposure) against its capacities.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from offshore_crane.errors import InputError
from offshore_crane.studies.sizing.envelopes import CAPACITIES, utilisation, worst_utilisation
from offshore_crane.studies.sizing.loads import WINCH_DEMANDS, load_utilisation
from offshore_crane.studies.sizing.extremes import (EXPOSURE, MIN_SEEDS, covers_exposure,
                                                    most_probable_extreme,
                                                    most_probable_maximum)


@dataclass(frozen=True)
class Verdict:
    """Utilisation of the capacities that a case's records support.

    Attributes:
        seeds: How many records (seeds) it rests on.
        basis: ``"gumbel"`` (most probable maximum over ``exposure``: the Gumbel fit of
            the maxima of at least :data:`MIN_SEEDS` records that each cover the
            exposure), ``"observed"`` (the largest observed peak: fewer records, records
            shorter than the exposure, or a deterministic motion).
        exposure: Full-scale exposure [s] asked for (NaN for a deterministic motion).
        record: Full-scale duration of one record [s] (NaN when not a sea).
        peaks: ``{quantity: (9,)}`` the peak push, pull, speed, power and stroke
            excursion the verdict uses (MPM or observed) [N·m, N, rad/s, m/s, W, rad, m].
        observed: The same, the largest observed over the seeds.
        utilisation: ``(9, 5)`` over :data:`CAPACITIES` (NaN: no capacity, no actuator).
        load: The hanging load's verdict (:class:`LoadVerdict`), or None without a cable.
        limits: ``{capacity: (9,)}`` what each column of ``utilisation`` is judged
            against: the capacities, and half the stroke range for ``stroke`` (inf: none).
        covered: Whether each record covers the exposure
            (:func:`~offshore_crane.studies.sizing.extremes.covers_exposure`; None for a
            deterministic motion).
    """

    seeds: int
    basis: str
    exposure: float
    record: float
    peaks: dict
    observed: dict
    utilisation: np.ndarray
    load: "LoadVerdict | None" = None
    limits: dict | None = None
    covered: bool | None = None

    def worst(self):
        """``(utilisation, actuator, capacity)`` (see :meth:`Envelope.worst`)."""
        return worst_utilisation(self.utilisation)

    @property
    def exceeded(self) -> bool:
        """True when some utilisation exceeds 1 (100 %), the hanging load's included."""
        return bool(np.nan_to_num(self.utilisation, nan=0.0).max(initial=0.0) > 1.0
                    or (self.load is not None and self.load.exceeded))

    def describe(self) -> str:
        """One line: what the verdict rests on, observed or extrapolated, and over what
        exposure."""
        hours = f"{self.exposure / 3600:g} h"
        records = (f"{self.seeds} record{'s' * (self.seeds != 1)} of "
                   f"{_duration(self.record)} full scale each")
        if self.basis == "gumbel":
            return (f"most probable maximum over {hours} full scale: the mode of the Gumbel "
                    f"fit (maximum likelihood) of the maxima of {records}, stationary")
        if math.isnan(self.record):
            return "observed peaks of one deterministic run"
        if self.covered is False:
            return (f"largest observed peak of {records}, shorter than the {hours} exposure: "
                    "observed, not extrapolated (short records do not extrapolate to the "
                    "exposure: docs/sizing.md); judge exposure records for a verdict")
        return (f"largest observed peak of {records}: observed, fewer than {MIN_SEEDS} "
                f"records for a Gumbel fit (the {hours} maximum varies from record to "
                f"record: run {MIN_SEEDS} seeds for its most probable value)")


@dataclass(frozen=True)
class LoadVerdict:
    """The hanging load judged against its limits (``payload.limits``), on the same basis
    as the actuators (most probable extreme over the exposure, or the observed one).

    Attributes:
        sway: Largest sway angle [rad]. tension_max: Largest tension [N].
        tension_min: Smallest tension [N] (the most probable minimum: the Gumbel fit of
            the negated minima).
        static: The static tension m·|g| [N]; ``ratio_min = tension_min / static``.
        observed: ``{"sway", "tension_min", "tension_max"}`` observed over the seeds.
        limits: The :class:`~offshore_crane.robot.description.LoadLimits`.
        utilisation: ``{"sway": sway / limit, "slack": limit ratio / ratio_min,
            "tension": tension_max / limit}`` (NaN: no limit given; inf: the cable goes
            slack, ratio ≤ 0, against a slack limit); with a winch also ``"winch pull"``,
            ``"winch speed"``, ``"winch acceleration"``, ``"winch power"`` against
            ``actuators.winch``.
        winch: ``{"pull", "speed", "acceleration", "power"}`` the winch's extreme demands
            [N, m/s, m/s², W] (empty without a winch).
        winch_capacities: The :class:`WinchCapacities` they are judged against.
    """

    sway: float
    tension_min: float
    tension_max: float
    static: float
    observed: dict
    limits: object
    utilisation: dict
    winch: dict = field(default_factory=dict)
    winch_capacities: object = None

    @property
    def ratio_min(self) -> float:
        """Smallest tension over the static tension [-]."""
        return self.tension_min / self.static if self.static > 0 else math.nan

    @property
    def exceeded(self) -> bool:
        """True when a limit is exceeded (utilisation above 1)."""
        return any(u > 1.0 for u in self.utilisation.values() if not math.isnan(u))


def load_verdict(envelopes, record: float, exposure: float, gumbel: bool):
    """:class:`LoadVerdict` of envelopes with a cable (None without)."""
    first = envelopes[0]
    if math.isnan(first.sway_max) or first.load_limits is None:
        return None

    def extreme(values, sign: float) -> float:
        return most_probable_extreme(values, record, exposure, gumbel, sign)

    observed = {"sway": max(e.sway_max for e in envelopes),
                "tension_min": min(e.tension_min for e in envelopes),
                "tension_max": max(e.tension_max for e in envelopes)}
    sway = extreme([e.sway_max for e in envelopes], 1.0)
    t_max = extreme([e.tension_max for e in envelopes], 1.0)
    t_min = extreme([e.tension_min for e in envelopes], -1.0)
    lim, static = first.load_limits, first.static_tension
    winch = {}
    for key in WINCH_DEMANDS if first.winch else ():   # extrapolated like the rest
        winch[key] = extreme([e.winch[key] for e in envelopes], 1.0)
        observed[f"winch {key}"] = max(e.winch[key] for e in envelopes)
    util = load_utilisation(sway, t_min / static if static > 0 else math.nan, t_max, lim,
                            winch, first.winch_capacities)
    return LoadVerdict(sway=sway, tension_min=t_min, tension_max=t_max, static=static,
                       observed=observed, limits=lim, utilisation=util, winch=winch,
                       winch_capacities=first.winch_capacities)


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
        :class:`Verdict`: the Gumbel most probable maximum with ≥ :data:`MIN_SEEDS`
        records that cover the exposure (:func:`covers_exposure`), else the observed
        maximum.
    """
    envelopes = list(envelopes)
    if not envelopes:
        raise InputError("verdict: no envelope given", name="envelopes")
    first = envelopes[0]
    record = math.nan if scale is None else first.duration * math.sqrt(scale)
    covered = None if scale is None else covers_exposure(first.duration, first.samples,
                                                         scale, exposure)
    gumbel = bool(covered) and len(envelopes) >= MIN_SEEDS
    observed, peaks = {}, {}
    for cap, attr in _PEAKS:
        values = np.array([getattr(e, attr) for e in envelopes])      # (seeds, 9)
        with np.errstate(invalid="ignore"):
            observed[cap] = values.max(axis=0)
        if not gumbel:
            peaks[cap] = observed[cap]
            continue
        out = np.full(9, np.nan)
        for k in range(9):
            column = values[:, k]
            if not np.isnan(column).any():
                out[k] = most_probable_maximum(column, record, max(exposure, record))
        peaks[cap] = out
    caps = first.capacities
    limits = {"push": caps["push_max"], "pull": caps["pull_max"], "speed": caps["speed_max"],
              "power": caps["power_max"],
              "stroke": 0.5 * (first.stroke_range[:, 1] - first.stroke_range[:, 0])}
    util = np.column_stack([utilisation(peaks[c], limits[c]) for c in CAPACITIES])
    util[~first.present] = np.nan
    return Verdict(seeds=len(envelopes), basis="gumbel" if gumbel else "observed",
                   exposure=math.nan if scale is None else exposure, record=record,
                   peaks=peaks, observed=observed, utilisation=util,
                   load=load_verdict(envelopes, record, max(exposure, record), gumbel),
                   limits=limits, covered=covered)


def _duration(seconds: float) -> str:
    """``3 h``, ``268.3 s``: a full-scale record's length for a sentence."""
    hours = seconds / 3600.0
    return f"{hours:.3g} h" if hours >= 0.999 else f"{seconds:.4g} s"
