"""Dynamic identification of the built platform (issue 24): the actuator forces are linear
in the bodies' inertial parameters, ``X = Y(q, q̇, q̈) π``.

- :func:`regressor`: the closed-loop robot's regressor ``Y (N, 9, P)`` (the reference
  path's: Pinocchio's tree regressor projected through the loops), with optional friction
  columns; ``Y π`` equals Kane's X to round-off.
- :func:`base_parameters`: the identifiable combinations ``β = K π`` from a pivoted QR of
  the regressor stacked over :func:`random_states` (numerical rank at
  :data:`RANK_TOLERANCE`), each writable as its combination (:meth:`BaseParameters.describe`).
- :func:`fourier_excitation`: a finite Fourier series motion inside the workspace;
  :func:`fit_base`: the base parameters from a record by weighted least squares, with
  their standard deviations; :func:`consistent_parameters`: every body's ten parameters,
  physically consistent (log-Cholesky least squares), closest to them;
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

__all__ = ["FRICTION", "PRIOR_WEIGHT", "RANK_TOLERANCE", "BaseParameters", "Fit", "Fourier",
           "Regressor", "base_parameters", "bounded_bodies", "com_bounds", "consistent",
           "consistent_parameters", "excitation_condition", "fit_base", "fourier_excitation",
           "identified_description", "log_derivatives", "optimise_excitation",
           "random_states", "regressor", "within_limits"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
