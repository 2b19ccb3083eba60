"""Motion sources: where ``t (N,)`` [s] and ``q, qd, qdd (N, 9)`` come from.

- :mod:`.trajectories`: the paper's Table 1, CSV files, finite differences, time grids;
- :mod:`.operations`: crane operations from waypoints (q7..q9);
- :mod:`.sea`: ship motion from sea states (spectra × a vessel's RAOs, Froude-scaled).

A motion source may check its own output against the robot
(:func:`offshore_crane.robot.kinematics.workspace`); it imports no dynamics.
"""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

__all__ = ["trajectories", "operations", "sea"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
