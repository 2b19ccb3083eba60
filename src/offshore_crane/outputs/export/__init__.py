"""Exports of the robot to other tools' formats.

- :mod:`offshore_crane.outputs.export.mjcf`: a MuJoCo model (MJCF) with the six loops closed by
  equality constraints (``offshore-crane export --mjcf``).

Nothing here is imported by ``import offshore_crane``; the exporters need no optional
package (the MuJoCo checks import ``mujoco`` lazily).
"""

from offshore_crane.lazy import submodule_getattr


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
