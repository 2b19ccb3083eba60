"""offshore-crane: inverse dynamics of a 9-DOF Stewart-platform + SCARA crane robot.

Quick start::

    import offshore_crane as oc
    robot = oc.load_robot()                      # expands models/offshore_crane.urdf.xacro
    q, qd, qdd = oc.trajectories.table1(t)       # (N, 9) each
    X = oc.inverse_dynamics(robot, q, qd, qdd)   # (N, 9): T1, T2 [N·m], Fs, Fl1..Fl6 [N]

Heavy dependencies (pinocchio, matplotlib, xacro, yourdfpy) are imported only when used.
"""

from __future__ import annotations

from .dynamics import inverse_dynamics
from .errors import (BackendMissingError, InputError, ModelError, NumericalError,
                     OffshoreCraneError, SceneError, SingularConfigurationError,
                     TrajectoryError, WorkspaceError)
from .conventions import ACTUATORS, ACTUATOR_UNITS, GRAVITY
from .kinematics.workspace import OffshoreCraneWarning, Thresholds
from .model import Robot, load_robot

__version__ = "0.1.0"

__all__ = ["load_robot", "inverse_dynamics", "trajectories", "Robot", "ACTUATORS",
           "ACTUATOR_UNITS", "GRAVITY", "Thresholds", "OffshoreCraneWarning",
           "OffshoreCraneError", "InputError", "TrajectoryError", "SceneError", "ModelError",
           "WorkspaceError", "SingularConfigurationError", "NumericalError",
           "BackendMissingError"]


def __getattr__(name):
    if name in ("trajectories", "serial", "scenes", "kinematics", "dynamics", "sea",
                "operations"):
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'offshore_crane' has no attribute '{name}'")
