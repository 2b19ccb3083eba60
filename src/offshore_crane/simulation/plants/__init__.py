"""Plants the RK4 driver runs (:mod:`offshore_crane.simulation.driver`): the rigid robot
(:mod:`.rigid`), the robot with a payload hanging on a rigid cable (:mod:`.hanging`) and
with its payload on an elastic cable and a winch (:mod:`.elastic`). A plant is its state
layout, its right-hand side, what it records and its stops (:class:`Plant`); adding one is
one file and its test."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr
from offshore_crane.simulation.plants._base import Plant
from offshore_crane.simulation.plants.elastic import ElasticPlant
from offshore_crane.simulation.plants.hanging import HangingPlant
from offshore_crane.simulation.plants.rigid import RigidPlant

__all__ = ["ElasticPlant", "HangingPlant", "Plant", "RigidPlant"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`): the
#: compiled kernels' modules too (they import Numba).
__getattr__ = submodule_getattr(__name__)
