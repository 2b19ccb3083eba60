"""Ship motion from sea states: wave spectra × vessel RAOs → Froude-scaled platform motion.

The Stewart platform reproduces the motion of a ship carrying a crane. This module
synthesises that motion from a sea state (significant wave height ``Hs`` [m], peak
period ``Tp`` [s], wave heading [deg]) and a vessel's response amplitude operators
(RAOs), and maps it to the robot's coordinates q1..q6 at a model scale λ. Full details,
with the formulas' sources, are in ``docs/sea.md``; the essentials:

**Spectra** (DNV-RP-C205, 3.5.5), in angular frequency ω [rad/s], ``ωp = 2π/Tp``:
``S_PM(ω) = 5/16 Hs² ωp⁴ ω⁻⁵ exp(−5/4 (ωp/ω)⁴)`` and
``S_J(ω) = A_γ S_PM(ω) γ^exp(−(ω−ωp)²/(2σ²ωp²))``, σ = 0.07 (ω ≤ ωp), 0.09 (ω > ωp),
default γ from ``Tp/√Hs`` (5 up to 3.6, 1 from 5, ``exp(5.75 − 1.15 Tp/√Hs)`` between).
The standard's ``A_γ = 1 − 0.287 ln γ`` is approximate (m0 is 1.8 % low at γ = 7);
here ``A_γ`` is computed numerically so that ``m0 = ∫S dω = Hs²/16`` exactly (to
quadrature round-off, ~1e-15; :func:`jonswap_normalisation`).

**Waves and vessel axes.** Vessel axes: x forward (to the bow), y to port, z up,
origin at the RAO table's reference point; roll, pitch, yaw about x, y, z
(right-handed: roll positive starboard down, pitch positive bow down, yaw positive bow
to port). Heading β: the direction the waves come *from*, relative to the bow: 180 deg
= head seas, 90 deg = from starboard, 0 = following seas; the waves travel along
``(cos β, sin β, 0)``. Long-crested: ``ζ(x, y, t) = Σ_j a_j cos(ω_j t + ε_j −
k_j (x cos β + y sin β))``. RAO phase convention (a *lead*): to the wave
``a cos(ωt + ε)`` at the reference point the response is
``|H| a cos(ωt + ε + arg H)``, i.e. ``Re(H a e^{i(ωt+ε)})``.

**Synthesis.** Components on a uniform frequency grid ``ω_j = j Δω`` (integers j) over
the RAO table's frequency band (the response is zero outside it), amplitudes
``a_j = √(2 S(ω_j) Δω)`` (deterministic) and phases ε_j uniform in [0, 2π) from
``numpy.random.default_rng(seed)``. Each DOF is ``x(t) = Re Σ_j c_j e^{iω_j t}`` with
``c_j = a_j e^{iε_j} H(ω_j, β)``; velocity and acceleration are the exact derivatives
(``iω c``, ``−ω² c``). Such a record repeats with period ``T_rep = 2π/Δω``: Δω is chosen
so that ``T_rep = L h`` with ``h`` the record's sampling step and ``L ≥ N`` (the number
of samples) a 5-smooth integer, hence ``T_rep ≥ N h > duration``. On that grid (and any
uniform grid whose step divides ``T_rep`` an integer number of times) the sum is one
inverse real FFT of length L, ``O(N log N)``; at any other times (an integrator's
stages) the same components are summed directly. Both give the same values to
round-off.

**Short-crested seas** (optional, ``spreading = s``): cos-2s spreading
``D(θ) ∝ cos^{2s}((θ − β)/2)``, ``|θ − β| ≤ π``, discretised into ``directions`` equal
bins of the full circle centred on β (bin centres ``β − π + (k + ½) 2π/K``) with weights
``w_k = D(θ_k)/Σ D`` (so that the variance is kept exactly). Each pair (ω_j, θ_k) is a
component with its own random phase and amplitude ``√(2 S_j Δω w_k)``; its response
uses the RAO interpolated at heading θ_k.

**RAO tables** (:func:`load_raos`): long-form CSV ``omega_rad_s,heading_deg,dof,
amplitude,phase_rad``; the real and imaginary parts of ``H = amplitude e^{i phase}``
are interpolated linearly in ω and in heading (periodic in 360 deg when the table goes
round the circle). The packaged ``"supply"`` vessel is the MSS toolbox's supply vessel
(MIT licence; ``data/vessels/supply.LICENSE.txt``).

**Point of the vessel.** The motion at a point ``r`` (vessel axes) is the rigid-body
transfer of the linear theory: ``x_P = x + θ × r`` with ``θ = (roll, pitch, yaw)``
(small angles, consistent with linear RAOs), applied to the complex amplitudes.

**Froude scaling** (:func:`platform_trajectory`): lengths / λ, times / √λ, angles
unchanged; hence linear velocities / √λ, linear accelerations unchanged, angular rates
× √λ, angular accelerations × λ. ``q1..q3 = home + x_P / λ``,
``q4, q5, q6 = roll, pitch, yaw`` (vessel axes = robot base axes, x forward, y port,
z up; the small angles are used as the Z-Y-X angles of ``R = Rz(q6) Ry(q5) Rx(q4)``,
which agrees with the linear rotation to second order).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from pathlib import Path

import numpy as np

from offshore_crane.conventions import SPECTRA
from offshore_crane.errors import SeaStateError, SeaWorkspaceError, WorkspaceError
from offshore_crane.motion.operations import _as_times

__all__ = ["DOFS", "SPECTRA", "RAO_COLUMNS", "VESSELS", "DEFAULT_DIRECTIONS",
           "spectrum", "default_gamma", "jonswap_normalisation", "spreading_directions",
           "response_spectrum",
           "RAOTable", "load_raos", "vessel_raos", "ShipMotion", "sea_state", "ship_motion",
           "SeaMotion", "sea_motion", "platform_trajectory"]

#: The six rigid-body DOFs, in the order of every ``(N, 6)`` array here [m, m, m, rad,
#: rad, rad].
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
#: Spectrum kinds accepted by :func:`spectrum`.
#: Header of a RAO table CSV file.
RAO_COLUMNS = ("omega_rad_s", "heading_deg", "dof", "amplitude", "phase_rad")
#: Packaged vessels: name -> RAO file in ``offshore_crane/motion/data/vessels``.
VESSELS = {"supply": "supply.csv"}
#: Default number of spreading directions: 10-deg bins, the heading step of the supply
#: vessel's table.
DEFAULT_DIRECTIONS = 36

# JONSWAP peak widths (DNV-RP-C205 3.5.5.4).
_SIGMA_BELOW, _SIGMA_ABOVE = 0.07, 0.09
# Default gamma (DNV-RP-C205 3.5.5.5): gamma = 5 for Tp/sqrt(Hs) <= 3.6, 1 for >= 5.
_GAMMA_RATIO_LOW, _GAMMA_RATIO_HIGH = 3.6, 5.0
# The peak enhancement gamma^r - 1 is below ln(gamma) e^-72 (< 1e-31 ln gamma) beyond
# 12 sigma of the peak: the normalisation integral stops there, on each side.
_PEAK_HALF_WIDTH_SIGMAS = 12.0
# Gauss-Legendre nodes per side of the peak: the integrand is smooth on each side (the
# Gaussian enhancement spans 12 sigma); 200 nodes integrate it to round-off.
_QUADRATURE_NODES = 200
# Below omega = 0.1 omega_p, exp(-5/4 (omega_p/omega)^4) < e^-12500 underflows to 0 in
# float64: the spectrum is returned as exactly 0 there (and the power law not formed).
_SPECTRUM_ZERO_BELOW = 0.1
# Headings closer than this to a table heading [deg] are that heading (round-off of
# angle arithmetic such as 360 - 350).
_HEADING_TOL_DEG = 1e-9
# Relative round-off allowed when comparing heading spacings (a few ulp of 360 deg).
_SPACING_RTOL = 1e-12
# Times within this many units in the last place of the largest |t| of a uniform grid
# count as that grid (arange(n) / rate * sqrt(scale) is off by a few ulp); the FFT path
# then evaluates at the exact grid times, a difference below the direct path's own
# round-off of omega * t.
_GRID_TOL_ULPS = 64.0
# Direct summation works on blocks of at most this many (time, component) pairs
# (4 M doubles: 32 MB per temporary array).
_DIRECT_BLOCK = 1 << 22
# Workspace search: relative width of the final bracket on lambda.
SCALE_RTOL = 1e-3
# Workspace search: doublings of lambda tried before giving up. After 60 the translations
# are scaled by 2^-60 < 1e-18, below the float resolution of the positions (~1e-16 m at
# 1 m): the pose is then the rotation-only pose to round-off.
_MAX_DOUBLINGS = 60
_SCALE_HINT = "give the Froude scale lambda = full-scale length / model length, > 0"
# Uniform grid inside a sea_state: the same rule as trajectories.time_grid.
_GRID_EPS = 1e-9


# ---------------------------------------------------------------------------- validation
def _real(value, name: str, unit: str, hint: str, *, low=None, low_open=True,
          allow_none=False):
    """``value`` as a finite float above ``low`` (strictly when ``low_open``), or raise."""
    if value is None and allow_none:
        return None
    if isinstance(value, (bool, str, bytes)) or np.iscomplexobj(value):
        raise SeaStateError(f"{name} must be a real number [{unit}], got {value!r}: {hint}",
                            name=name)
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise SeaStateError(f"{name} must be a real number [{unit}], got {value!r}: {hint}",
                            name=name) from None
    if not math.isfinite(x):
        raise SeaStateError(f"{name} = {x!r} is not finite [{unit}]: {hint}", name=name)
    if low is not None and (x <= low if low_open else x < low):
        relation = ">" if low_open else ">="
        raise SeaStateError(f"{name} = {x!r} {unit} must be {relation} {low:g}: {hint}",
                            name=name)
    return x


def _integer(value, name: str, low: int, hint: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise SeaStateError(f"{name} must be an integer, got {value!r}: {hint}", name=name)
    if value < low:
        raise SeaStateError(f"{name} = {value} must be >= {low}: {hint}", name=name)
    return int(value)


def _vector3(value, name: str, unit: str) -> np.ndarray:
    try:
        v = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise SeaStateError(f"{name} must be 3 numbers [{unit}], got {value!r}",
                            name=name) from None
    if v.shape != (3,):
        raise SeaStateError(f"{name} must be 3 numbers (x, y, z) [{unit}], got shape "
                            f"{v.shape}", name=name)
    if not np.isfinite(v).all():
        raise SeaStateError(f"{name} = {value!r} is not finite [{unit}]", name=name)
    return v


def _sea_arguments(hs, tp, heading_deg, kind, gamma) -> tuple[float, float, float, str,
                                                                 float | None]:
    hs = _real(hs, "hs", "m", "give the significant wave height", low=0.0)
    tp = _real(tp, "tp", "s", "give the peak period", low=0.0)
    heading = _real(heading_deg, "heading", "deg",
                    "give the wave heading (180 = head seas, 90 = from starboard)")
    if kind not in SPECTRA:
        raise SeaStateError(f"unknown spectrum kind {kind!r}: use one of "
                            f"{', '.join(SPECTRA)}", name="kind")
    if kind == "pierson-moskowitz" and gamma is not None:
        raise SeaStateError(f"gamma = {gamma!r} applies to the JONSWAP spectrum only: leave "
                            "it out with kind='pierson-moskowitz'", name="gamma")
    gamma = _real(gamma, "gamma", "-", "the JONSWAP peak enhancement must be >= 1 (1 is "
                  "Pierson-Moskowitz)", low=1.0, low_open=False, allow_none=True)
    return hs, tp, heading, kind, gamma


# ------------------------------------------------------------------------------ spectra
def default_gamma(hs: float, tp: float) -> float:
    """DNV-RP-C205 3.5.5.5's default JONSWAP peak enhancement for ``Hs`` [m], ``Tp`` [s].

    ``γ = 5`` for ``Tp/√Hs ≤ 3.6``, ``γ = exp(5.75 − 1.15 Tp/√Hs)`` for
    ``3.6 < Tp/√Hs < 5`` and ``γ = 1`` for ``Tp/√Hs ≥ 5`` (Tp in s, Hs in m); continuous
    at 5, and at 3.6 up to the standard's rounding (``exp(1.61) = 5.003``).
    """
    ratio = tp / math.sqrt(hs)
    if ratio <= _GAMMA_RATIO_LOW:
        return 5.0
    if ratio >= _GAMMA_RATIO_HIGH:
        return 1.0
    return math.exp(5.75 - 1.15 * ratio)


@lru_cache(maxsize=1)
def _legendre():
    return np.polynomial.legendre.leggauss(_QUADRATURE_NODES)


def _enhancement(x: np.ndarray, gamma: float) -> np.ndarray:
    """JONSWAP peak factor ``γ^r(x)`` at ``x = ω/ωp``."""
    sigma = np.where(x <= 1.0, _SIGMA_BELOW, _SIGMA_ABOVE)
    return np.exp(math.log(gamma) * np.exp(-((x - 1.0) ** 2) / (2.0 * sigma * sigma)))


@lru_cache(maxsize=64)
def jonswap_normalisation(gamma: float) -> float:
    """``A_γ`` such that the JONSWAP spectrum's zeroth moment is ``Hs²/16`` exactly.

    With ``x = ω/ωp`` the Pierson-Moskowitz shape is the probability density
    ``p(x) = 5 x⁻⁵ exp(−5/4 x⁻⁴)`` times ``Hs²/16`` (its integral is exactly 1), so
    ``A_γ = 1 / (1 + ∫ p(x) (γ^r(x) − 1) dx)``. The correction integral is non-zero only
    near the peak; it is computed by Gauss-Legendre quadrature on [1 − 12σa, 1] and
    [1, 1 + 12σb] (smooth on each side), accurate to round-off.
    DNV-RP-C205's ``1 − 0.287 ln γ`` approximates it (0.7 % low at γ = 6, 1.8 % at 7).

    Args:
        gamma: Peak enhancement, >= 1.

    Returns:
        ``A_γ`` (1 for γ = 1).
    """
    if gamma == 1.0:
        return 1.0
    nodes, weights = _legendre()
    total = 0.0
    for a, b in ((1.0 - _PEAK_HALF_WIDTH_SIGMAS * _SIGMA_BELOW, 1.0),
                 (1.0, 1.0 + _PEAK_HALF_WIDTH_SIGMAS * _SIGMA_ABOVE)):
        x = 0.5 * (b - a) * nodes + 0.5 * (a + b)
        sigma = _SIGMA_BELOW if b == 1.0 else _SIGMA_ABOVE
        r = np.exp(-((x - 1.0) ** 2) / (2.0 * sigma * sigma))
        p = 5.0 * x ** -5 * np.exp(-1.25 * x ** -4)
        total += 0.5 * (b - a) * float(np.dot(weights, p * np.expm1(math.log(gamma) * r)))
    return 1.0 / (1.0 + total)


def spectrum(omega, hs, tp, kind: str = "jonswap", gamma=None) -> np.ndarray:
    """Wave spectrum ``S(ω)`` [m² s/rad] after DNV-RP-C205 3.5.5, normalised to ``Hs²/16``.

    Args:
        omega: Angular frequencies [rad/s], scalar or array, finite and >= 0.
        hs: Significant wave height [m], > 0.
        tp: Peak period [s], > 0.
        kind: ``"jonswap"`` or ``"pierson-moskowitz"``.
        gamma: JONSWAP peak enhancement (>= 1); default :func:`default_gamma`. Not
            allowed with ``"pierson-moskowitz"`` (which is γ = 1).

    Returns:
        ``S`` with the shape of ``omega`` [m² s/rad]; ``∫₀^∞ S dω = Hs²/16`` exactly (the
        JONSWAP normalisation is numerical, :func:`jonswap_normalisation`). A density
        per Hz is ``S_f(f) = 2π S(2πf)``.

    Raises:
        SeaStateError: bad ``hs``, ``tp``, ``kind``, ``gamma`` or ``omega``.
    """
    hs, tp, _, kind, gamma = _sea_arguments(hs, tp, 0.0, kind, gamma)
    try:
        w = np.asarray(omega, dtype=float)
    except (TypeError, ValueError):
        raise SeaStateError(f"omega must be numbers [rad/s], got {omega!r}",
                            name="omega") from None
    bad = ~np.isfinite(w) | (w < 0.0)
    if bad.any():
        k = int(np.argmax(bad.ravel()))
        raise SeaStateError(f"omega[{k}] = {float(w.ravel()[k])!r} must be finite and >= 0 [rad/s]",
                            name="omega", index=k)
    if kind == "jonswap" and gamma is None:
        gamma = default_gamma(hs, tp)
    wp = 2.0 * math.pi / tp
    x = w / wp
    out = np.zeros_like(x)
    live = x > _SPECTRUM_ZERO_BELOW
    y = 1.0 / x[live]
    y4 = y ** 4
    with np.errstate(over="ignore", invalid="ignore"):
        s = (5.0 / 16.0) * hs * hs / wp * y4 * y * np.exp(-1.25 * y4)
        if kind == "jonswap" and gamma != 1.0:
            s = s * jonswap_normalisation(gamma) * _enhancement(x[live], gamma)
    if not np.isfinite(s).all():
        raise SeaStateError(f"the spectrum overflows with hs = {hs:g} m, tp = {tp:g} s, "
                            f"gamma = {gamma}: give physical values", name="hs")
    out[live] = s
    return out


# ------------------------------------------------------------------------ short-crested
def spreading_directions(s=None, directions: int = DEFAULT_DIRECTIONS):
    """Directions and weights of the cos-2s spreading (long-crested when ``s`` is None).

    ``D(θ) ∝ cos^{2s}(θ/2)`` for ``θ`` in (−π, π] relative to the mean heading, in K
    equal bins of the full circle with centres ``θ_k = −π + (k + ½) 2π/K`` and weights
    ``w_k = D(θ_k) / Σ D(θ_m)`` (midpoint rule, renormalised so that ``Σ w_k = 1``
    exactly: the directions share the variance of each frequency). Directions whose
    weight underflows to exactly 0 are dropped (they carry nothing).

    Args:
        s: Spreading exponent (> 0), or None for long-crested seas.
        directions: K, the number of bins (>= 1).

    Returns:
        ``(offsets_deg (K',), weights (K',))``: headings relative to the mean [deg] and
        weights summing to 1; ``([0.], [1.])`` for long-crested seas.
    """
    if s is None:
        return np.zeros(1), np.ones(1)
    s = _real(s, "spreading", "-", "give the cos-2s spreading exponent s > 0, or None for "
              "long-crested seas", low=0.0)
    k = _integer(directions, "directions", 1, "give the number of spreading directions")
    theta = -math.pi + (np.arange(k) + 0.5) * (2.0 * math.pi / k)
    d = np.cos(0.5 * theta) ** (2.0 * s)
    keep = d > 0.0
    return np.degrees(theta[keep]), d[keep] / d[keep].sum()


# ---------------------------------------------------------------------------- RAO tables
@dataclass(frozen=True, eq=False)
class RAOTable:
    """A vessel's motion RAOs on a grid of frequencies × headings.

    Attributes:
        omega: ``(F,)`` wave frequencies [rad/s], strictly increasing, F >= 2.
        heading_deg: ``(H,)`` wave headings [deg] in [0, 360), increasing (our
            convention: 180 = head seas, 90 = waves from starboard).
        values: ``(F, H, 6)`` complex RAOs ``amplitude · e^{i phase}`` for
            :data:`DOFS` [m/m, rad/m] (phase lead, vessel axes x forward, y port, z up).
        source: Where the table came from (file path or packaged name).
    """

    omega: np.ndarray
    heading_deg: np.ndarray
    values: np.ndarray
    source: str

    @property
    def periodic(self) -> bool:
        """Whether heading interpolation wraps round 360 deg.

        True when the gap across 360 deg (``h_0 + 360 − h_last``) is no wider than the
        widest gap between consecutive headings inside the table: a table that goes
        round the circle (0:10:350) wraps, a half-circle table (0:10:180) does not.
        """
        h = self.heading_deg
        if h.size < 2:
            return False
        wrap = h[0] + 360.0 - h[-1]
        # equal spacings computed as 360 - 350 and 20 - 10 differ by round-off only
        return bool(wrap <= np.diff(h).max() * (1.0 + _SPACING_RTOL))

    def _heading_weights(self, heading_deg: np.ndarray):
        """Bracketing indices and weights for headings [deg]; raise if one is not covered."""
        h_tab = self.heading_deg
        h = np.mod(heading_deg, 360.0)
        diff = np.abs(np.mod(h[:, None] - h_tab[None, :] + 180.0, 360.0) - 180.0)
        nearest = diff.argmin(axis=1)
        exact = diff[np.arange(h.size), nearest] <= _HEADING_TOL_DEG
        idx = np.searchsorted(h_tab, h)
        i0 = np.where(exact, nearest, idx - 1)
        i1 = np.where(exact, nearest, idx)
        wrap = ~exact & ((idx == 0) | (idx == h_tab.size))
        if wrap.any() and not self.periodic:
            k = int(np.argmax(wrap))
            raise SeaStateError(
                f"{self.source}: heading {h[k]:g} deg is not covered by the RAO table "
                f"(headings {h_tab[0]:g}..{h_tab[-1]:g} deg, which do not go round the "
                "circle): use a heading inside that range, or a table with more headings",
                name="heading", path=self.source)
        i0 = np.where(wrap, h_tab.size - 1, i0)
        i1 = np.where(wrap, 0, i1)
        gap = np.mod(h_tab[i1] - h_tab[i0], 360.0)
        offset = np.mod(h - h_tab[i0], 360.0)
        w = np.where(exact, 0.0, offset / np.where(gap > 0.0, gap, 1.0))
        return i0, i1, w

    def __call__(self, omega, heading_deg) -> np.ndarray:
        """Complex RAOs interpolated at frequencies × headings.

        Real and imaginary parts are interpolated linearly in ω and in heading (heading
        periodic when :attr:`periodic`); outside ``[omega[0], omega[-1]]`` the response
        is 0.

        Args:
            omega: ``(M,)`` [rad/s].
            heading_deg: ``(K,)`` [deg], any real (taken modulo 360).

        Returns:
            ``(M, K, 6)`` complex [m/m, rad/m].

        Raises:
            SeaStateError: a heading outside a non-periodic table's range.
        """
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        h = np.atleast_1d(np.asarray(heading_deg, dtype=float))
        i0, i1, wh = self._heading_weights(h)
        v = self.values
        vh = v[:, i0, :] * (1.0 - wh)[None, :, None] + v[:, i1, :] * wh[None, :, None]
        grid = self.omega
        j = np.clip(np.searchsorted(grid, w, side="right") - 1, 0, grid.size - 2)
        s = ((w - grid[j]) / (grid[j + 1] - grid[j]))[:, None, None]
        out = vh[j] * (1.0 - s) + vh[j + 1] * s
        out[(w < grid[0]) | (w > grid[-1])] = 0.0
        return out


def _file_error(source, line, column, text, name=None):
    where = f"{source}, line {line}" + (f", column {column}" if column else "")
    return SeaStateError(f"{where}: {text}", name=name or column, path=source, line=line,
                         column=column)


def _decode(data: bytes, source: str) -> str:
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        start = data.rfind(b"\n", 0, exc.start) + 1
        line = data.count(b"\n", 0, exc.start) + 1
        col = data.count(b",", start, exc.start)
        column = RAO_COLUMNS[col] if col < len(RAO_COLUMNS) else f"{col + 1}"
        raise _file_error(source, line, column,
                          f"byte 0x{data[exc.start]:02x} is not UTF-8 text: save the file "
                          "as UTF-8 (plain ASCII numbers and DOF names)") from None


def _parse_raos(data: bytes, source: str) -> RAOTable:
    """Parse and validate a RAO CSV (see :func:`load_raos`)."""
    import csv

    lines = _decode(data, source).splitlines()
    rows = [(n + 1, cells) for n, cells in enumerate(csv.reader(lines)) if
            any(c.strip() for c in cells)]
    if not rows:
        raise _file_error(source, 1, None, "the file is empty: write the header "
                          f"{','.join(RAO_COLUMNS)} and one row per omega, heading, dof")
    line0, header = rows[0]
    if tuple(c.strip() for c in header) != RAO_COLUMNS:
        raise _file_error(source, line0, None, f"header {','.join(header)!r} must be "
                          f"{','.join(RAO_COLUMNS)}")
    numeric = (0, 1, 3, 4)
    values = np.empty((len(rows) - 1, 4))
    dof = np.empty(len(rows) - 1, dtype=int)
    line_of = np.empty(len(rows) - 1, dtype=int)
    for r, (line, cells) in enumerate(rows[1:]):
        line_of[r] = line
        if len(cells) != len(RAO_COLUMNS):
            raise _file_error(source, line, None, f"{len(cells)} cells, expected "
                              f"{len(RAO_COLUMNS)} ({','.join(RAO_COLUMNS)})")
        for k, j in enumerate(numeric):
            cell = cells[j].strip()
            try:
                x = float(cell)
            except ValueError:
                raise _file_error(source, line, RAO_COLUMNS[j], f"{cell!r} is not a number: "
                                  "write a decimal number") from None
            if not math.isfinite(x):
                raise _file_error(source, line, RAO_COLUMNS[j], f"{cell!r} is not finite: "
                                  "give a finite number")
            values[r, k] = x
        name = cells[2].strip().lower()
        if name not in DOFS:
            raise _file_error(source, line, "dof", f"unknown dof {cells[2].strip()!r}: use "
                              f"one of {', '.join(DOFS)}")
        dof[r] = DOFS.index(name)
    omega, heading, amplitude, phase = values.T
    checks = ((omega, "omega_rad_s", "must be >= 0 [rad/s]"),
              (amplitude, "amplitude", "is negative: amplitudes are magnitudes (>= 0); put "
               "the sign in the phase (+pi)"))
    for column_values, column, text in checks:
        bad = column_values < 0.0
        if bad.any():
            r = int(np.argmax(bad))
            raise _file_error(source, int(line_of[r]), column,
                              f"{float(column_values[r])!r} {text}")
    heading = np.mod(heading, 360.0)
    seen: dict = {}
    last: dict = {}
    for r in range(len(dof)):
        key = (omega[r], heading[r], dof[r])
        if key in seen:
            raise _file_error(source, int(line_of[r]), None,
                              f"duplicate row: omega {omega[r]:g} rad/s, heading "
                              f"{heading[r]:g} deg, dof {DOFS[dof[r]]} is already on line "
                              f"{seen[key]} (headings are taken modulo 360): remove one")
        seen[key] = int(line_of[r])
        block = (heading[r], dof[r])
        if block in last and omega[r] < last[block][0]:
            raise _file_error(source, int(line_of[r]), "omega_rad_s",
                              f"omega {omega[r]:g} rad/s does not increase after "
                              f"{last[block][0]:g} on line {last[block][1]} (heading "
                              f"{heading[r]:g} deg, dof {DOFS[dof[r]]}): sort the rows by "
                              "omega within each heading and dof")
        last[block] = (omega[r], int(line_of[r]))
    w_grid = np.unique(omega)
    h_grid = np.unique(heading)
    present = np.zeros((w_grid.size, h_grid.size, 6), dtype=bool)
    iw = np.searchsorted(w_grid, omega)
    ih = np.searchsorted(h_grid, heading)
    present[iw, ih, dof] = True
    missing_dof = [d for d in range(6) if not present[:, :, d].any()]
    if missing_dof:
        raise _file_error(source, int(line_of[-1]), "dof",
                          f"no rows for dof {', '.join(DOFS[d] for d in missing_dof)}: the "
                          f"table needs all six ({', '.join(DOFS)}), zero amplitude where "
                          "there is no response")
    if not present.all():
        a, b, d = (int(x) for x in np.argwhere(~present)[0])
        group = present[a, b].any()
        lines = sorted(int(line_of[r]) for r in np.flatnonzero((iw == a) & (ih == b)))
        if group:
            raise _file_error(source, lines[-1], "dof",
                              f"missing dof {DOFS[d]} for omega {w_grid[a]:g} rad/s, heading "
                              f"{h_grid[b]:g} deg (rows on lines "
                              f"{', '.join(map(str, lines))}): every omega and heading needs "
                              "all six dofs")
        raise _file_error(source, int(line_of[-1]), None,
                          f"no rows for omega {w_grid[a]:g} rad/s at heading {h_grid[b]:g} "
                          "deg: the table must be a full grid of omega x heading x dof")
    if w_grid.size < 2:
        raise _file_error(source, int(line_of[-1]), "omega_rad_s",
                          f"only one frequency ({w_grid[0]:g} rad/s): give at least two to "
                          "interpolate between")
    table = np.zeros((w_grid.size, h_grid.size, 6), dtype=complex)
    table[iw, ih, dof] = amplitude * np.exp(1j * phase)
    for array in (w_grid, h_grid, table):
        array.setflags(write=False)          # packaged tables are shared (cached)
    return RAOTable(w_grid, h_grid, table, source)


def load_raos(path) -> RAOTable:
    """Read a vessel's RAO table from a long-form CSV file.

    Format: UTF-8 text, header ``omega_rad_s,heading_deg,dof,amplitude,phase_rad``, one
    row per (frequency [rad/s], heading [deg], dof); ``dof`` one of :data:`DOFS`;
    ``amplitude`` >= 0 in m/m (surge, sway, heave) or rad/m (roll, pitch, yaw);
    ``phase_rad`` the phase lead (response ``amplitude · a cos(ωt + ε + phase)`` to the
    wave ``a cos(ωt + ε)`` at the table's reference point). Vessel axes x forward, y
    port, z up; roll positive starboard down, pitch bow down, yaw bow to port; heading
    180 = head seas, 90 = waves from starboard (taken modulo 360). The rows must form a
    full grid of frequencies × headings × the six dofs, with frequencies increasing (in
    file order) within each heading and dof, no duplicate; blank lines are ignored.

    Args:
        path: The CSV file (str or path-like).

    Returns:
        :class:`RAOTable`.

    Raises:
        SeaStateError: unreadable file, non-UTF-8 bytes, bad header, a non-numeric or
            non-finite cell, an unknown dof, a negative frequency or amplitude, a
            duplicate row, frequencies not increasing, a missing dof or grid point; the
            message starts with ``file, line N, column C``.
    """
    try:
        p = Path(os.fspath(path))
    except TypeError:
        raise SeaStateError(f"RAO table path must be a file name, got {path!r}",
                            name="vessel") from None
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise SeaStateError(f"{p}: cannot read the RAO table ({exc.strerror}): give an "
                            f"existing CSV file or one of {', '.join(VESSELS)}",
                            name="vessel", path=str(p)) from None
    return _parse_raos(data, str(p))


@lru_cache(maxsize=len(VESSELS))
@lru_cache(maxsize=None)
def _packaged(name: str) -> RAOTable:
    from importlib import resources

    ref = resources.files("offshore_crane.motion").joinpath("data", "vessels", VESSELS[name])
    return _parse_raos(ref.read_bytes(), f"offshore_crane/motion/data/vessels/{VESSELS[name]}")


def vessel_raos(vessel="supply") -> RAOTable:
    """The RAO table of a packaged vessel (:data:`VESSELS`), a CSV path, or a table.

    Raises:
        SeaStateError: an unknown name that is not a file, or any :func:`load_raos` error.
    """
    if isinstance(vessel, RAOTable):
        return vessel
    if isinstance(vessel, str) and vessel in VESSELS:
        return _packaged(vessel)
    try:
        is_file = Path(os.fspath(vessel)).is_file()
    except TypeError:
        is_file = False
    if not is_file:
        raise SeaStateError(f"unknown vessel {vessel!r}: use one of {', '.join(VESSELS)} or "
                            "the path of a RAO CSV file", name="vessel")
    return load_raos(vessel)


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
         n: int) -> np.ndarray:
    """``Re Σ_j coef[j] e^{i j Δω (t0 + m T/L)}`` for m = 0..n-1 (``T = 2π/Δω``): ``(n, C)``.

    Exact for any harmonics (those above L/2 fold onto their alias with the conjugate
    coefficient; the samples are the same numbers): one inverse real FFT of length L
    per channel.
    """
    b = coef * np.exp(1j * (harmonics * d_omega * t0))[:, None]
    k = harmonics % L
    upper = k > L // 2
    k = np.where(upper, L - k, k)
    b = np.where(upper[:, None], b.conj(), b)
    b *= np.where((k == 0) | (2 * k == L), float(L), 0.5 * L)[:, None]
    spec = np.zeros((L // 2 + 1, coef.shape[1]), dtype=complex)
    if np.unique(k).size == k.size:
        spec[k] = b
    else:
        np.add.at(spec, k, b)
    x = np.fft.irfft(spec, n=L, axis=0)
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

    def _evaluate(self, coef: np.ndarray, t, method: str):
        if method not in ("auto", "fft", "direct"):
            raise SeaStateError(f"unknown method {method!r}: use 'auto', 'fft' or 'direct'",
                                name="method")
        t, scalar = _as_times(t)
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
            out = _fft(coef, self.harmonics, self.d_omega, plan[0], plan[1], t.size)
        else:
            out = _direct(coef, omega, t)
        return out, scalar

    def __call__(self, t, method: str = "auto"):
        """Motion, velocity, acceleration at times ``t`` (full scale).

        Args:
            t: Times [s], scalar or ``(n,)``, inside ``[start, start +
                repetition_period]``; any order and spacing.
            method: ``"auto"`` (FFT on a compatible uniform grid when it is cheaper,
                else direct summation), ``"fft"`` or ``"direct"``; they agree to
                round-off.

        Returns:
            ``(motion, velocity, acceleration)``, each ``(n, 6)`` (``(6,)`` for a scalar)
            in :data:`DOFS` order [m, rad], [m/s, rad/s], [m/s², rad/s²], vessel axes.

        Raises:
            SeaStateError: non-finite times, times outside the non-repeating span.
        """
        out, scalar = self._evaluate(self._channels, t, method)
        parts = tuple(np.ascontiguousarray(out[:, 6 * i:6 * i + 6]) for i in range(3))
        return tuple(p[0] for p in parts) if scalar else parts

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
    hs, tp, heading, kind, gamma = _sea_arguments(hs, tp, heading_deg, kind, gamma)
    seed = _integer(seed, "seed", 0, "give a non-negative integer seed")
    r = _vector3(point, "point", "m")
    highpass = _real(highpass, "highpass", "rad/s", "give the cut-off frequency >= 0, or "
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
    _real(scale, "scale", "-", _SCALE_HINT, low=0.0)
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
    duration = _real(duration, "duration", "s", "give the record's length", low=0.0)
    rate = _real(rate, "rate", "Hz", "give the sampling rate", low=0.0)
    start = _real(start, "start", "s", "give the record's first time")
    hs, tp, heading, kind, gamma, seed, r, highpass, table, offsets, weights = _checked(
        hs, tp, heading_deg, vessel, seed, kind, gamma, point, spreading, directions,
        highpass)
    if kind == "jonswap" and gamma is None:
        gamma = default_gamma(hs, tp)
    n = math.floor(duration * rate + _GRID_EPS) + 1
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
    hs, tp, heading, kind, gamma = _sea_arguments(hs, tp, heading_deg, kind, gamma)
    scale = _real(scale, "scale", "-", "give the Froude scale lambda > 0", low=0.0)
    root = math.sqrt(scale)
    w = np.atleast_1d(np.asarray(omega, dtype=float)) / root
    S = spectrum(w, hs, tp, kind, gamma)
    offsets, weights = spreading_directions(spreading, directions)
    H = _point_raos(vessel_raos(vessel), w, heading + offsets, _vector3(point, "point", "m"))
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
    rate = _real(rate, "rate", "Hz", "give the sampling rate", low=0.0)
    segment = _integer(segment, "segment", 8, "give the Welch segment length in samples")
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
    t, scalar = _as_times(t)
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


# ------------------------------------------------------------------ Froude-scaled motion
@dataclass(frozen=True, eq=False)
class SeaMotion:
    """The robot's reference motion from a ship in a sea state, at model scale λ.

    ``q, qd, qdd = motion(t)`` at any model-scale times (an integrator's stages too):
    ``q1..q3 = home + x_P(t√λ)/λ``, ``q4..q6 = θ(t√λ)`` (roll, pitch, yaw),
    ``q7..q9`` from the crane operation (zeros without one); rates and accelerations
    are the exact derivatives (Froude: linear rates / √λ, linear accelerations
    unchanged, angular rates × √λ, angular accelerations × λ). Build it with
    :func:`sea_motion`.

    Attributes:
        ship: The full-scale :class:`ShipMotion`.
        scale: λ, full-scale length / model length (> 0).
        home: ``(9,)`` home pose: zeros except ``q3 = home_height`` [m].
        operation: :class:`~offshore_crane.motion.operations.Operation` or None.
        duration: Model-scale record length [s].
        rate: Model-scale sampling rate [Hz].
    """

    ship: ShipMotion
    scale: float
    home: np.ndarray
    operation: object
    duration: float
    rate: float

    def time_grid(self) -> np.ndarray:
        """The model-scale record's times ``(N,)`` [s] (``trajectories.time_grid``)."""
        from offshore_crane.motion.trajectories import time_grid

        return time_grid(self.duration, self.rate)

    def __call__(self, t):
        """``(q, qd, qdd)`` at model-scale times ``t`` [s]: each ``(n, 9)`` (``(9,)`` for a
        scalar), [m, rad], [m/s, rad/s], [m/s², rad/s²].

        Raises:
            SeaStateError: non-finite times, or times beyond the record's non-repeating
                span (``ship.repetition_period / √λ``).
        """
        t, scalar = _as_times(t)
        root = math.sqrt(self.scale)
        end = self.ship.repetition_period / root
        outside = (t < 0.0) | (t > end)
        if outside.any():
            k = int(np.argmax(outside))
            raise SeaStateError(
                f"t[{k}] = {float(t[k]):.9g} s is outside [0, {end:.9g}] s, the model-scale "
                f"span on which this sea does not repeat (record {self.duration:g} s at "
                f"scale {self.scale:g}): build the motion for a longer duration",
                name="t", index=k)
        x, v, a = self.ship(t * root)
        n = t.size
        q = np.empty((n, 9))
        qd = np.empty((n, 9))
        qdd = np.empty((n, 9))
        q[:, :3] = self.home[:3] + x[:, :3] / self.scale
        qd[:, :3] = v[:, :3] / root
        qdd[:, :3] = a[:, :3]
        q[:, 3:6] = x[:, 3:]
        qd[:, 3:6] = v[:, 3:] * root
        qdd[:, 3:6] = a[:, 3:] * self.scale
        if self.operation is None:
            q[:, 6:] = self.home[6:]
            qd[:, 6:] = 0.0
            qdd[:, 6:] = 0.0
        else:
            q[:, 6:], qd[:, 6:], qdd[:, 6:] = self.operation(t)
        return (q[0], qd[0], qdd[0]) if scalar else (q, qd, qdd)

    def trajectory(self, name: str = "sea"):
        """The record on its design grid as a
        :class:`~offshore_crane.motion.trajectories.Trajectory`."""
        from offshore_crane.motion.trajectories import Trajectory

        t = self.time_grid()
        return Trajectory(name, t, *self(t), source=self)

    def check(self, robot, trajectory=None) -> None:
        """Raise :class:`SeaWorkspaceError` if the record leaves the robot's workspace.

        Every sample's leg lengths, U-joint angles and sphere heights are checked by
        :func:`offshore_crane.dynamics.solve` (``limits=True``). On failure the error
        names the first violation (sample, leg, value) and the smallest scale λ at which
        the whole record fits: found by bisection in log λ to a relative bracket of
        :data:`SCALE_RTOL`, on the assumption that a record that fits at λ also fits at
        every larger λ (the translations shrink towards home while the rotations stay);
        the bracket's ends are checked (the lower one fails, the reported upper one fits
        over the whole record). If the rotations alone (λ → ∞) leave the workspace, it
        says that no scale fits.

        Args:
            robot: From :func:`offshore_crane.load_robot`.
            trajectory: The design-grid :class:`Trajectory` if already computed.
        """
        traj = self.trajectory() if trajectory is None else trajectory
        _check_scaled(robot, traj.t, traj.q, self.home, self.scale)


def _violation(robot, q, t):
    """The WorkspaceError that ``q`` meets (:func:`offshore_crane.robot.kinematics.check_workspace`),
    or None."""
    from offshore_crane.robot.kinematics import check_workspace

    try:
        check_workspace(robot, q, t)
    except WorkspaceError as exc:
        return exc
    return None


def _what(exc) -> str:
    """The descriptive part of a workspace message (before its advice)."""
    return str(exc).split(";")[0]


def _check_scaled(robot, t, q, home, scale) -> None:
    from offshore_crane.conventions import ARM_JOINTS

    first = _violation(robot, q, t)
    if first is None:
        return
    if first.joint in ARM_JOINTS:
        raise first
    shift = (q[:, :3] - home[:3]) * scale                 # full-scale translations [m]

    def pose(lam, idx=None):
        qq = q.copy() if idx is None else q[idx].copy()
        qq[:, :3] = home[:3] + (shift if idx is None else shift[idx]) / lam
        return qq

    head = (f"the ship motion at scale {scale:g} leaves the workspace: {_what(first)}")
    data = dict(joint=first.joint, index=first.index, value=first.value, scale=scale)
    rot = _violation(robot, pose(math.inf), t)
    if rot is not None:
        raise SeaWorkspaceError(
            f"{head}; no scale fits: the rotations alone (translations removed) leave it too "
            f"({_what(rot)}): choose a milder sea state, another heading or a point nearer "
            "the vessel's centre of rotation", rotations_only=True, **data)
    witnesses = {first.index}

    def fits(lam) -> bool:
        idx = np.array(sorted(witnesses))
        if _violation(robot, pose(lam, idx), t[idx]) is not None:
            return False
        exc = _violation(robot, pose(lam), t)
        if exc is not None:
            witnesses.add(exc.index)
            return False
        return True

    lo, hi = scale, 2.0 * scale
    for _ in range(_MAX_DOUBLINGS):
        if fits(hi):
            break
        lo, hi = hi, 2.0 * hi
    else:
        raise SeaWorkspaceError(
            f"{head}; no scale up to {hi:g} fits although the rotations alone do: the "
            "rotations are at the workspace's edge; choose a milder sea state",
            rotations_only=False, **data)
    while hi / lo - 1.0 > SCALE_RTOL:
        mid = math.sqrt(lo * hi)
        if fits(mid):
            hi = mid
        else:
            lo = mid
    span = (t[-1] - t[0]) * math.sqrt(scale)
    raise SeaWorkspaceError(
        f"{head}; this full-scale record ({span:.6g} s) fits from scale {hi:.4g} (bisection: "
        f"{lo:.4g} fails, {hi:.4g} fits): use scale >= {hi:.4g} (to replay the same record "
        f"there, scale duration and rate by sqrt({scale:g}/scale); other values draw "
        "another record), or a milder sea state", min_scale=hi, **data)


def _sea_motion(duration, rate, hs, tp, heading_deg, scale, robot, **options):
    from offshore_crane.motion.operations import Operation
    from offshore_crane.motion.trajectories import time_grid

    operation = options.pop("operation", None)
    time_grid(duration, rate)                           # validates duration, rate, size
    scale = _real(scale, "scale", "-", _SCALE_HINT, low=0.0)
    try:
        home = robot.home_pose()
    except AttributeError:
        raise SeaStateError("robot must come from offshore_crane.load_robot() (its "
                            "parameters give home_height)", name="robot") from None
    if operation is not None:
        if isinstance(operation, Operation):
            operation.check(robot)
        else:
            operation = Operation.from_waypoints(operation, robot)
    root = math.sqrt(scale)
    ship = sea_state(hs, tp, heading_deg, duration * root, rate / root, **options)
    return SeaMotion(ship, scale, home, operation, float(duration), float(rate))


def sea_motion(duration, rate, hs, tp, heading_deg, scale, robot, *, vessel="supply", seed=0,
               kind: str = "jonswap", gamma=None, point=(0.0, 0.0, 0.0), spreading=None,
               directions: int = DEFAULT_DIRECTIONS, highpass=None, operation=None,
               check: bool = True) -> SeaMotion:
    """The robot's reference motion (a callable source) from a ship in a sea state.

    Args:
        duration: Length of the model-scale record [s] (the full-scale sea spans
            ``duration · √scale``).
        rate: Model-scale sampling rate [Hz] (full scale ``rate / √scale``).
        hs, tp, heading_deg: Sea state at full scale ([m], [s], [deg]).
        scale: Froude scale λ = full-scale length / model length (> 0).
        robot: From :func:`offshore_crane.load_robot` (home height, limits).
        vessel, seed, kind, gamma, point, spreading, directions, highpass: As
            :func:`sea_state` (full-scale values: ``point`` [m], ``highpass`` [rad/s]).
        operation: Crane operation for q7..q9: waypoints ``[[t, q7, q8, q9], ...]``
            (model-scale time [s]) or an :class:`~offshore_crane.motion.operations.Operation`;
            None keeps the arm at zero.
        check: Check the record on its design grid against the workspace
            (:meth:`SeaMotion.check`).

    Returns:
        :class:`SeaMotion`.

    Raises:
        SeaStateError, TrajectoryError: bad arguments. SeaWorkspaceError: the record
        leaves the workspace (with the smallest scale that fits).
    """
    motion = _sea_motion(duration, rate, hs, tp, heading_deg, scale, robot, vessel=vessel,
                         seed=seed, kind=kind, gamma=gamma, point=point, spreading=spreading,
                         directions=directions, highpass=highpass, operation=operation)
    if check:
        motion.check(robot)
    return motion


def platform_trajectory(duration, rate, hs, tp, heading_deg, scale, robot, *,
                        vessel="supply", seed=0, kind: str = "jonswap", gamma=None,
                        point=(0.0, 0.0, 0.0), spreading=None,
                        directions: int = DEFAULT_DIRECTIONS, highpass=None, operation=None,
                        check: bool = True, name: str = "sea"):
    """The model-scale record of :func:`sea_motion` as a
    :class:`~offshore_crane.motion.trajectories.Trajectory` ``(name, t, q, qd, qdd)``.

    ``t = trajectories.time_grid(duration, rate)``; ``q`` ``(N, 9)`` with analytic
    ``qd``, ``qdd`` (see :class:`SeaMotion`). Arguments as :func:`sea_motion`.

    Raises:
        SeaStateError, TrajectoryError: bad arguments. SeaWorkspaceError: the record
        leaves the workspace; the message names the sample, the leg and the value, and
        the smallest scale at which the whole record fits (or that none does).
    """
    motion = _sea_motion(duration, rate, hs, tp, heading_deg, scale, robot, vessel=vessel,
                         seed=seed, kind=kind, gamma=gamma, point=point, spreading=spreading,
                         directions=directions, highpass=highpass, operation=operation)
    traj = motion.trajectory(name)
    if check:
        motion.check(robot, traj)
    return traj
