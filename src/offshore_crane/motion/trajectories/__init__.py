"""Joint-space trajectories of the 9-DOF crane: the paper's Table 1, CSV files, finite differences.

A trajectory is sampled on a time axis ``t`` ``(N,)`` [s] and gives the generalized
coordinates ``q`` ``(N, 9)`` with their first and second time derivatives ``qd`` and
``qdd``. Units are SI: ``q1, q2, q3, q9`` in [m] (``qd`` [m/s], ``qdd`` [m/s²]) and
``q4 .. q8`` in [rad] (``qd`` [rad/s], ``qdd`` [rad/s²]).

Sources:

* :func:`table1` evaluates the paper's Table 1 (sums of cosines) with analytic derivatives.
* :func:`read_csv` / :func:`write_csv` read and write ``t_s,q1,...,q9`` CSV files; the
  derivatives of a CSV trajectory come from :func:`finite_difference`.
* :func:`load` builds a :class:`Trajectory` from either."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.motion.trajectories.paper import (TABLE1_PERIOD, DEFAULT_RATE, MAX_SAMPLES,
                                                      time_grid, table1)
from offshore_crane.motion.trajectories.differences import finite_difference
from offshore_crane.motion.trajectories.files import (CSV_COLUMNS, CSV_COLUMNS_DERIVATIVES,
                                                      read_csv, write_csv)
from offshore_crane.motion.trajectories.records import Trajectory, hermite, load

__all__ = [
    "TABLE1_PERIOD",
    "DEFAULT_RATE",
    "CSV_COLUMNS",
    "time_grid",
    "table1",
    "finite_difference",
    "read_csv",
    "write_csv",
    "Trajectory",
    "load",
]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
