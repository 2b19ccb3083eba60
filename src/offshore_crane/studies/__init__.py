"""Studies over runs: :mod:`.sizing` (envelopes against the actuators' capacities,
extreme-value fits, verdicts), :mod:`.sweep` (grids of cases on joblib or Dask,
resumable results, operability) and :mod:`.identification` (the regressor and the base
parameters of the built platform)."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

__all__ = ["design", "identification", "sizing", "sweep"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
