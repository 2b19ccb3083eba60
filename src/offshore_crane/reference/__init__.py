"""Reference paths that share only the URDF with what they check.

A reference here reads the robot through ``robot.urdf`` / ``robot.pinocchio_model`` and
the joint and frame names of ``docs/conventions.md``, and nothing else of the package's
kinematics or dynamics code, so that agreement with the Kane paths is evidence rather
than an echo. Nothing is imported here: each module loads its heavy dependencies
(Numba, Pinocchio) itself.

- :mod:`.rnea`: Pinocchio's RNEA on the equivalent tree, with loop-closing tree states of
  its own (inverse dynamics, ``method="rnea"``).
- :mod:`.constrained`: closed-loop forward dynamics with Pinocchio's constraint dynamics
  (six 3-D loop constraints on the equivalent tree), and the tree states that close the
  loops (Newton on Pinocchio's frame placements and Jacobians).
"""
