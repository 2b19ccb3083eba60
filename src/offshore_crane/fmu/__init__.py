"""The crane as an FMI 2.0 co-simulation unit (``pip install "offshore-crane[fmu]"``):
:func:`export_fmu` writes a scene's crane as an FMU (``offshore-crane export --fmu``),
built by PythonFMU, whose model is :class:`~offshore_crane.fmu.model.CraneSlave` (its
simulation in a process of its own, :mod:`offshore_crane.fmu._worker`).
docs/control.md says how to run it (FMPy, OpenModelica, a co-simulation master) and
what the machine that runs it needs.
"""

from __future__ import annotations

from offshore_crane.errors import require

require("pythonfmu", '"offshore-crane[fmu]"', "offshore_crane.fmu (the FMU export)")

from offshore_crane.fmu._export import MODEL, export_fmu  # noqa: E402
from offshore_crane.lazy import submodule_getattr  # noqa: E402

__all__ = ["MODEL", "export_fmu"]

#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
