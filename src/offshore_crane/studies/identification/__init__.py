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
  body's ten parameters, physically consistent (by :data:`MARGIN` of the nominal robot;
  judged as a description file judges it: :func:`physical`), closest to them (a convex
  problem, solved by a barrier method); :func:`fit_log`, :func:`predict`: a log of any
  length block by block;
  :func:`base_rows`, :func:`mass_totals`, :func:`unexcited`: what a log determines and
  what the prior decided;
  :func:`identified_description`: the identified robot as a description file.

docs/identification.md has the formulas, the groupings and the checks.
"""

from offshore_crane.lazy import submodule_getattr

from offshore_crane.studies.identification._regressor import (FRICTION, Regressor,
                                                              actuator_rows, identifiable,
                                                              regressor, regressor_blocks)
from offshore_crane.studies.identification._base import (RANK_TOLERANCE, BaseParameters,
                                                         base_parameters, random_states)
from offshore_crane.studies.identification._excitation import (Fourier, excitation_condition,
                                                               excited, fourier_excitation,
                                                               optimise_excitation,
                                                               within_limits)
from offshore_crane.studies.identification._fit import (Fit, Triangles, fit_base,
                                                        log_derivatives)
from offshore_crane.studies.identification._blocks import fit_log, predict
from offshore_crane.studies.identification._consistent import (MARGIN, PRIOR_WEIGHT,
                                                               consistent,
                                                               consistent_parameters)
from offshore_crane.studies.identification._description import (bounded_bodies, com_bounds,
                                                                identified_description,
                                                                physical)
from offshore_crane.studies.identification._report import (WEAK, BaseRow, MassTotal,
                                                           base_rows, mass_totals, unexcited)

__all__ = ["FRICTION", "MARGIN", "PRIOR_WEIGHT", "RANK_TOLERANCE", "WEAK",
           "BaseParameters", "BaseRow", "Fit", "Fourier", "MassTotal", "Regressor",
           "Triangles", "actuator_rows", "base_parameters", "base_rows",
           "bounded_bodies", "com_bounds", "consistent", "consistent_parameters",
           "excitation_condition", "excited", "fit_base", "fit_log", "fourier_excitation",
           "identifiable", "identified_description", "log_derivatives", "mass_totals",
           "optimise_excitation", "physical", "predict", "random_states", "regressor",
           "regressor_blocks", "unexcited", "within_limits"]

#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
