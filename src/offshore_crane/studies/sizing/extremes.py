"""Extreme values of irregular sea states: the Gumbel fit of per-seed maxima and the most
probable maximum over an exposure.
"""

from __future__ import annotations

import math

import numpy as np

from offshore_crane.errors import InputError, InsufficientSeedsError
from offshore_crane.scenes.keys import EXTREMES_DEFAULTS, GUMBEL_MIN_RECORDS


#: Fewest seeds (records) a Gumbel fit is made on: with 5 per-record maxima the
#: maximum-likelihood scale is within about ±40 % (one standard deviation) of the true
#: one; fewer give a fit that says nothing (the verdict then rests on the observed maximum
#: and says so).
MIN_SEEDS = GUMBEL_MIN_RECORDS
#: Default exposure of the most probable maximum, full scale [s]: 3 hours, the usual
#: duration of a stationary sea state (DNV-RP-C205).
EXPOSURE = 3600.0 * EXTREMES_DEFAULTS["exposure"]


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


def covers_exposure(duration: float, samples: int, scale: float, exposure: float) -> bool:
    """True when a record of ``duration`` [s] (model scale, ``t[-1] − t[0]``) over
    ``samples`` samples covers ``exposure`` [s] full scale at Froude scale ``scale``: its
    samples span the exposure to within one sample interval (an exposure record's judged
    window, :mod:`offshore_crane.scenes.exposure`, ends on the last sample within it).

    The verdict fits a Gumbel distribution only to maxima of records that cover the
    exposure: it does not extrapolate shorter records to it (docs/sizing.md: on the
    hanging-load scene, 60 s records extrapolated to 3 h overstate the sway's extreme).
    """
    if not (samples > 1 and math.isfinite(duration) and scale > 0):
        return False
    interval = duration / (samples - 1)
    return (duration + interval) * math.sqrt(scale) >= exposure


def most_probable_extreme(values, record: float, exposure: float, gumbel: bool, sign: float = 1.0) -> float:
    """The extreme a verdict uses of per-record extremes ``values (n_seeds,)``: the most
    probable maximum (``sign = 1``) or minimum (``sign = −1``: the maximum of the
    negated values) over ``exposure`` [s] when ``gumbel`` and every value is finite, else
    the observed one."""
    values = sign * np.asarray(values, dtype=float)
    if gumbel and np.isfinite(values).all():
        return sign * most_probable_maximum(values, record, exposure)
    return sign * float(values.max())
