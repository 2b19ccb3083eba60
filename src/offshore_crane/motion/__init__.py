"""Motion sources: where ``t (N,)`` [s] and ``q, qd, qdd (N, 9)`` come from.

- :mod:`.trajectories`: the paper's Table 1, CSV files, finite differences, time grids;
- :mod:`.operations`: crane operations from waypoints (q7..q9);
- :mod:`.sea`: ship motion from sea states (spectra × a vessel's RAOs, Froude-scaled).

A motion source may check its own output against the robot
(:func:`offshore_crane.robot.kinematics.workspace`); it imports no dynamics.
"""

from __future__ import annotations

import importlib

__all__ = ["trajectories", "operations", "sea"]


def __getattr__(name: str):
    if name in __all__:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
