"""Names, units and tolerances that several modules share (one place for each).

The coordinates, frames and signs they refer to are described in ``docs/conventions.md``
(the repository's conventions page); this module only holds the values the code needs.
"""

from __future__ import annotations

#: Number of U-P-S legs of the Stewart-Gough platform.
N_LEGS = 6
#: Number of independent coordinates q1..q9 (docs/conventions.md, "Coordinates").
N_COORDINATES = 9
#: Names of q1..q9 and their units.
COORDINATES = tuple(f"q{i}" for i in range(1, N_COORDINATES + 1))
COORDINATE_UNITS = ("m", "m", "m", "rad", "rad", "rad", "rad", "rad", "m")


def coordinate_column(k: int, order: int = 0, tag: str = "") -> str:
    """The CSV column of coordinate ``k`` (0-based), its unit in the name: ``q1_m``,
    ``qd4_rad_s``, ``qdd9_m_s2`` for ``order`` 0, 1, 2; ``tag`` before the unit
    (``q1_ref_m``). The one rule every CSV writer and reader follows."""
    return (f"{'q' + 'd' * order}{k + 1}{tag}_{COORDINATE_UNITS[k]}"
            + ("", "_s", "_s2")[order])


#: ``q1_m .. q9_m``, their rates and accelerations, as CSV columns.
Q_COLUMNS = tuple(coordinate_column(k) for k in range(N_COORDINATES))
QD_COLUMNS = tuple(coordinate_column(k, 1) for k in range(N_COORDINATES))
QDD_COLUMNS = tuple(coordinate_column(k, 2) for k in range(N_COORDINATES))
#: Column names CSV files had before units were in them (``q1``, ``qd1``, ``qdd1``,
#: ``q1_ref``), each with today's name: files written then are still read.
LEGACY_COLUMNS = {**{f"q{k + 1}": Q_COLUMNS[k] for k in range(N_COORDINATES)},
                  **{f"qd{k + 1}": QD_COLUMNS[k] for k in range(N_COORDINATES)},
                  **{f"qdd{k + 1}": QDD_COLUMNS[k] for k in range(N_COORDINATES)},
                  **{f"q{k + 1}_ref": coordinate_column(k, tag="_ref")
                     for k in range(N_COORDINATES)}}

#: Order of the actuator vector X (paper Eq. 40).
ACTUATORS = ("T1", "T2", "Fs", "Fl1", "Fl2", "Fl3", "Fl4", "Fl5", "Fl6")
ACTUATOR_UNITS = ("N·m", "N·m", "N", "N", "N", "N", "N", "N", "N")
ARM_ACTUATORS = ACTUATORS[:3]
LEG_ACTUATORS = ACTUATORS[3:]

#: URDF joints (the equivalent tree, docs/conventions.md "The equivalent tree (URDF)").
PLATFORM_JOINTS = ("platform_x", "platform_y", "platform_z",
                   "platform_roll", "platform_pitch", "platform_yaw")   # q1..q6
ARM_JOINTS = ("arm_joint1", "arm_joint2", "arm_slide")                  # q7..q9
#: The hanging load's sway joints (when payload.cable_length > 0): phi1 about x of arm_tip,
#: phi2 about the rotated y (docs/cable.md); they follow the arm joints in the tree.
CABLE_JOINTS = ("cable_joint1", "cable_joint2")
SWAY = ("phi1", "phi2")
LEG_JOINTS = tuple((f"leg{i}_u1", f"leg{i}_u2", f"leg{i}_slide")
                   for i in range(1, N_LEGS + 1))
ACTUATED_JOINTS = ARM_JOINTS + tuple(j[2] for j in LEG_JOINTS)
LEG_TIPS = tuple(f"leg{i}_tip" for i in range(1, N_LEGS + 1))
PLATFORM_ANCHORS = tuple(f"platform_anchor{i}" for i in range(1, N_LEGS + 1))

#: Default gravity in the base frame [m/s²] (z up).
GRAVITY = (0.0, 0.0, -9.81)
#: Density of air [kg/m³] at sea level and 15 °C (ISO 2533 standard atmosphere): the
#: default ``payload.air_density`` of the hanging payload's drag.
AIR_DENSITY = 1.225

#: Two exact methods (Kane and the RNEA reference, which share only the URDF) must agree
#: to this, relative to max |X|: both are exact, so they differ by round-off (~1e-15);
#: 1e-9 leaves room for ill-conditioned poses (κ ε ≤ 2e-11 below the warning threshold).
AGREEMENT_RTOL = 1e-9

#: Relative tolerance (of λ1 + λ2 + λ3) of the inertia checks (positive semi-definite,
#: triangle inequality): URDF and CAD files print inertias with 6-7 significant digits,
#: and a thin disc sits exactly on the triangle boundary.
INERTIA_RTOL = 1e-6

#: From this many samples a short-lived process gains by the compiled kernels: loading
#: Numba and the cached kernels costs ~1.2 s, the NumPy kernels ~2 µs a sample more
#: (:func:`offshore_crane.dynamics.quick_backend`).
NUMBA_MIN = 500_000

#: Samples per block of the fused Kane pass vectorised across samples
#: (:mod:`offshore_crane.dynamics.lanes`): two AVX-512 registers of doubles (measured on
#: the 2-core machine, the formulas alone: 8 lanes 713 ns a sample, 16 lanes 290, 32 lanes
#: 273, one sample at a time 770). Calls with fewer samples run one sample at a time.
LANES = 16

#: Wave spectra of :mod:`offshore_crane.motion.sea` (here so that the command line lists them
#: without importing the sea module).
SPECTRA = ("jonswap", "pierson-moskowitz")
