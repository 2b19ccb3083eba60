"""Studies over runs: :mod:`.sizing` (envelopes against the actuators' capacities,
extreme-value fits, verdicts), :mod:`.sweep` (grids of cases on joblib or Dask,
resumable results, operability) and :mod:`.identification` (the regressor and the base
parameters of the built platform)."""

from __future__ import annotations

import importlib

__all__ = ["identification", "sizing", "sweep"]


def __getattr__(name: str):
    if name in __all__:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
