"""The RNEA reference path: Pinocchio's RNEA on the equivalent tree, projected on u.

It shares nothing with Kane's code but the URDF: it reads the joint placements, axes and
frames from Pinocchio's own model of it (``robot.pinocchio_model``, the names of
``docs/conventions.md``), and imports only Pinocchio, NumPy, Numba and the package's
ground floor.

1. :mod:`.tree`: the serial chains read from Pinocchio's model (:func:`read_tree`).
2. :mod:`.closure`: loop closure (:func:`tree_state`): for each leg, the passive
   U-joint angles and leg length that put ``leg{i}_tip`` on ``platform_anchor{i}``
   (Newton on the leg chain's tip), their rates and accelerations (compiled with Numba).
3. :mod:`.projection`: ``τ = RNEA(q_tree, v_tree, a_tree)`` [N, N·m] by
   ``pin.rneaInParallel``, projected on the independent speeds (``Gᵀ S X = Gᵀ τ``,
   solved by QR) (:func:`actuator_forces`).

It returns raw arrays (:class:`Forces`: X, condition numbers, leg lengths, U-joint
angles, sphere heights); it applies no workspace limit nor singularity policy: its caller
(``offshore_crane.dynamics``, ``method="rnea"``) does.

Frames: the base frame is Pinocchio's world (the URDF root ``base``); units SI.
"""

from offshore_crane.lazy import submodule_getattr

from offshore_crane.reference.rnea.closure import (MAX_NEWTON, MAX_TURN, RESIDUAL_TOL,
                                                   tree_state, tree_states)
from offshore_crane.reference.rnea.projection import (BLOCK, Forces, actuator_forces, pool,
                                                      project, rnea_projected)
from offshore_crane.reference.rnea.tree import Chain, Tree, read_tree

__all__ = ["BLOCK", "MAX_NEWTON", "MAX_TURN", "RESIDUAL_TOL", "Chain", "Forces", "Tree",
           "actuator_forces", "pool", "project", "read_tree", "rnea_projected", "tree_state",
           "tree_states"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
