"""Dynamic identification of the built platform (issue 24): the actuator forces are linear
in the bodies' inertial parameters, ``X = Y(q, q̇, q̈) π``.

- :func:`regressor`: the closed-loop robot's regressor ``Y (N, 9, P)`` (the reference
  path's: Pinocchio's tree regressor projected through the loops), with optional friction
  columns; ``Y π`` equals Kane's X to round-off.
- :func:`base_parameters`: the identifiable combinations ``β = K π`` from a pivoted QR of
  the regressor stacked over :func:`random_states` (numerical rank at
  :data:`RANK_TOLERANCE`), each writable as its combination (:meth:`BaseParameters.describe`).
- :func:`fourier_excitation`: a finite Fourier series motion inside the workspace;
  :func:`fit_base`: the base parameters from a record by weighted least squares (QR and
  SVD of the weighted regressor, never normal equations), with their standard
  deviations, along what the record excites; :func:`consistent_parameters`: every
  body's ten parameters, physically consistent, closest to them (a convex problem,
  solved by a barrier method); :func:`base_rows`, :func:`mass_totals`,
  :func:`unexcited`: what a log determines and what the prior decided;
  :func:`identified_description`: the identified robot as a description file.

docs/identification.md has the formulas, the groupings and the checks.
"""

from offshore_crane.lazy import submodule_getattr

from offshore_crane.studies.identification._regressor import FRICTION, Regressor, regressor
from offshore_crane.studies.identification._base import (RANK_TOLERANCE, BaseParameters,
                                                         base_parameters, random_states)
from offshore_crane.studies.identification._excitation import (Fourier, excitation_condition,
                                                               fourier_excitation,
                                                               optimise_excitation,
                                                               within_limits)
from offshore_crane.studies.identification._fit import Fit, fit_base, log_derivatives
from offshore_crane.studies.identification._consistent import (PRIOR_WEIGHT, consistent,
                                                               consistent_parameters)
from offshore_crane.studies.identification._description import (bounded_bodies, com_bounds,
                                                                identified_description)
from offshore_crane.studies.identification._report import (WEAK, BaseRow, MassTotal,
                                                           base_rows, mass_totals, unexcited)

__all__ = ["FRICTION", "PRIOR_WEIGHT", "RANK_TOLERANCE", "WEAK", "BaseParameters", "BaseRow", "Fit",
           "Fourier", "MassTotal", "Regressor", "base_parameters", "base_rows",
           "bounded_bodies", "com_bounds", "consistent", "consistent_parameters",
           "excitation_condition", "fit_base", "fourier_excitation", "identified_description",
           "log_derivatives", "mass_totals", "optimise_excitation", "random_states",
           "regressor", "unexcited", "within_limits"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
