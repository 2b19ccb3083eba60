"""The crane as a Gymnasium environment (``pip install "offshore-crane[gym]"``).

Importing this module registers ``CraneLift-v0``::

    import gymnasium
    env = gymnasium.make("offshore_crane.gym:CraneLift-v0",
                         scene="scenes/compensated_lift.toml", control_period=0.01)

:class:`CraneLift` (the environment), :class:`LiftReward` (its default reward),
:class:`CraneLiftVector` (many seeds at once in worker processes:
``gymnasium.make_vec(..., num_envs=16, vectorization_mode="vector_entry_point",
workers=2)``). docs/control.md walks through them.
"""

from __future__ import annotations

from offshore_crane.errors import require

require("gymnasium", '"offshore-crane[gym]"', "offshore_crane.gym (the Gymnasium "
        "environment)")

from gymnasium.envs.registration import register, registry  # noqa: E402

from offshore_crane.gym._env import CraneLift  # noqa: E402
from offshore_crane.gym._reward import LiftReward  # noqa: E402
from offshore_crane.gym._vector import CraneLiftVector  # noqa: E402
from offshore_crane.lazy import submodule_getattr  # noqa: E402

__all__ = ["CraneLift", "CraneLiftVector", "LiftReward"]

#: The environment's id (``offshore_crane.gym:`` before it in ``gymnasium.make``).
ID = "CraneLift-v0"
if ID not in registry:
    register(id=ID, entry_point="offshore_crane.gym._env:CraneLift",
             vector_entry_point="offshore_crane.gym._vector:CraneLiftVector")

#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
