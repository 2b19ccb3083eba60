"""offshore-crane: dynamics of a 9-DOF Stewart-platform + SCARA crane robot.

Quick start::

    import offshore_crane as oc
    from offshore_crane.motion import trajectories
    robot = oc.load_robot()                      # models/descriptions/lab.toml -> URDF
    t = trajectories.time_grid(10.0, 100.0)      # (N,) [s]
    q, qd, qdd = trajectories.table1(t)          # (N, 9) each
    X = oc.inverse_dynamics(robot, q, qd, qdd)   # (N, 9): T1, T2 [N·m], Fs, Fl1..Fl6 [N]
    qdd2 = oc.forward_dynamics(robot, q, qd, X)  # (N, 9), = qdd to round-off
    run = oc.simulate(robot, 10.0, trajectories.table1, controller=oc.Controller())

The package is a pipeline of columns, each a sub-package (``docs/architecture.md``):
``robot`` → ``motion`` → ``dynamics`` (``reference`` checks it) → ``simulation`` →
``scenes`` → ``studies`` → ``outputs``, with ``serial`` (any URDF chain) beside them and
``errors`` (every exception, rooted at :class:`~offshore_crane.errors.OffshoreCraneError`)
on the ground floor. Sub-packages and heavy dependencies (pinocchio, matplotlib, xacro,
yourdfpy) are imported only when used.
"""

from __future__ import annotations

import importlib

from offshore_crane.lazy import find_submodule
from offshore_crane.dynamics import Result, inverse_dynamics
from offshore_crane.dynamics.forward import (EquationsOfMotion, actuation_matrix,
                                             bias_forces, forward_dynamics, mass_matrix)
from offshore_crane.robot import Robot, load_robot
from offshore_crane.simulation import Controller, SimulationResult, Stepper, simulate

__version__ = "0.1.0"

__all__ = ["load_robot", "Robot", "inverse_dynamics", "forward_dynamics", "mass_matrix",
           "bias_forces", "actuation_matrix", "simulate", "Controller", "Result",
           "CableResult", "EquationsOfMotion", "SimulationResult", "Stepper"]

#: The columns, loaded on first use as ``oc.<name>`` (as is every other sub-module, and
#: theirs in turn: ``oc.dynamics.cable``; :mod:`offshore_crane.lazy`).
SUBPACKAGES = ("errors", "conventions", "robot", "motion", "dynamics", "reference",
               "simulation", "scenes", "studies", "outputs", "serial", "cli")

#: Names kept importable from the top for compatibility (not in ``__all__``): the
#: exceptions (their home is :mod:`offshore_crane.errors`) and a few constants.
_COMPATIBLE = {"ACTUATORS": "conventions", "ACTUATOR_UNITS": "conventions",
               "GRAVITY": "conventions", "Thresholds": "robot.kinematics.workspace",
               "OffshoreCraneWarning": "robot.kinematics.workspace",
               "equations_of_motion": "dynamics.forward", "CableResult": "dynamics.cable"}


def __getattr__(name: str):
    module = find_submodule(__name__, name)
    if module is not None:
        return module
    if name in _COMPATIBLE:
        return getattr(importlib.import_module(f"{__name__}.{_COMPATIBLE[name]}"), name)
    errors = importlib.import_module(f"{__name__}.errors")
    if name.endswith("Error") and hasattr(errors, name):
        return getattr(errors, name)
    raise AttributeError(f"module 'offshore_crane' has no attribute '{name}'")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__) | set(SUBPACKAGES))
