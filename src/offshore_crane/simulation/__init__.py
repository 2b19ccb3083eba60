"""The robot run forward in time: :mod:`.control` (control laws), :mod:`.driver` (the RK4
driver every plant and law runs on), :mod:`.rigid` (the 9-coordinate robot, its equations
in :mod:`.rigid_equations`), :mod:`.swing` (with the payload swinging on its cable) and
:mod:`.stepper` (a run a controller outside steps, one control period at a time)."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.simulation.control import Controller
from offshore_crane.simulation.rigid import SimulationResult, simulate
from offshore_crane.simulation.stepper import Stepper

__all__ = ["Controller", "SimulationResult", "Stepper", "simulate"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
