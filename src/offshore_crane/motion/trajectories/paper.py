"""The paper's Table 1 trajectory (sums of cosines, analytic rates and accelerations) and the
uniform time axes every motion is sampled on.
"""

from __future__ import annotations

import math

import numpy as np

from offshore_crane.errors import TrajectoryError
from offshore_crane.validation import as_real, check_memory


#: Period of the slowest Table 1 components (q4, q5, q6, q9 at 0.2 rad/s) [s]. Over it
#: q1..q3 make two cycles but q7, q8 (0.5 rad/s) make 2.5 and end with the opposite sign;
#: the whole table repeats only after 2 * TABLE1_PERIOD = 20 pi s.
TABLE1_PERIOD = 10.0 * math.pi
#: Default sampling rate of :func:`time_grid` [Hz].
DEFAULT_RATE = 100.0


#: Largest number of samples :func:`time_grid` accepts (about 7 GB for t, q, qd, qdd).
MAX_SAMPLES = 10**8

# Table 1 as q_j(t) = offset_j + amplitude_j * cos(omega_j * t + phase_j), j = 1..9.
_TABLE1_OFFSET = np.array([0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])  # [m or rad]
_TABLE1_AMPLITUDE = np.array([0.03, 0.02, 0.035, math.pi / 9, math.pi / 9, math.pi / 9,
                              math.pi, math.pi / 3, 0.15])  # [m or rad]
_TABLE1_OMEGA = np.array([0.4, 0.4, 0.4, 0.2, 0.2, 0.2, 0.5, 0.5, 0.2])  # [rad/s]
_TABLE1_PHASE = np.array([0.0, 0.5, 0.0, 0.2, 0.3, 0.4, 0.0, 0.0, math.pi / 2])  # [rad]


def _positive_finite(value, name: str, unit: str, hint: str) -> float:
    """Return ``value`` as a float, or raise TrajectoryError if it is not finite and > 0."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise TrajectoryError(
            f"{name} must be a positive number [{unit}], got {value!r}: {hint}.", name=name
        ) from None
    if not (math.isfinite(x) and x > 0.0):
        raise TrajectoryError(
            f"{name} must be positive and finite [{unit}], got {x!r}: {hint}.", name=name)
    return x


def time_grid(duration: float = TABLE1_PERIOD, rate: float = DEFAULT_RATE) -> np.ndarray:
    """Uniform time axis ``t = arange(N) / rate`` starting at 0.

    ``N = floor(duration * rate + 1e-9) + 1``, so both ends are included when
    ``duration * rate`` is an integer; otherwise the last sample is the last one before
    ``duration``. The defaults give 3142 samples from 0 to 31.41 s.

    Args:
        duration: Length of the time span [s], > 0.
        rate: Sampling rate [Hz], > 0.

    Returns:
        ``t`` ``(N,)`` [s].

    Raises:
        TrajectoryError: ``duration`` or ``rate`` not positive and finite, or more than
            ``MAX_SAMPLES`` samples.
    """
    duration = _positive_finite(duration, "duration", "s", "give the length of the trajectory")
    rate = _positive_finite(rate, "rate", "Hz", "give the sampling rate")
    steps = duration * rate + 1e-9
    if steps >= MAX_SAMPLES:
        raise TrajectoryError(
            f"duration={duration!r} s at rate={rate!r} Hz gives about {steps:.3g} samples, "
            f"more than the limit {MAX_SAMPLES}: shorten the duration or lower the rate.",
            name="rate",
        )
    n = math.floor(steps) + 1
    check_memory(28.0 * 8.0 * n, f"{duration:g} s at {rate:g} Hz ({n} samples of t, q, qd, qdd)",
                 "shorten the duration or lower the rate", "duration")
    return np.arange(n) / rate


def table1(t):
    """The paper's Table 1 trajectory and its analytic first and second derivatives.

    ``q_j(t) = c_j + a_j cos(w_j t + p_j)``, ``qd_j = -a_j w_j sin(w_j t + p_j)``,
    ``qdd_j = -a_j w_j² cos(w_j t + p_j)``, with (t in [s])::

        q1 = 0.03 cos(0.4t)               q6 = (pi/9) cos(0.2t + 0.4)
        q2 = 0.02 cos(0.4t + 0.5)         q7 = pi cos(0.5t)
        q3 = 0.5 + 0.035 cos(0.4t)        q8 = (pi/3) cos(0.5t)
        q4 = (pi/9) cos(0.2t + 0.2)       q9 = 0.15 cos(0.2t + pi/2)
        q5 = (pi/9) cos(0.2t + 0.3)

    Args:
        t: Time [s], scalar or ``(N,)``.

    Returns:
        ``(q, qd, qdd)``, each ``(9,)`` for a scalar ``t`` or ``(N, 9)`` for ``t`` ``(N,)``,
        in [m or rad], [m/s or rad/s], [m/s² or rad/s²].

    Raises:
        TrajectoryError: ``t`` is not numeric, has more than one axis, or holds a NaN or
            infinity (``index`` is the first such sample, None for a scalar).
    """
    t = as_real("t", t, TrajectoryError, "s")
    if t.ndim > 1:
        raise TrajectoryError(
            f"t must be a scalar or a 1-D array of times [s], got shape {t.shape}: "
            "flatten it first.", name="t")
    finite = np.isfinite(t)
    if not finite.all():
        index = None if t.ndim == 0 else int(np.argmin(finite))
        value = float(t.item() if t.ndim == 0 else t[index])
        where = "" if index is None else f" at sample {index}"
        raise TrajectoryError(
            f"t is not finite{where} (t = {value!r}): give finite times [s].",
            name="t", index=index)
    phase = np.multiply.outer(t, _TABLE1_OMEGA) + _TABLE1_PHASE  # (..., 9) [rad]
    cos = np.cos(phase)
    q = _TABLE1_OFFSET + _TABLE1_AMPLITUDE * cos
    qd = -(_TABLE1_AMPLITUDE * _TABLE1_OMEGA) * np.sin(phase)
    qdd = -(_TABLE1_AMPLITUDE * _TABLE1_OMEGA**2) * cos
    return q, qd, qdd
