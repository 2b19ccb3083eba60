"""The ship's motion from a sea state: random-phase synthesis of spectrum x RAOs at any times
(direct sums or FFT on uniform grids), response spectra and Welch estimates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from offshore_crane.errors import SeaStateError
from offshore_crane.motion.operations import as_times
from offshore_crane.motion.sea.arguments import (DEFAULT_DIRECTIONS, GRID_EPS, SCALE_HINT,
                                                 integer, real, sea_arguments, vector3)
from offshore_crane.motion.sea.raos import RAOTable, VESSELS, vessel_raos
from offshore_crane.motion.sea.spectra import default_gamma, spectrum, spreading_directions
from offshore_crane.validation import check_memory, thread_count


# Times within this many units in the last place of the largest |t| of a uniform grid
# count as that grid (arange(n) / rate * sqrt(scale) is off by a few ulp); the FFT path
# then evaluates at the exact grid times, a difference below the direct path's own
# round-off of omega * t.
_GRID_TOL_ULPS = 64.0
# A sea state whose spectrum puts less than this share of its variance m0 = Hs²/16 inside
# the RAO table's band is refused: its record's standard deviation would be under a tenth
# of the one the sea state implies (typical seas put over 95 % inside: Tp 4..40 s on the
# supply vessel's 0.1..3.1 rad/s).
BAND_SHARE_MIN = 0.01
# Direct summation works on blocks of at most this many (time, component) pairs
# (4 M doubles: 32 MB per temporary array).
_DIRECT_BLOCK = 1 << 22


# ------------------------------------------------------------------------------ synthesis
def _smooth_length(n: int) -> int:
    """Smallest integer >= n whose prime factors are 2, 3 and 5 (a fast FFT length)."""
    best = 1 << max(0, (n - 1).bit_length())
    p5 = 1
    while p5 < best:
        p35 = p5
        while p35 < best:
            m = p35
            while m < n:
                m *= 2
            best = min(best, m)
            p35 *= 3
        p5 *= 5
    return best


def _direct(coef: np.ndarray, omega: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``Re Σ_j coef[j] e^{i ω_j t}`` at every ``t``: ``(n, C)``, by blocks of samples."""
    out = np.empty((t.size, coef.shape[1]))
    step = max(1, _DIRECT_BLOCK // max(1, omega.size))
    re, im = np.ascontiguousarray(coef.real), np.ascontiguousarray(coef.imag)
    for a in range(0, t.size, step):
        phase = np.multiply.outer(t[a:a + step], omega)
        out[a:a + step] = np.cos(phase) @ re - np.sin(phase) @ im
    return out


def _fft(coef: np.ndarray, harmonics: np.ndarray, d_omega: float, t0: float, L: int,
         n: int, threads: int = 1) -> np.ndarray:
    """``Re Σ_j coef[j] e^{i j Δω (t0 + m T/L)}`` for m = 0..n-1 (``T = 2π/Δω``): ``(n, C)``
    (a transposed view of channel-major memory).

    Exact for any harmonics (those above L/2 fold onto their alias with the conjugate
    coefficient; the samples are the same numbers): one inverse real FFT of length L
    per channel, the channels shared among ``threads`` threads (NumPy's FFT releases the
    GIL), each filling one spectrum of its own (only the components' bins are non-zero)
    and transforming it straight into its row of the result.
    """
    b = coef * np.exp(1j * (harmonics * d_omega * t0))[:, None]
    k = harmonics % L
    upper = k > L // 2
    k = np.where(upper, L - k, k)
    b = np.where(upper[:, None], b.conj(), b)
    b *= np.where((k == 0) | (2 * k == L), float(L), 0.5 * L)[:, None]
    unique = np.unique(k).size == k.size
    x = np.empty((coef.shape[1], L))

    def channels(rows):
        spec = np.zeros(L // 2 + 1, dtype=complex)
        for c in rows:
            if unique:
                spec[k] = b[:, c]
            else:
                spec[k] = 0.0
                np.add.at(spec, k, b[:, c])
            np.fft.irfft(spec, n=L, out=x[c])

    parts = np.array_split(np.arange(len(x)), min(threads, len(x)))
    if len(parts) == 1:
        channels(parts[0])
    else:
        from concurrent.futures import ThreadPoolExecutor

        with ThreadPoolExecutor(len(parts)) as pool:
            list(pool.map(channels, parts))
    x = x.T
    return x[:n] if n <= L else x[np.arange(n) % L]     # n = L + 1: t0 + T repeats t0


@dataclass(frozen=True, eq=False)
class ShipMotion:
    """A vessel's wave-frequency motion at full scale, as frequency components.

    ``x_d(t) = Re Σ_j coefficients[j, d] e^{i ω_j t}`` for the six :data:`DOFS` at the
    chosen point, ``ω_j = harmonics[j] · d_omega``. Call it at any times in
    ``[start, start + repetition_period]``. Build it with :func:`sea_state`.

    Attributes:
        d_omega: Frequency step Δω [rad/s].
        harmonics: ``(M,)`` integers j of the components.
        coefficients: ``(M, 6)`` complex amplitudes [m, rad] at the point (after the
            rigid-body transfer).
        elevation_coefficients: ``(M,)`` complex amplitudes of the wave elevation at the
            RAO table's reference point [m] (the same components: only the frequencies
            of the table's band).
        start: First time of the record [s].
        duration: The record's span the frequency grid was designed for [s].
        rate: The sampling rate it was designed for [Hz] (FFT grid ``start + m/rate``).
        sea: The sea state and options it was built from (hs, tp, heading_deg, kind,
            gamma, seed, vessel, point, spreading, directions, highpass).
    """

    d_omega: float
    harmonics: np.ndarray
    coefficients: np.ndarray
    elevation_coefficients: np.ndarray
    start: float
    duration: float
    rate: float
    sea: dict = field(default_factory=dict)

    @property
    def omega(self) -> np.ndarray:
        """``(M,)`` component frequencies [rad/s]."""
        return self.harmonics * self.d_omega

    @property
    def repetition_period(self) -> float:
        """``2π/Δω`` [s]: the record repeats after it (> :attr:`duration` by design)."""
        return 2.0 * math.pi / self.d_omega

    @cached_property
    def _channels(self) -> np.ndarray:
        """``(M, 18)`` complex: motion, velocity (``iω c``), acceleration (``−ω² c``)."""
        w = self.omega[:, None]
        c = self.coefficients
        return np.hstack([c, 1j * w * c, -(w * w) * c])

    def variance(self) -> np.ndarray:
        """``(6,)`` variance of each DOF over a repetition period, ``Σ |c_j|²/2``."""
        return 0.5 * (np.abs(self.coefficients) ** 2).sum(axis=0)

    def _grid(self, t: np.ndarray):
        """``(t0, L)`` when ``t`` is (to round-off) ``t0 + m T/L``, m = 0..n-1, else None."""
        n = t.size
        if n < 2 or t[-1] <= t[0]:
            return None
        period = self.repetition_period
        L = int(round(period * (n - 1) / (t[-1] - t[0])))
        if L < 2:
            return None
        grid = t[0] + np.arange(n) * (period / L)
        tol = _GRID_TOL_ULPS * np.spacing(max(abs(t[0]), abs(t[-1])))
        if np.abs(grid - t).max() > tol:
            return None
        return float(t[0]), L

    def _evaluate(self, coef: np.ndarray, t, method: str, threads: int = 1):
        if method not in ("auto", "fft", "direct"):
            raise SeaStateError(f"unknown method {method!r}: use 'auto', 'fft' or 'direct'",
                                name="method")
        t, scalar = as_times(t)
        lo, hi = self.start, self.start + self.repetition_period
        slack = _GRID_TOL_ULPS * np.spacing(max(abs(lo), abs(hi)))
        outside = (t < lo - slack) | (t > hi + slack)
        if outside.any():
            k = int(np.argmax(outside))
            raise SeaStateError(
                f"t[{k}] = {t[k]:.9g} s is outside [{lo:.9g}, {hi:.9g}] s, the span on which "
                f"this sea does not repeat (repetition period {hi - lo:.9g} s): build the "
                "sea for a longer duration", name="t", index=k)
        plan = self._grid(t) if method != "direct" else None
        if method == "fft" and plan is None:
            raise SeaStateError("method 'fft' needs uniform times whose step divides the "
                                f"repetition period {self.repetition_period:.9g} s an integer "
                                "number of times: use method 'auto'", name="method")
        omega = self.omega
        if plan is not None and (method == "fft" or t.size * omega.size
                                 >= plan[1] * math.log2(plan[1])):
            out = _fft(coef, self.harmonics, self.d_omega, plan[0], plan[1], t.size,
                       thread_count(threads))
        else:
            out = _direct(coef, omega, t)
        return out, scalar

    def __call__(self, t, method: str = "auto", threads: int = 1):
        """Motion, velocity, acceleration at times ``t`` (full scale).

        Args:
            t: Times [s], scalar or ``(n,)``, inside ``[start, start +
                repetition_period]``; any order and spacing.
            method: ``"auto"`` (FFT on a compatible uniform grid when it is cheaper,
                else direct summation), ``"fft"`` or ``"direct"``; they agree to
                round-off.
            threads: Threads sharing the FFT's 18 channels (capped at the CPU count);
                the same numbers in any count.

        Returns:
            ``(motion, velocity, acceleration)``, each ``(n, 6)`` (``(6,)`` for a scalar)
            in :data:`DOFS` order [m, rad], [m/s, rad/s], [m/s², rad/s²], vessel axes.

        Raises:
            SeaStateError: non-finite times, times outside the non-repeating span.
            InputError: a bad ``threads``.
        """
        out, scalar = self._evaluate(self._channels, t, method, threads)
        parts = tuple(np.ascontiguousarray(out[:, 6 * i:6 * i + 6]) for i in range(3))
        return tuple(p[0] for p in parts) if scalar else parts

    def side_by_side(self, t, method: str = "auto", threads: int = 1) -> np.ndarray:
        """:meth:`__call__`'s three results as the columns of one new ``(n, 18)`` array
        (motion, velocity, acceleration), ``t`` ``(n,)``: no copies into three arrays,
        for callers that take columns of it anyway (or scale it in place). On the FFT
        path it is column-major (the FFT's rows seen transposed); ``threads`` as
        :meth:`__call__`.

        Raises:
            SeaStateError: as :meth:`__call__`; InputError: a bad ``threads``.
        """
        return self._evaluate(self._channels, np.atleast_1d(t), method, threads)[0]

    def elevation(self, t, method: str = "auto"):
        """Wave elevation at the RAO table's reference point [m] (table's band only).

        Returns:
            ``(n,)`` [m] (a float for a scalar ``t``).
        """
        out, scalar = self._evaluate(self.elevation_coefficients[:, None], t, method)
        return float(out[0, 0]) if scalar else out[:, 0].copy()


def _checked(hs, tp, heading_deg, vessel, seed, kind, gamma, point, spreading, directions,
             highpass):
    """The sea-state arguments checked (one text for :func:`sea_state` and
    :func:`check_arguments`), with the vessel's table and the spreading directions."""
    hs, tp, heading, kind, gamma = sea_arguments(hs, tp, heading_deg, kind, gamma)
    seed = integer(seed, "seed", 0, "give a non-negative integer seed")
    r = vector3(point, "point", "m")
    highpass = real(highpass, "highpass", "rad/s", "give the cut-off frequency >= 0, or "
                     "None", low=0.0, low_open=False, allow_none=True)
    offsets, weights = spreading_directions(spreading, directions)
    table = vessel_raos(vessel)
    table(table.omega[:1], heading + offsets)        # every direction covered, or raise
    return hs, tp, heading, kind, gamma, seed, r, highpass, table, offsets, weights


def check_arguments(hs, tp, heading_deg, scale, *, vessel="supply", seed=0,
                    kind: str = "jonswap", gamma=None, point=(0.0, 0.0, 0.0), spreading=None,
                    directions: int = DEFAULT_DIRECTIONS, highpass=None,
                    operation=None) -> None:
    """Check :func:`sea_motion`'s sea arguments without building the motion (what a scene
    file is checked with when it is read): the same checks, the same messages.

    Raises:
        SeaStateError: the first bad argument (``name`` says which).
    """
    _checked(hs, tp, heading_deg, vessel, seed, kind, gamma, point, spreading, directions,
             highpass)
    real(scale, "scale", "-", SCALE_HINT, low=0.0)
    if operation is not None:
        from offshore_crane.motion.operations import Operation

        if not isinstance(operation, Operation):
            Operation.from_waypoints(operation)


def vessel_names() -> tuple:
    """Names of the shipped vessels (``vessel="supply"``)."""
    return tuple(VESSELS)


def sea_state(hs, tp, heading_deg, duration, rate, *, vessel="supply", seed=0,
              kind: str = "jonswap", gamma=None, point=(0.0, 0.0, 0.0), spreading=None,
              directions: int = DEFAULT_DIRECTIONS, highpass=None,
              start: float = 0.0) -> ShipMotion:
    """Build the frequency components of a vessel's motion in a sea state (full scale).

    The frequency grid is designed for the record ``start + m/rate``, m = 0..N−1 with
    ``N = floor(duration · rate) + 1``: ``Δω = 2π/(L/rate)`` with L the smallest
    5-smooth integer >= N, so the record does not repeat within it (repetition period
    ``L/rate >= N/rate > duration``) and the FFT path applies on it. Components:
    ``ω_j = j Δω`` inside the RAO table's frequency band, ``S(ω_j) > 0``, and
    ``ω_j >= highpass``; for each (ω_j, direction θ_k) the phase is
    ``2π · rng.random()`` drawn in the order of all harmonics of the band × directions
    (so a high-pass drops components without changing the others' phases).

    Args:
        hs: Significant wave height [m], > 0.
        tp: Peak period [s], > 0.
        heading_deg: Mean wave heading [deg] (180 head seas, 90 from starboard).
        duration: Span of the record [s], > 0.
        rate: Sampling rate of the record [Hz], > 0.
        vessel: Packaged vessel name, CSV path or :class:`RAOTable`.
        seed: Seed of ``numpy.random.default_rng`` (integer >= 0).
        kind, gamma: Spectrum (:func:`spectrum`).
        point: ``(3,)`` point of the vessel [m], vessel axes, relative to the table's
            reference point (the crane's base); motion there by ``x + θ × r``.
        spreading: cos-2s spreading exponent s (> 0), or None for long-crested seas.
        directions: Number of spreading directions (:func:`spreading_directions`).
        highpass: Cut-off [rad/s] (full scale): components below it are left out (an
            ideal high-pass, exact in the frequency domain: no transient, no phase
            shift), e.g. to remove slow surge, sway and yaw; None keeps all.
        start: First time of the record [s].

    Returns:
        :class:`ShipMotion`.

    Raises:
        SeaStateError: any bad argument; a heading the table does not cover; a record
            too short to hold one frequency of the table's band.
    """
    duration = real(duration, "duration", "s", "give the record's length", low=0.0)
    rate = real(rate, "rate", "Hz", "give the sampling rate", low=0.0)
    start = real(start, "start", "s", "give the record's first time")
    hs, tp, heading, kind, gamma, seed, r, highpass, table, offsets, weights = _checked(
        hs, tp, heading_deg, vessel, seed, kind, gamma, point, spreading, directions,
        highpass)
    if kind == "jonswap" and gamma is None:
        gamma = default_gamma(hs, tp)
    n = math.floor(duration * rate + GRID_EPS) + 1
    check_memory(3 * 6 * 8.0 * n + 16.0 * _smooth_length(n),
                 f"a ship's motion of {duration:g} s at {rate:g} Hz ({n} samples)",
                 "shorten the duration or lower the rate", "duration")
    L = _smooth_length(n)
    d_omega = 2.0 * math.pi * rate / L
    j_lo = max(1, math.ceil(table.omega[0] / d_omega))
    j_hi = math.floor(table.omega[-1] / d_omega)
    if j_hi < j_lo:
        raise SeaStateError(
            f"a record of {duration:g} s has frequency step {d_omega:.4g} rad/s, wider than "
            f"the RAO table's band {table.omega[0]:.4g}..{table.omega[-1]:.4g} rad/s: use "
            "a longer duration", name="duration")
    harmonics = np.arange(j_lo, j_hi + 1, dtype=np.int64)
    phases = 2.0 * math.pi * np.random.default_rng(seed).random((harmonics.size,
                                                                 offsets.size))
    omega = harmonics * d_omega
    S = spectrum(omega, hs, tp, kind, gamma)
    inside = float(S.sum() * d_omega) / (hs * hs / 16.0)   # the band's share of m0
    if not inside >= BAND_SHARE_MIN:
        raise SeaStateError(
            f"the {kind} spectrum of tp = {tp:g} s (peak {2.0 * math.pi / tp:.4g} rad/s) has "
            f"{100.0 * inside:.2g} % of its energy in the vessel's RAO band "
            f"{table.omega[0]:.4g}..{table.omega[-1]:.4g} rad/s: give tp between "
            f"{2.0 * math.pi / table.omega[-1]:.3g} and {2.0 * math.pi / table.omega[0]:.3g} s",
            name="tp")
    keep = S > 0.0
    if highpass is not None:
        keep &= omega >= highpass
    harmonics, omega, S, phases = harmonics[keep], omega[keep], S[keep], phases[keep]
    A = np.sqrt(2.0 * S * d_omega)[:, None] * np.sqrt(weights)[None, :] * np.exp(1j * phases)
    coef = np.einsum("mk,mkd->md", A, _point_raos(table, omega, heading + offsets, r))
    if not (np.isfinite(coef).all() and np.isfinite(A).all()):
        raise SeaStateError(f"the motion's amplitudes overflow with hs = {hs:g} m, point = "
                            f"{tuple(r.tolist())} m: give physical values", name="point")
    sea = dict(hs=hs, tp=tp, heading_deg=heading, kind=kind, gamma=gamma, seed=seed,
               vessel=table.source, point=tuple(r.tolist()), spreading=spreading,
               directions=directions if spreading is not None else 1, highpass=highpass)
    return ShipMotion(d_omega, harmonics, coef, A.sum(axis=1), start, duration, rate, sea)


def _point_raos(table: RAOTable, omega, headings, r) -> np.ndarray:
    """``(M, K, 6)`` RAOs at the point ``r`` of the vessel: ``H_x + H_θ × r`` (linear)."""
    H = table(omega, headings)
    H[..., :3] += np.cross(H[..., 3:], r)
    return H


def response_spectrum(omega, hs, tp, heading_deg, vessel="supply", kind: str = "jonswap",
                      gamma=None, point=(0.0, 0.0, 0.0), spreading=None,
                      directions: int = DEFAULT_DIRECTIONS, scale: float = 1.0) -> np.ndarray:
    """Target spectra of the six DOFs: ``Σ_k w_k S(ω) |H_P(ω, β + θ_k)|²``.

    The spectrum a long record of :func:`ship_motion` (same arguments) estimates, e.g.
    by Welch's method (whose density per Hz is ``2π`` times this). At model scale λ
    (``scale``), for the record of :func:`platform_trajectory`: ``omega`` is then the
    model-scale frequency ``ω_m = ω √λ`` and the spectra are
    ``S_m(ω_m) = S(ω_m/√λ) / (λ² √λ)`` for translations and ``S(ω_m/√λ) / √λ`` for
    angles (each band's variance scaled by ``1/λ²`` or kept).

    Args:
        omega: ``(n,)`` frequencies [rad/s] (model scale when ``scale`` is given).
        hs, tp, heading_deg, vessel, kind, gamma, point, spreading, directions: As
            :func:`sea_state`.
        scale: Froude scale λ (> 0); 1 for full scale.

    Returns:
        ``(n, 6)`` [m² s/rad] (translations) and [rad² s/rad] (angles).
    """
    hs, tp, heading, kind, gamma = sea_arguments(hs, tp, heading_deg, kind, gamma)
    scale = real(scale, "scale", "-", "give the Froude scale lambda > 0", low=0.0)
    root = math.sqrt(scale)
    w = np.atleast_1d(np.asarray(omega, dtype=float)) / root
    S = spectrum(w, hs, tp, kind, gamma)
    offsets, weights = spreading_directions(spreading, directions)
    H = _point_raos(vessel_raos(vessel), w, heading + offsets, vector3(point, "point", "m"))
    out = np.einsum("k,mkd->md", weights, np.abs(H) ** 2) * S[:, None] / root
    out[:, :3] /= scale * scale
    return out


def welch(x, rate, segment: int = 2048):
    """Welch's estimate of a record's one-sided spectral density, per rad/s.

    Hann-windowed segments of ``segment`` samples overlapping by half, each detrended by
    its mean, periodograms averaged; the density per Hz ``S_f`` (what
    ``scipy.signal.welch`` returns) is converted to ``S_ω = S_f / 2π`` so that it compares
    with :func:`response_spectrum`.

    Args:
        x: ``(N,)`` or ``(N, C)`` record, uniformly sampled.
        rate: Sampling rate [Hz], > 0.
        segment: Segment length (samples), 8 ≤ segment ≤ N.

    Returns:
        ``(omega (K,), S (K,) or (K, C))``: frequencies [rad/s] and density
        [unit² s/rad].

    Raises:
        SeaStateError: bad shapes, non-finite values, a segment longer than the record.
    """
    x = np.asarray(x, dtype=float)
    rate = real(rate, "rate", "Hz", "give the sampling rate", low=0.0)
    segment = integer(segment, "segment", 8, "give the Welch segment length in samples")
    if x.ndim not in (1, 2) or x.shape[0] < segment:
        raise SeaStateError(f"welch needs a record of at least segment = {segment} samples "
                            f"along axis 0, got shape {x.shape}", name="x")
    if not np.isfinite(x).all():
        raise SeaStateError("welch: the record holds non-finite values", name="x")
    step = segment // 2
    starts = np.arange(0, x.shape[0] - segment + 1, step)
    window = np.hanning(segment + 1)[:-1]            # periodic Hann (as scipy's 'hann')
    idx = starts[:, None] + np.arange(segment)[None, :]
    seg = x[idx]                                      # (S, segment[, C])
    seg = seg - seg.mean(axis=1, keepdims=True)
    w = window[None, :, None] if x.ndim == 2 else window[None, :]
    spec = np.abs(np.fft.rfft(seg * w, axis=1)) ** 2
    density = spec.mean(axis=0) / (rate * np.sum(window ** 2))
    density[1:] *= 2.0                                # one-sided
    if segment % 2 == 0:
        density[-1] /= 2.0                            # the Nyquist bin is not doubled
    f = np.fft.rfftfreq(segment, 1.0 / rate)
    return 2.0 * math.pi * f, density / (2.0 * math.pi)


def ship_motion(t, hs, tp, heading_deg, vessel="supply", seed=0, kind: str = "jonswap",
                gamma=None, point=(0.0, 0.0, 0.0), spreading=None,
                directions: int = DEFAULT_DIRECTIONS, highpass=None):
    """A vessel's motion in a sea state at times ``t`` (full scale), analytic derivatives.

    The frequency grid is designed from ``t`` (:func:`sea_state` with ``start = t[0]``,
    ``duration = t[-1] − t[0]``, ``rate = (n − 1)/duration``): the record does not repeat
    within ``t``; uniform times go through the FFT (O(N log N)), others through direct
    summation of the same components. To evaluate one sea at several sets of times (an
    integrator's stages), build it once with :func:`sea_state` and call it.

    Args:
        t: ``(n,)`` strictly increasing times [s], n >= 2.
        hs, tp, heading_deg, vessel, seed, kind, gamma, point, spreading, directions,
            highpass: As :func:`sea_state`.

    Returns:
        ``(motion, velocity, acceleration)``, each ``(n, 6)`` in :data:`DOFS` order
        [m, rad], [m/s, rad/s], [m/s², rad/s²], vessel axes (x forward, y port, z up).

    Raises:
        SeaStateError: bad arguments, times not finite or not increasing, fewer than 2.
    """
    t, scalar = as_times(t)
    if scalar or t.size < 2:
        raise SeaStateError("ship_motion needs at least 2 times (they set the frequency "
                            "grid); for single times build the sea with sea_state() and "
                            "call it", name="t")
    bad = np.diff(t) <= 0.0
    if bad.any():
        k = int(np.argmax(bad)) + 1
        raise SeaStateError(f"t is not strictly increasing at sample {k} (t[{k - 1}] = "
                            f"{float(t[k - 1])!r}, t[{k}] = {float(t[k])!r} s)", name="t",
                            index=k)
    span = float(t[-1] - t[0])
    ship = sea_state(hs, tp, heading_deg, span, (t.size - 1) / span, vessel=vessel,
                     seed=seed, kind=kind, gamma=gamma, point=point, spreading=spreading,
                     directions=directions, highpass=highpass, start=float(t[0]))
    return ship(t)
