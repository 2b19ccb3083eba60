"""offshore-crane: inverse dynamics of a 9-DOF Stewart-platform + SCARA crane robot.

Quick start::

    import offshore_crane as oc
    robot = oc.load_robot()                      # models/descriptions/lab.toml -> URDF
    q, qd, qdd = oc.trajectories.table1(t)       # (N, 9) each
    X = oc.inverse_dynamics(robot, q, qd, qdd)   # (N, 9): T1, T2 [N·m], Fs, Fl1..Fl6 [N]
    qdd2 = oc.forward_dynamics(robot, q, qd, X)  # (N, 9), = qdd to round-off
    run = oc.simulate(robot, 10.0, oc.trajectories.table1, controller=oc.Controller())

Heavy dependencies (pinocchio, matplotlib, xacro, yourdfpy) are imported only when used.
"""

from __future__ import annotations

from .dynamics import inverse_dynamics
from .dynamics.forward import (actuation_matrix, bias_forces, equations_of_motion,
                               forward_dynamics, mass_matrix)
from .errors import (BackendMissingError, ConstraintResidualError,
                     DescriptionError, GridError, InputError, InsufficientSeedsError,
                     ModelError, NumericalError, OffshoreCraneError, OutputError,
                     ResultsDirectoryError, SceneError, SchedulerError, SeaStateError,
                     SeaWorkspaceError, SimulationError, SingularConfigurationError,
                     SlackCableError, TrajectoryError, ViewerError, WorkspaceError)
from .conventions import ACTUATORS, ACTUATOR_UNITS, GRAVITY
from .kinematics.workspace import OffshoreCraneWarning, Thresholds
from .model import Robot, load_robot
from .control import Controller
from .simulate import SimulationResult, simulate     # the function (the module: sys.modules)

__version__ = "0.1.0"

__all__ = ["load_robot", "inverse_dynamics", "forward_dynamics", "mass_matrix",
           "bias_forces", "actuation_matrix", "equations_of_motion", "simulate",
           "SimulationResult", "Controller", "trajectories", "Robot", "ACTUATORS",
           "ACTUATOR_UNITS", "GRAVITY", "Thresholds", "OffshoreCraneWarning",
           "OffshoreCraneError", "InputError", "TrajectoryError", "SceneError", "ModelError",
           "DescriptionError", "WorkspaceError", "SingularConfigurationError",
           "NumericalError", "ConstraintResidualError", "SimulationError", "OutputError",
           "SeaStateError", "SeaWorkspaceError", "BackendMissingError",
           "InsufficientSeedsError", "GridError", "ResultsDirectoryError", "SchedulerError",
           "SlackCableError", "ViewerError"]


def __getattr__(name):
    if name in ("trajectories", "serial", "scenes", "kinematics", "dynamics", "sea",
                "operations", "sizing", "sweep", "cable", "cable_simulation", "visual",
                "export"):
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'offshore_crane' has no attribute '{name}'")
