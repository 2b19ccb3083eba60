"""Robot description files: any 6-U-P-S platform with a crane arm, from its data.

A robot description is a TOML file holding every number of the robot: where the twelve
joints are, what each body weighs, where its centre of mass sits and its inertia tensor,
the strokes and joint limits, the actuators' capacities and the payload.
``models/descriptions/lab.toml`` (the placeholder lab design, the default) and
``models/descriptions/harib_srinivasan_2003.toml`` (a platform from the literature) are
the shipped examples; ``docs/robot-description.md`` is the user's guide. The robot's URDF
is still expanded from the one xacro ``models/offshore_crane.urdf.xacro``: this module
reads, checks and resolves the description, and the xacro reads the resolved numbers
(:meth:`Description.xacro_data`, written as YAML and loaded with ``xacro.load_yaml``).

Units are SI throughout (m, kg, kg·m², rad, N, N·m, m/s, rad/s, W); the only exception
is spelled in the key (``*_deg``: degrees). Frames (docs/conventions.md):

- **base**: fixed, z up; the URDF root. P_i, the U-joint centres, are in it.
- **platform**: origin O2, the platform's *reference point*, whose position in the base
  frame is (q1, q2, q3); axes turned by ``R_base_platform = Rz(q6) Ry(q5) Rx(q4)``. The
  S_i (sphere centres), the platform's centre of mass ``platform.com`` and the arm
  column's placement are in it. O2 is the centre of mass when ``platform.com`` is zero
  (the default, as in the paper); a description may put O2 anywhere, e.g. at the centre
  of the joint circle, and q1..q3 are then that point's position.
- **leg part frames**: the lower part's frame has its origin at P_i, the upper part's at
  S_i; both have z along the leg from P_i towards S_i and x along the U-joint's second
  axis a2 (``R_base_leg = R_base_U Ry(θ1) Rx(θ2)``, columns ``[a2, u × a2, u]``).
  A part's centre of mass and inertia are given in its frame.
- **arm frames**: ``arm_column`` is welded to the platform at ``arm.column.origin``
  (platform frame, rotated by ``arm.column.rpy``); each joint's origin and axis are in
  its parent body's frame (link1 in the column's, link2 in link1's, the slider in
  link2's); the tip frame ``arm_tip`` is placed in the slider's frame; the payload in
  the tip's.
- rpy angles follow URDF: ``R = Rz(yaw) Ry(pitch) Rx(roll)`` for ``rpy = [roll, pitch,
  yaw]`` [rad].
- Inertia tensors are about the body's centre of mass, in its frame's axes, as the six
  URDF numbers ``{ ixx, iyy, izz, ixy, ixz, iyz }`` [kg·m²] (products ``ixy = -∫xy dm``
  as in URDF; omitted products are 0).

Format (every key; ``*`` required)::

    format = 1                  # version of this format
    name = "lab"                # label (default: the file's stem)
    source = "..."              # free text: where the numbers come from

    [home]
    height = 0.5                # * q3 of the home pose [m]: O2's height with q1 = q2 =
                                # q4 = q5 = q6 = 0. The loops must close there (every leg
                                # inside its stroke) and the U-joints are oriented there.

    [base.joints]               # * the U-joint centres P_i, base frame [m], EITHER
    points = [[x, y, z], ...]   #   six points (leg 1 first), OR on a circle:
    radius = 0.6                #   radius [m],
    height = 0.05               #   height of the circle's plane [m],
    angles_deg = [...]          #   the six polar angles [deg], or pairs: legs 2k-1, 2k
    half_angle_deg = 15         #   at pair_angles_deg[k] -/+ half_angle_deg,
    pair_angles_deg = [0, 120, 240]      # (default [0, 120, 240])
    [base]
    ujoint_axes = [[x, y, z], ...]  # first U-joint axis a1 of each leg, base frame (unit
                                # length not required). Default: horizontal and
                                # perpendicular to the leg at home, so both U-joint angles
                                # are zero at home.
    ujoint_axes2 = [[...], ...] # second axis a2 at zero U-joint angles (perpendicular to
                                # a1); the leg direction at zero angles is a2 x a1.
                                # Default: the leg's home direction fixes it.
    shape = {...}               # the base's drawing (a shape table, below)

    [platform]
    mass = 40.0                 # * [kg]
    com = [0, 0, 0]             # centre of mass relative to O2, platform frame [m]
    inertia = { ixx = ..., iyy = ..., izz = ..., ixy = 0, ixz = 0, iyz = 0 }
                                # * about the CoM [kg·m²] (or derived from shape)
    shape = { type = "cylinder", radius = 0.4, length = 0.04, xyz = [0, 0, 0] }
    [platform.joints]           # * the sphere centres S_i, platform frame [m]: as
                                # [base.joints]; pairs: legs 2k, 2k+1 (leg 7 = leg 1) at
                                # pair_angles_deg[k] -/+ half_angle_deg, default
                                # [60, 180, 300]

    [legs.lower]                # * the lower part (cylinder, on the U-joint); frame: origin
                                # P_i, z along the leg
    mass = 2.0                  # * [kg]
    length = 0.42               # * extent from P_i along z [m]; the CoM must lie in 0..length
    radius = 0.035              # drawing radius [m]; without inertia: a solid cylinder
    com = [0, 0, 0.21]          # default (0, 0, length/2) [m]
    inertia = {...}             # about the CoM, part frame [kg·m²]
    [legs.upper]                # * the upper part (rod, on the sphere); frame: origin S_i,
                                # z along the leg; extent -length..0; CoM default
                                # (0, 0, -length/2)
    [legs.stroke]
    min = 0.40                  # * shortest |P_i S_i| [m]
    max = 0.82                  # * longest [m]
    [legs.ujoint]
    limit = 1.2                 # * |angle| limit of both U-joint axes [rad], 0 < limit <= pi/2
    [legs.3.lower]              # per-leg values: any key of lower, upper, stroke, ujoint
    mass = 2.1                  # for leg 3 only (the others keep [legs.lower])

    [arm]
    enabled = true              # false: the Stewart platform alone (alias with_arm).
                                # Without an [arm] table the robot has no arm.
    [arm.column]                # body 2, welded to the platform
    origin = [0, 0, 0.02]       # * in the platform frame [m]
    rpy = [0, 0, 0]             # [rad]
    mass, com, inertia, shape   # as the platform
    [arm.link1]                 # body 3 on arm_joint1 (revolute, q7); also link2 (body 4,
                                # arm_joint2, q8) and slider (body 5, arm_slide, prismatic, q9)
    origin = [0, 0, 0.33]       # * joint origin in the parent body's frame [m]
    rpy = [0, 0, 0]             # joint frame orientation [rad]
    axis = [0, 0, 1]            # joint axis in the joint frame (default z; slider x)
    min = -3.3                  # * lower joint limit [rad] (slider [m])
    max = 3.3                   # * upper joint limit
    mass, com, inertia, shape   # body in the joint frame
    [arm.tip]
    origin = [0.3, 0, 0]        # * frame arm_tip in the slider's frame [m]
    rpy = [0, 0, 0]

    [payload]                   # a rigid body welded to arm_tip (requires the arm)
    mass = 0.0                  # [kg], 0: no payload
    com = [0, 0, 0]             # its centre of mass in the arm_tip frame [m]
    inertia = {...}             # about its CoM [kg·m²]; omitted entries 0 (default: a
                                # point mass)
    cable_length = 0.0          # [m]; 0: welded. > 0 is read by the hanging-load model
                                # (issue 12); the URDF always welds the payload.

    [payload.limits]            # a hanging load's limits, judged by size (none: none)
    sway_max_deg = 45.0         # largest sway from the tip's vertical [deg], in (0, 90]
    tension_ratio_min = 0.1     # smallest tension / static tension m·g, in [0, 1)
    tension_max = 100.0         # largest cable tension [N]

    [actuators.Fl]              # capacities of the six leg actuators (Fl1..Fl6 for one);
                                # also T1, T2 (arm motors [N·m], [rad/s]) and Fs (slider)
    push_max = 5000             # largest force along + (extension) [N] (torque [N·m])
    pull_max = 5000             # largest force along - [N] (magnitude)
    speed_max = 0.5             # largest |rate| [m/s] ([rad/s])
    power_max = 2000            # largest |force x rate| [W]; default: no limit
                                # (unlimited: inf, TOML's literal)

    shape = { type = "cylinder" | "box" | "sphere" | "none", radius = r, length = h,
              size = [a, b, c], xyz = [x, y, z] }
        A solid of uniform density centred at xyz (cylinder axis z, box edges along
        x, y, z): the body's drawing, and its inertia (with com = xyz) when the body
        gives no inertia. Default drawings are made from the dimensions.

Expressions: any number may be a string holding an arithmetic expression over other
fields (:mod:`offshore_crane.robot.expressions`), e.g. ``z = "-platform.shape.length / 2"``;
an override of a field moves every number computed from it.

Dotted names: every number has one (``legs.lower.mass``, ``platform.inertia.ixx``,
``payload.com.z``, ``base.joints.points.3.z``, ``actuators.Fl.push_max``); overrides
(``load_robot(overrides=...)``, ``--set NAME=VALUE``, a scene's ``[robot]`` table) use
them, and the flat names of earlier versions are aliases
(:mod:`offshore_crane.robot.overrides`).

Validation (:func:`resolve`, one path for the file and every override; errors are
:class:`~offshore_crane.errors.DescriptionError` naming the file and the field): unknown
keys, missing fields, wrong shapes and types, unit strings, non-finite numbers,
magnitudes above :data:`MAGNITUDE_LIMIT`; negative masses, inertias that no rigid body has
(not positive semi-definite, or breaking the triangle inequality, relative tolerance
:data:`INERTIA_RTOL`), a leg part's centre of mass outside the part; coincident or
collinear anchors; empty ranges; a home pose that does not close the loops (a leg outside
its stroke, a sphere centre below its U-joint, a U-joint outside its limits); U-joint
axes parallel to the leg; a singular leg arrangement at home."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.robot.description.schema import (FORMAT, DESCRIPTION_DIR, DEFAULT_DESCRIPTION,
                                                     N_LEGS, MAGNITUDE_LIMIT, COM_RTOL,
                                                     ANCHOR_RTOL, ORTHOGONAL_TOL,
                                                     HOME_CONDITION_LIMIT, GIMBAL_LIMIT,
                                                     REVOLUTE_LIMIT, DISC_MARGIN, DISC_THICKNESS,
                                                     LEG_DRAW_RATIO, ARM_DRAW_RATIO, LEG_KEYS,
                                                     ACTUATOR_GROUPS, ACTUATORS, ARM_BODIES,
                                                     INERTIA_KEYS, XYZ, Leaf, SHAPE, BODY, PART,
                                                     LEG, ACTUATOR, PLACEMENT, JOINT_BODY, SCHEMA,
                                                     leaf_components, field_names, schema_lookup)
from offshore_crane.robot.description.values import as_boolean
from offshore_crane.robot.description.results import (Capacities, Body, ArmJoint, Description,
                                                     LoadLimits, WinchCapacities)
from offshore_crane.robot.description.loading import resolve, frozen, resolve_data
from offshore_crane.robot.description.files import (description_dir, default_description, read_description,
                                                    read_toml, label)


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
