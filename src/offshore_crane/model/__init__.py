"""The robot: its xacro, the expanded URDF and the arrays the solvers read from it."""

from __future__ import annotations

from functools import cached_property
from pathlib import Path

from ..conventions import (ACTUATED_JOINTS, ACTUATORS, ACTUATOR_UNITS, ARM_JOINTS,
                           PLATFORM_JOINTS)
from .hybrid import HybridModel
from .urdf import URDF, parse_urdf
from .xacro_cache import expand, normalise_overrides, xacro_arguments, xacro_path

__all__ = ["Robot", "load_robot", "ACTUATORS", "ACTUATOR_UNITS", "ACTUATED_JOINTS",
           "ARM_JOINTS", "PLATFORM_JOINTS", "xacro_arguments"]

_ROBOTS: dict = {}


class Robot:
    """The hybrid robot built from one expansion of the xacro.

    Attributes:
        overrides: ``{xacro argument: value text}`` applied to the defaults.
        urdf: The expanded URDF text (the equivalent tree).
        urdf_path: Cached file holding ``urdf`` (None if the cache is not writable).
        description: The parsed URDF.
        hybrid: Arrays the solvers read (:class:`HybridModel`).
    """

    def __init__(self, urdf: str, urdf_path: Path | None = None, overrides: dict | None = None):
        from .hybrid import hybrid_from_urdf

        self.overrides = dict(overrides or {})
        self.urdf = urdf
        self.urdf_path = urdf_path
        self.description: URDF = parse_urdf(urdf)
        from .validate import validate
        validate(self.description, self.parameters)      # masses, inertias, lengths, home
        self.hybrid: HybridModel = hybrid_from_urdf(self.description)

    @property
    def parameters(self) -> dict[str, str]:
        """All xacro arguments with the values used (defaults overridden)."""
        return {**xacro_arguments(), **self.overrides}

    @cached_property
    def pinocchio_model(self):
        """The equivalent tree as a ``pinocchio.Model`` (imports pinocchio on first use)."""
        from ..errors import require

        pin = require("pinocchio", "pin", "The RNEA path")
        return pin.buildModelFromXML(self.urdf)

    def __repr__(self) -> str:
        return f"Robot(overrides={self.overrides}, total_mass={self.hybrid.total_mass:.3f} kg)"


def load_robot(**overrides) -> Robot:
    """Expand the robot's xacro with ``overrides`` (xacro arguments) and load it.

    Example: ``load_robot(platform_mass=55.0, leg_max_length=0.8)``. Robots are memoised
    per process under their normalised overrides; expanded URDFs are cached on disk.

    Raises:
        ModelError: unknown parameter name, non-numeric value, invalid structure.
    """
    key = tuple(normalise_overrides(overrides).items())
    robot = _ROBOTS.get(key)
    if robot is None:
        urdf, path = expand(dict(key))
        robot = _ROBOTS.setdefault(key, Robot(urdf, path, dict(key)))   # one per key, even
    return robot                                                        # across threads
