"""MuJoCo model (MJCF) of the robot, with the six loops closed (``docs/mjcf.md``).

The model is generated from the robot's expanded URDF (the equivalent tree, parsed as
``robot.description``; the drawing from ``robot.urdf``) and nothing else: every mass,
centre of mass, inertia tensor, joint placement and axis is the URDF's. Plain XML
(:mod:`xml.etree`); writing a model needs no MuJoCo, loading and checking one does
(:func:`load`, :func:`forward`, optional extra ``mujoco``).

Structure (MuJoCo bodies, in the order of the URDF tree):

- ``platform``: one body carrying the six virtual joints of the URDF, in its order:
  slides ``platform_x``, ``platform_y``, ``platform_z`` (q1, q2, q3 [m]) then hinges
  ``platform_yaw`` (q6), ``platform_pitch`` (q5), ``platform_roll`` (q4) [rad]. MuJoCo
  applies the joints of one body in order, each about its axis in the frame the previous
  ones moved, so the platform's orientation is ``Rz(q6) Ry(q5) Rx(q4)``: the convention
  of ``docs/conventions.md``. (The URDF's massless links between them cannot be MuJoCo
  bodies: MuJoCo refuses a moving body without mass.) No motor, damping or armature.
- ``arm_column`` (welded to the platform), ``arm_link1``, ``arm_link2``, ``arm_slider``
  on hinges ``arm_joint1`` (q7), ``arm_joint2`` (q8) and slide ``arm_slide`` (q9);
  ``arm_tip`` and ``payload`` welded below (a site when massless). When the URDF has the
  hanging load's joints ``cable_joint1`` (about x of ``arm_tip``) and ``cable_joint2``
  (about y), they become two hinges of the ``payload`` body (phi1, phi2 [rad]).
- ``leg{i}_lower``: the U-joint, hinges ``leg{i}_u1`` (axis a1) then ``leg{i}_u2``;
  ``leg{i}_upper`` below it on slide ``leg{i}_slide``, whose position is the leg length
  [m]. The sites ``leg{i}_tip`` (on the upper link) and ``platform_anchor{i}`` (on the
  platform) are the sphere centre S_i seen from either side.
- ``<equality><connect site1="leg{i}_tip" site2="platform_anchor{i}">``: the spherical
  joints, which close the loops (MuJoCo's soft constraints, made as stiff as MuJoCo
  allows: :data:`SOLREF`, :data:`SOLIMP`).
- Motors with gear 1 on the nine actuated joints, named and ordered as X
  (``T1, T2, Fs, Fl1..Fl6``): ``data.ctrl`` is X [N·m, N].

Joint positions equal the URDF's (``ref`` sets each joint's value in the written
configuration, see :func:`_chain_placement`): ``qpos`` holds q1..q9 (platform rotations
in the order q6, q5, q4), the U-joint angles and the leg lengths (:attr:`MJCF.joints`).
The model is written in a configuration where the loops are closed, the robot's home
pose or a given ``q``, so that ``qpos0`` closes them; the keyframe ``hold`` holds that
pose with the static actuator forces as ``ctrl``."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.outputs.export.mjcf.exporting import joint_values, export
from offshore_crane.outputs.export.mjcf.tree import mjcf_from_urdf
from offshore_crane.outputs.export.mjcf.mujoco import mujoco_state, load, MujocoForward, forward
from offshore_crane.outputs.export.mjcf.settings import (TIMESTEP, INTEGRATOR, SOLREF, SOLIMP,
                                                         AGREEMENT, SOLVER, SOLVER_ITERATIONS,
                                                         SOLVER_TOLERANCE, CABLE_JOINTS,
                                                         POINT_MASS_INERTIA, MJCF)

__all__ = ["MJCF", "export", "mjcf_from_urdf", "joint_values", "mujoco_state", "load",
           "forward", "MujocoForward", "AGREEMENT", "CABLE_JOINTS", "TIMESTEP", "INTEGRATOR", "SOLREF", "SOLIMP"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
