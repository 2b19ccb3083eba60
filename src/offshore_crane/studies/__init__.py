"""Studies over runs: :mod:`.sizing` (envelopes against the actuators' capacities,
extreme-value fits, verdicts) and :mod:`.sweep` (grids of cases on joblib or Dask,
resumable results, operability)."""

from __future__ import annotations

import importlib

__all__ = ["sizing", "sweep"]


def __getattr__(name: str):
    if name in __all__:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
