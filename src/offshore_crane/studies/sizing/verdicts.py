"""Sizing verdicts: every actuator's worst case over runs (or its most probable maximum over an
exposure) against its capacities.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import InputError
from offshore_crane.studies.sizing.envelopes import utilisation, worst_utilisation
from offshore_crane.studies.sizing.extremes import EXPOSURE, MIN_SEEDS, most_probable_maximum


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
        return worst_utilisation(self.utilisation)

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
    util = np.column_stack([utilisation(peaks["push"], caps["push_max"]),
                            utilisation(peaks["pull"], caps["pull_max"]),
                            utilisation(peaks["speed"], caps["speed_max"]),
                            utilisation(peaks["power"], caps["power_max"]),
                            utilisation(peaks["stroke"], half)])
    util[~first.present] = np.nan
    return Verdict(seeds=len(envelopes), basis="gumbel" if gumbel else "observed",
                   exposure=exposure if gumbel else math.nan, record=record, peaks=peaks,
                   observed=observed, utilisation=util)
