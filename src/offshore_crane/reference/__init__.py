"""Reference paths that share only the URDF with what they check.

A reference here reads the robot by attribute only -- ``robot.pinocchio_model``
(Pinocchio's model of the URDF's equivalent tree) and the joint and frame names of
``docs/conventions.md`` (:mod:`offshore_crane.conventions`) -- and imports only Pinocchio,
NumPy, Numba and the package's ground floor (errors, conventions, spatial, io,
validation), never the robot, motion or dynamics code (an import-linter contract in
``pyproject.toml`` keeps it so): agreement with the Kane paths is evidence rather than an
echo. Whatever it needs of the robot (leg chains, payload mass, sway damping, joint
limits) it reads from Pinocchio's model. Nothing is imported here: each module loads its
heavy dependencies (Numba, Pinocchio) itself.

- :mod:`.rnea`: Pinocchio's RNEA on the equivalent tree, with loop-closing tree states of
  its own (inverse dynamics, ``method="rnea"``). It returns raw arrays (X, condition
  numbers, leg lengths, U-joint angles, sphere heights); its caller in
  ``offshore_crane.dynamics`` applies the workspace limits and the singularity policy.
- :mod:`.cable`: the hanging load by Pinocchio (sway joints of the URDF), likewise raw;
  ``offshore_crane.dynamics.cable`` checks it.
- :mod:`.constrained`: closed-loop forward dynamics with Pinocchio's constraint dynamics
  (six 3-D loop constraints on the equivalent tree), and the tree states that close the
  loops (Newton on Pinocchio's frame placements and Jacobians); it checks its own
  residuals and the URDF's joint limits.
"""

from offshore_crane.lazy import submodule_getattr


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
