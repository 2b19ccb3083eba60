"""The robot: its description file, the URDF expanded from the xacro, and the arrays the
solvers read from it.

Loading (:func:`load_robot`) runs one path for every robot:

1. :func:`offshore_crane.robot.description.resolve` reads the description file (TOML,
   default ``models/descriptions/lab.toml``), applies the overrides (checked by
   :func:`offshore_crane.robot.overrides.normalise`), evaluates and checks everything;
2. :func:`offshore_crane.robot.xacro_cache.expand` expands the xacro with the resolved
   numbers (cached, verified, thread-safe);
3. the URDF is parsed, validated (:func:`offshore_crane.robot.validate.validate`) and
   read into the solvers' arrays (:func:`offshore_crane.robot.hybrid.hybrid_from_urdf`).
"""

from __future__ import annotations

import hashlib
import os
import threading
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

from offshore_crane.lazy import submodule_getattr
from offshore_crane.conventions import (ACTUATED_JOINTS, ACTUATORS, ACTUATOR_UNITS, ARM_JOINTS,
                           PLATFORM_JOINTS)
from offshore_crane.robot.hybrid import HybridModel
from offshore_crane.robot.urdf import URDF, parse_urdf
from offshore_crane.robot.xacro_cache import expand, xacro_path

if TYPE_CHECKING:
    import numpy as np

__all__ = ["Robot", "load_robot", "ACTUATORS", "ACTUATOR_UNITS", "ACTUATED_JOINTS",
           "ARM_JOINTS", "PLATFORM_JOINTS", "xacro_arguments"]

_ROBOTS: dict = {}
#: Guards :data:`_ROBOTS`: one thread builds a robot, the others wait for it and share it.
_ROBOTS_LOCK = threading.RLock()


class Robot:
    """The hybrid robot built from one description (or from a URDF alone).

    Attributes:
        urdf: The expanded URDF text (the equivalent tree).
        urdf_path: Cached file holding ``urdf`` (None if the cache is not writable, or for
            a robot built from URDF text).
        description: The parsed URDF (:class:`~offshore_crane.robot.urdf.URDF`).
        hybrid: Arrays the solvers read (:class:`HybridModel`).
        spec: The resolved robot description
            (:class:`~offshore_crane.robot.description.Description`), or None for a
            robot built from URDF text.
        overrides: ``{dotted name: value}`` applied to the description file.
        description_path: The description file, or None.
    """

    def __init__(self, urdf: str, urdf_path: Path | None = None, spec=None):
        from offshore_crane.robot.hybrid import hybrid_from_urdf
        from offshore_crane.robot.validate import validate

        self.spec = spec
        self.overrides = dict(spec.overrides) if spec is not None else {}
        self.description_path = spec.path if spec is not None else None
        #: The description file's bytes as read once (set by :func:`load_robot`).
        self.description_content: bytes | None = None
        self.urdf = urdf
        self.urdf_path = urdf_path
        self.description: URDF = parse_urdf(urdf)
        validate(self.description, home_height=None if spec is None else spec.home_height)
        self.hybrid: HybridModel = hybrid_from_urdf(self.description)

    @property
    def parameters(self) -> dict[str, str]:
        """The flat parameters of earlier versions (aliases) with their values as text,
        for the aliases whose field the description gives (``home_height`` always)."""
        from offshore_crane.robot.overrides import legacy_parameters

        if self.spec is None:
            from offshore_crane.robot.validate import home_height

            h = home_height(self.description)
            return {} if h is None else {"home_height": repr(float(h))}
        return legacy_parameters(self.spec.values, self.spec.has_arm)

    @property
    def load_limits(self):
        """The hanging load's limits (:class:`~offshore_crane.robot.description.LoadLimits`;
        none judged when the description gives none)."""
        from offshore_crane.robot.description import LoadLimits

        return LoadLimits() if self.spec is None else self.spec.load_limits

    @property
    def winch(self):
        """The winch's capacities
        (:class:`~offshore_crane.robot.description.WinchCapacities`; all ``inf`` when the
        description gives none)."""
        from offshore_crane.robot.description import WinchCapacities

        return WinchCapacities() if self.spec is None else self.spec.winch

    @property
    def capacities(self):
        """The actuators' capacities (:class:`~offshore_crane.robot.description.Capacities`,
        in the order of X; ``inf`` where the description gives none)."""
        if self.spec is None:
            from offshore_crane.robot.description import ACTUATORS as names, Capacities
            import numpy as np

            inf = np.full(len(names), np.inf)
            return Capacities(names, inf, inf.copy(), inf.copy(), inf.copy())
        return self.spec.capacities

    @property
    def home_height(self) -> float | None:
        """q3 of the home pose [m] (None when unknown)."""
        h = self.parameters.get("home_height")
        return None if h is None else float(h)

    def home_pose(self) -> "np.ndarray":
        """q ``(9,)`` of the home pose [m, rad]: zeros except ``q3 = home_height``.

        Raises:
            InputError: the description gives no home height (set ``home.height`` in
                it, or pass the pose explicitly).
        """
        import numpy as np

        from offshore_crane.errors import InputError

        h = self.home_height
        if h is None:
            raise InputError("the robot has no known home height: set home.height in its "
                             "description or give the pose q explicitly", name="q")
        q = np.zeros(9)
        q[2] = h
        return q

    def without_hanging_payload(self) -> "Robot":
        """This robot, or for a payload on a cable the same robot without it (its
        kinematics and workspace, which the payload does not change, for checks that
        need no force: the rigid solvers refuse a hanging payload)."""
        if self.hybrid.cable is None:
            return self
        from offshore_crane.robot.overrides import normalise

        welded = normalise({**self.overrides, "payload.mass": 0.0,
                            "payload.cable_length": 0.0, "payload.sway_damping": 0.0,
                            "payload.drag_area": 0.0})
        return _load(self.description_path, self.description_content, welded)

    @cached_property
    def pinocchio_model(self):
        """The equivalent tree as a ``pinocchio.Model`` (imports pinocchio on first use)."""
        from offshore_crane.errors import require

        pin = require("pinocchio", "pin", "The RNEA path")
        return pin.buildModelFromXML(self.urdf)

    def __repr__(self) -> str:
        name = self.spec.name if self.spec is not None else "urdf"
        return (f"Robot({name!r}, overrides={self.overrides}, "
                f"total_mass={self.hybrid.total_mass:.3f} kg)")


def xacro_arguments() -> dict[str, str]:
    """The flat parameter names of earlier versions with their default values (text):
    :func:`offshore_crane.robot.overrides.xacro_arguments`."""
    from offshore_crane.robot.overrides import xacro_arguments as arguments

    return arguments()


def load_robot(description: str | os.PathLike | None = None, overrides: dict | None = None,
               **aliases) -> Robot:
    """Load a robot from its description file, with overrides.

    Examples: ``load_robot()`` (the lab design), ``load_robot("my_platform.toml")``,
    ``load_robot(overrides={"legs.lower.mass": 3.1, "payload.mass": 2.0})``,
    ``load_robot(platform_mass=55.0)`` (flat names of earlier versions, aliases of the
    dotted ones; see :mod:`offshore_crane.robot.overrides`).

    Robots are memoised per process under (file, its content, overrides); expanded URDFs
    are cached on disk. Safe to call from several threads at once.

    Args:
        description: Path of a description file (TOML); None for the shipped default.
        overrides: ``{dotted name or alias: value}``.
        **aliases: More overrides given as keywords (flat names, or dotted names through
            ``**{"legs.lower.mass": 3}``).

    Raises:
        DescriptionError: a bad file, field or override (names the file and the field).
        ModelError: the expanded URDF is invalid (should not happen for a valid
            description).
    """
    from offshore_crane.robot.description import default_description, read_description
    from offshore_crane.robot.overrides import normalise

    merged = dict(overrides or {})
    for name, value in aliases.items():
        if name in merged:
            from offshore_crane.errors import DescriptionError

            raise DescriptionError(f"override: {name} given twice (in overrides and as a "
                                   "keyword)", path="override", field=name)
        merged[name] = value
    canonical = normalise(merged)
    path = os.fspath(description) if description is not None else os.fspath(
        default_description())
    if not isinstance(path, str):
        from offshore_crane.errors import InputError

        raise InputError(f"description must be a file path, got {description!r}",
                         name="description")
    content = read_description(path)               # once: a pipe cannot be read twice
    return _load(path, content, canonical)


def _load(path: str, content: bytes, canonical: dict) -> Robot:
    """The robot of description ``content`` (the bytes of ``path``) with the checked
    ``canonical`` overrides: memoised, resolved, expanded."""
    from offshore_crane.robot.description import frozen, resolve

    key = (os.path.abspath(path), hashlib.sha256(content).hexdigest(), frozen(canonical))
    robot = _ROBOTS.get(key)
    if robot is not None:
        return robot
    with _ROBOTS_LOCK:
        robot = _ROBOTS.get(key)
        if robot is None:
            spec = resolve(path, canonical, content=content)
            urdf, cached = expand(spec.xacro_data())
            robot = _ROBOTS[key] = Robot(urdf, cached, spec)
            robot.description_content = content
    return robot


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
