"""Dynamic identification of the built platform (issue 24): the actuator forces are linear
in the bodies' inertial parameters, ``X = Y(q, q̇, q̈) π``.

- :func:`regressor`: the closed-loop robot's regressor ``Y (N, 9, P)`` (the reference
  path's: Pinocchio's tree regressor projected through the loops), with optional friction
  columns; ``Y π`` equals Kane's X to round-off.
- :func:`base_parameters`: the identifiable combinations ``β = K π`` from a pivoted QR of
  the regressor stacked over :func:`random_states` (numerical rank at
  :data:`RANK_TOLERANCE`), each writable as its combination (:meth:`BaseParameters.describe`).

docs/identification.md has the formulas, the groupings and the checks.
"""

from offshore_crane.studies.identification._regressor import FRICTION, Regressor, regressor
from offshore_crane.studies.identification._base import (RANK_TOLERANCE, BaseParameters,
                                                        base_parameters, random_states)

__all__ = ["FRICTION", "RANK_TOLERANCE", "BaseParameters", "Regressor", "base_parameters",
           "random_states", "regressor"]
