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

**A second vessel's deck** (:func:`deck_motion`, ship-to-ship transfer): the same sea
state and transfer to a point of a vessel with its own seed, the displacement of that
point scaled like the platform's translations.

**Froude scaling** (:func:`platform_trajectory`): lengths / λ, times / √λ, angles
unchanged; hence linear velocities / √λ, linear accelerations unchanged, angular rates
× √λ, angular accelerations × λ. ``q1..q3 = home + x_P / λ``,
``q4, q5, q6 = roll, pitch, yaw`` (vessel axes = robot base axes, x forward, y port,
z up; the small angles are used as the Z-Y-X angles of ``R = Rz(q6) Ry(q5) Rx(q4)``,
which agrees with the linear rotation to second order)."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.conventions import SPECTRA
from offshore_crane.motion.sea.arguments import DOFS, DEFAULT_DIRECTIONS
from offshore_crane.motion.sea.spectra import (default_gamma, jonswap_normalisation, spectrum,
                                               spreading_directions)
from offshore_crane.motion.sea.raos import RAO_COLUMNS, VESSELS, RAOTable, load_raos, vessel_raos
from offshore_crane.motion.sea.synthesis import (ShipMotion, check_arguments, vessel_names,
                                                 sea_state, response_spectrum, welch, ship_motion)
from offshore_crane.motion.sea.scaling import (SCALE_RTOL, SeaMotion, sea_motion,
                                               platform_trajectory, DeckMotion, deck_motion)

__all__ = ["DOFS", "SPECTRA", "RAO_COLUMNS", "VESSELS", "DEFAULT_DIRECTIONS",
           "spectrum", "default_gamma", "jonswap_normalisation", "spreading_directions",
           "response_spectrum",
           "RAOTable", "load_raos", "vessel_raos", "ShipMotion", "sea_state", "ship_motion",
           "SeaMotion", "sea_motion", "platform_trajectory", "DeckMotion", "deck_motion"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
