"""Sea-state arguments: the checks shared by the spectra, the synthesis and the scaling (one-
line :class:`~offshore_crane.errors.SeaStateError` naming the argument, its unit and what to
give), and the constants they share.
"""

from __future__ import annotations

import math

import numpy as np

from offshore_crane.conventions import SPECTRA
from offshore_crane.errors import SeaStateError


#: The six rigid-body DOFs, in the order of every ``(N, 6)`` array here [m, m, m, rad,
#: rad, rad].
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


#: Default number of spreading directions: 10-deg bins, the heading step of the supply
#: vessel's table.
DEFAULT_DIRECTIONS = 36


# Headings closer than this to a table heading [deg] are that heading (round-off of
# angle arithmetic such as 360 - 350).
HEADING_TOL_DEG = 1e-9
# Relative round-off allowed when comparing heading spacings (a few ulp of 360 deg).
SPACING_RTOL = 1e-12


SCALE_HINT = "give the Froude scale lambda = full-scale length / model length, > 0"
# Uniform grid inside a sea_state: the same rule as trajectories.time_grid.
GRID_EPS = 1e-9


# ---------------------------------------------------------------------------- validation
def real(value, name: str, unit: str, hint: str, *, low=None, low_open=True,
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


def integer(value, name: str, low: int, hint: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise SeaStateError(f"{name} must be an integer, got {value!r}: {hint}", name=name)
    if value < low:
        raise SeaStateError(f"{name} = {value} must be >= {low}: {hint}", name=name)
    return int(value)


def vector3(value, name: str, unit: str) -> np.ndarray:
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


def sea_arguments(hs, tp, heading_deg, kind, gamma) -> tuple[float, float, float, str,
                                                                 float | None]:
    hs = real(hs, "hs", "m", "give the significant wave height", low=0.0)
    tp = real(tp, "tp", "s", "give the peak period", low=0.0)
    heading = real(heading_deg, "heading", "deg",
                    "give the wave heading (180 = head seas, 90 = from starboard)")
    if kind not in SPECTRA:
        raise SeaStateError(f"unknown spectrum kind {kind!r}: use one of "
                            f"{', '.join(SPECTRA)}", name="kind")
    if kind == "pierson-moskowitz" and gamma is not None:
        raise SeaStateError(f"gamma = {gamma!r} applies to the JONSWAP spectrum only: leave "
                            "it out with kind='pierson-moskowitz'", name="gamma")
    gamma = real(gamma, "gamma", "-", "the JONSWAP peak enhancement must be >= 1 (1 is "
                  "Pierson-Moskowitz)", low=1.0, low_open=False, allow_none=True)
    return hs, tp, heading, kind, gamma
