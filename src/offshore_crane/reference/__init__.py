"""Reference paths that share only the URDF with what they check.

A reference here reads the robot through ``robot.urdf`` / ``robot.pinocchio_model`` and
the joint and frame names of CONVENTIONS.md, and nothing else of the package's kinematics
or dynamics code, so that agreement with the Kane path is evidence rather than an echo.

- :mod:`.constrained`: closed-loop forward dynamics with Pinocchio's constraint dynamics
  (six 3-D loop constraints on the equivalent tree), and the tree states that close the
  loops (Newton on Pinocchio's frame placements and Jacobians).
"""

from __future__ import annotations

from .constrained import ConstrainedDynamics, TreeStates, constrained_dynamics, forward_dynamics, tree_states

__all__ = ["ConstrainedDynamics", "TreeStates", "constrained_dynamics", "forward_dynamics",
           "tree_states"]
