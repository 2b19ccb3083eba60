"""Scenes: what a simulation contains, read from a small TOML file.

A scene says which sub-systems exist, how the legs are modelled, what hangs at the arm
tip, the gravity, the trajectory, which actuator forces are wanted and by which
method(s). The solver then computes nothing the scene does not need (see
:func:`offshore_crane.dynamics.solve`: arm-only outputs skip the legs, a static platform
skips its velocity and acceleration terms, massless legs skip their inertia terms; all
exact). ``offshore-crane id --scene FILE.toml`` runs one; ``scenes/`` holds examples.

Schema (every key optional; SI units; unknown keys or sections are errors)::

    name = "crane with payload"        # label (default: the file's stem)
    description = "..."                # free text
    gravity = [0.0, 0.0, -9.81]        # base frame [m/s²]
    outputs = ["T1", "T2", "Fs"]       # any of T1 T2 Fs Fl1..Fl6 (default: all that exist)
    methods = ["kane"]                 # kane | kane-explicit | rnea; two or more are
                                       # compared (max |ΔX| ≤ 1e-9 max |X|)

    [robot]                            # the robot (docs/robot-description.md)
    description = "my_platform.toml"   # its description file (relative to this file;
                                       # default: the shipped lab design)
    "legs.lower.mass" = 3.1            # any field, by its dotted name or its alias
    platform_mass = 55.0               # (platform_mass = platform.mass)

    [subsystems]
    platform = true                    # false: the arm on a fixed deck (no legs; only
                                       # T1, T2, Fs exist)
    arm = true                         # false: the Stewart platform alone (only Fl1..Fl6)
    leg_model = "full"                 # "full" (exact), "thin-rod", "massless"
                                       # (approximations, method kane only)
    deck_pose = [0, 0, 0.5, 0, 0, 0]   # q1..q6 of the fixed deck [m, rad]; only with
                                       # platform = false; default (0, 0, home_height, 0, 0, 0)

    [payload]                          # a rigid body welded to the frame arm_tip
    mass = 2.0                         # [kg], ≥ 0 (default 0: no payload)
    offset = [0.0, 0.0, -0.05]         # its centre of mass in the arm_tip frame [m]
    inertia = { ixx = 1e-3, iyy = 1e-3, izz = 1e-3, ixy = 0, ixz = 0, iyz = 0 }
                                       # about its centre of mass, arm_tip axes [kg·m²];
                                       # positive definite; default 0 (a point mass)
    cable_length = 0.0                 # [m]: > 0 hangs the payload (a point mass: offset
                                       # and inertia zero) on a cable from arm_tip
    sway_damping = 0.0                 # [N·m·s/rad] of each sway angle (with a cable)
    drag_area = 0.0                    # [m²] C_d·A of the payload in air (with a cable)
    air_density = 1.225                # [kg/m³] the air the drag acts in
    [cable]                            # the swing, with cable_length > 0 (docs/cable.md)
    initial = [0.05, 0.0]              # sway phi1, phi2 at the start [rad] (default 0)
    initial_rate = [0.0, 0.0]          # [rad/s]
    substeps = 1                       # RK4 steps per sample interval
    slack = "error"                    # or "warn": mark slack-cable samples and go on

    [actuators]                        # capacities: overrides of the description's
    Fl.push_max = 3000.0               # actuators.* fields (Fl = all legs, Fl1..Fl6, T1,
    T1 = { push_max = 40, pull_max = 40 }   # T2, Fs; push_max, pull_max, speed_max,
                                       # power_max) [N, N·m, m/s, rad/s, W]

    [trajectory]
    source = "table1"                  # "table1", "sea" ([sea] below) or a CSV file
                                       # t_s,q1..q9 (relative to this file)
    duration = 31.4159                 # table1, sea: model-scale span from t = 0 [s]
                                       # (default 10π for table1, 60 for sea)
    rate = 100.0                       # table1, sea: sampling rate [Hz] (default 100)
    fd_order = 4                       # CSV only: finite-difference order 2, 4 or 6

    [sea]                              # source = "sea": a ship in a sea state, Froude-
    hs = 2.5                           # scaled onto q1..q6 (offshore_crane.motion.sea,
    tp = 8.0                           # docs/sea.md); full-scale Hs [m], Tp [s],
    heading = 90.0                     # heading [deg] (180 head seas, 90 from starboard)
    scale = 20.0                       # Froude scale λ (full-scale length / model length)
    vessel = "supply"                  # shipped vessel or an RAO CSV (relative to this file)
    kind = "jonswap"                   # or "pierson-moskowitz"; gamma = 3.3 (JONSWAP only)
    spreading = 4.0                    # cos-2s exponent (short-crested); directions = 36
    seed = 0                           # random phases
    point = [0.0, 0.0, 0.0]            # the crane's base on the vessel [m], full scale
    highpass = 0.3                     # drop components below this [rad/s], full scale

    [operation]                        # q7..q9 with source = "sea" (else held at zero)
    waypoints = [[0, 0, 0, 0.1], [5, 0.8, -0.5, 0.2]]  # [t s, q7 rad, q8 rad, q9 m], quintic

How a scene maps onto the robot and the solver:

- ``[robot]``, ``[payload]`` and ``[subsystems] arm`` are overrides of the robot
  description, all checked by one path (:func:`offshore_crane.robot.overrides.normalise`
  and the description's own checks, as if written in the description file): ``arm =
  false`` is ``arm.enabled = false`` (no column, links, slider; q7..q9 of the trajectory
  are then ignored); ``[payload]`` ``mass``, ``offset``, ``inertia`` are ``payload.mass``,
  ``payload.com``, ``payload.inertia`` (a link ``payload`` welded to ``arm_tip``, which
  the Kane and the Pinocchio paths both read). A field given two different values (in
  ``[robot]`` and ``[payload]``, or by the scene and ``--set``) is an error.
- ``platform = false``: the legs are not evaluated and q1..q6 of the trajectory are
  replaced by ``deck_pose`` with zero rates, so the static-platform pruning applies.

Errors are :class:`~offshore_crane.errors.SceneError` with a one-line message naming the
file and the key, e.g. ``scenes/x.toml: [payload] mass = -1: must be ≥ 0 kg``."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.scenes.reading import scene_from_dict, load_scene
from offshore_crane.scenes.assembly import (controller, instruments, deck_pose, sea_trajectory, load_robot,
                                            still_water_level, target_deck, lift_deck,
                                            with_robot_overrides, load_trajectory,
                                            sea_workspace_error, with_trajectory,
                                            with_overrides, with_values)
from offshore_crane.scenes.stepping import stepper
from offshore_crane.scenes.running import (SceneRun, CABLE_METHODS, SwingPlan, compare_methods,
                                           run, run_swing, swing_plan, cable_simulation,
                                           plant_options)
from offshore_crane.scenes.fidelity import Fidelity, compare_fidelity, format_fidelity
from offshore_crane.scenes.keys import (SECTIONS, TOP_KEYS, SUBSYSTEM_KEYS, PAYLOAD_KEYS,
                                        CABLE_KEYS, INERTIA_KEYS, TRAJECTORY_KEYS, SEA_KEYS,
                                        SEA_REQUIRED, OPERATION_KEYS, SEA_DURATION, SEA_RATE,
                                        CONTROL_KEYS, CONTROLLER_KEYS, SCENE_FIELDS,
                                        FIDELITY_REPEAT)
from offshore_crane.scenes.scene import Payload, Scene, sea_arguments, check_scene, hoist_waypoints


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
