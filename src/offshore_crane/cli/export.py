"""``offshore-crane export``: the robot as a MuJoCo model (MJCF) with the loops closed,
or a scene's crane as an FMI co-simulation unit (``--fmu``, docs/control.md).

Writes the robot of ``--robot``/``--set``/``--scene`` as an MJCF file: the legs as
U-joint + slide with motors, the six spherical joints as equality constraints, the arm's
joints with motors, every inertia from the URDF, written at the home pose or ``--pose``
with the loops closed. ``--check`` loads it in MuJoCo and compares its accelerations
with ours along Table 1 (needs the optional extra ``mujoco``). See docs/mjcf.md.
"""

from __future__ import annotations

from offshore_crane.errors import InputError

#: Samples of Table 1 that ``--check`` compares (over its 10π s span).
CHECK_SAMPLES = 50


def add_parser(sub) -> None:
    from offshore_crane.cli.common import add_robot_options

    doc = __doc__.splitlines()
    p = sub.add_parser("export", help="the robot as a MuJoCo model (MJCF)",
                       description=doc[0].split(": ", 1)[1] + " " + " ".join(
                           line.strip() for line in doc[2:7]))
    p.add_argument("--mjcf", metavar="FILE.xml", help="write the MuJoCo model to this file "
                   "('.xml'; '-': standard output)")
    p.add_argument("--fmu", metavar="FILE.fmu", help="write the scene's crane as an FMI "
                   "2.0 co-simulation FMU (needs --scene and --control-period; the extra "
                   "'fmu')")
    p.add_argument("--control-period", type=float, metavar="S", help="--fmu: the FMU's "
                   "communication step [s], a whole number of the scene's integration steps")
    p.add_argument("--duration", type=float, metavar="S", help="--fmu: the run [s] "
                   "(default: the scene's)")
    p.add_argument("--action", choices=("forces", "reference"), default="forces",
                   help="--fmu: the FMU's inputs, the actuators' forces (default) or a "
                   "reference for the scene's controller")
    p.add_argument("--scene", metavar="FILE.toml", help="scene whose robot and gravity "
                   "are exported")
    p.add_argument("--pose", metavar="Q1,...,Q9", help="configuration written (qpos0 and "
                   "the keyframe 'hold') [m, rad], comma-separated; default the home pose")
    p.add_argument("--sway", metavar="PHI1,PHI2", help="cable angles [rad] of a hanging "
                   "load (default 0,0)")
    p.add_argument("--gravity", type=float, nargs=3, metavar=("GX", "GY", "GZ"),
                   help="gravity in the base frame [m/s²] (default: the scene's, else "
                   "0 0 -9.81)")
    p.add_argument("--limits", action="store_true", help="write the joint ranges of the "
                   "URDF and the actuators' capacities as ctrlrange (default: none, the "
                   "comparison model)")
    p.add_argument("--timestep", type=float, metavar="S", help="MuJoCo's time step [s] "
                   "(default 0.001); the loops' time constant is two steps")
    p.add_argument("--no-hold", action="store_true", help="do not compute the static forces "
                   "of the keyframe 'hold'")
    p.add_argument("--check", action="store_true", help="load the model in MuJoCo and "
                   "compare its forward dynamics with ours along Table 1 (exit 1 beyond the "
                   "stated tolerance)")
    add_robot_options(p)
    p.set_defaults(run=run)


def run(args) -> int:
    import sys

    import numpy as np

    from offshore_crane import scenes
    from offshore_crane.io import plan_outputs, write_text
    from offshore_crane.cli.common import comma_numbers, robot_scene

    if args.fmu is not None:
        return _fmu(args)
    if args.mjcf is None:
        raise InputError("export: give --mjcf FILE.xml or --fmu FILE.fmu", name="--mjcf")
    pose = None if args.pose is None else np.array(comma_numbers(args.pose, 9, "--pose"))
    sway = None if args.sway is None else np.array(comma_numbers(args.sway, 2, "--sway"))
    scene = robot_scene(args, scenes.load_scene(args.scene) if args.scene else scenes.Scene())
    outputs = plan_outputs({"--mjcf": args.mjcf}, [args.scene, *scene.inputs()],
                           {"--mjcf": ("xml",)})
    say = (lambda *a: print(*a, file=sys.stderr)) if outputs["--mjcf"].kind == "stdout" \
        else print
    robot = scenes.load_robot(scene)
    gravity = scene.gravity if args.gravity is None else tuple(args.gravity)
    from offshore_crane.outputs.export.mjcf import TIMESTEP, export

    model = export(robot, pose, sway=sway, gravity=gravity, limits=args.limits,
                   hold=not args.no_hold,
                   timestep=TIMESTEP if args.timestep is None else args.timestep)
    if "ea" in scene.cable:
        say(f"note: the scene's elastic cable (EA = {scene.cable['ea']:g} N) is written as the "
            "rigid cable, its EA -> infinity limit (docs/mjcf.md)")
    if robot.hybrid.drag > 0.0:
        say(f"note: the payload's air drag (payload.drag_area = {robot.hybrid.drag_area:g} m²) "
            "is not written (MuJoCo's fluid models would put air on every body); --check "
            "compares with our swing without it (docs/mjcf.md)")
    status = _check(model, robot, gravity, say) if args.check else 0
    write_text(outputs["--mjcf"], model.xml)
    say(f"offshore-crane export: {robot.spec.name if robot.spec else 'urdf'}, "
        f"{len(model.joints)} joints, {len(model.actuators)} motors, 6 loops, "
        f"qpos0 = {'--pose' if pose is not None else 'home pose'}"
        + ("" if model.hold is None else
           f"; keyframe 'hold': ctrl = {np.array2string(model.hold, precision=4)}"))
    say(f"wrote {args.mjcf}")
    return status


def _fmu(args) -> int:
    """``--fmu``: the scene's crane as an FMU (:func:`offshore_crane.fmu.export_fmu`),
    every path checked before it is built."""
    from offshore_crane import scenes
    from offshore_crane.errors import require
    from offshore_crane.io import plan_outputs

    if args.mjcf is not None:
        raise InputError("export: give --mjcf or --fmu, one at a time", name="--fmu")
    for flag, value in (("--scene", args.scene), ("--control-period", args.control_period)):
        if value is None:
            raise InputError(f"export --fmu needs {flag}", name=flag)
    scene = scenes.load_scene(args.scene)
    target = plan_outputs({"--fmu": args.fmu}, [args.scene, *scene.inputs()],
                          {"--fmu": ("fmu",)})["--fmu"]
    if target.kind != "file":
        raise InputError(f"--fmu {args.fmu}: an FMU is a zip archive: give a file",
                         name="--fmu")
    require("pythonfmu", '"offshore-crane[fmu]"', "export --fmu")
    from offshore_crane.fmu import export_fmu

    export_fmu(args.scene, target, control_period=args.control_period,
               duration=args.duration, action=args.action)
    print(f"wrote {args.fmu}: FMI 2.0 co-simulation, step {args.control_period:g} s "
          f"(docs/control.md)")
    return 0


def _states(robot, gravity):
    """Table 1 (``CHECK_SAMPLES`` samples over 10π s) when it fits the robot's workspace,
    else as many seeded states within 1 cm and 0.05 rad of home (rates 0.3 m/s, rad/s;
    accelerations 2 m/s², rad/s²; the arm's Table 1 motion when there is an arm)."""
    import numpy as np

    from offshore_crane import inverse_dynamics
    from offshore_crane.motion import trajectories
    from offshore_crane.errors import WorkspaceError
    from offshore_crane.robot.kinematics import legs

    t = np.linspace(0.0, 10 * np.pi, CHECK_SAMPLES)
    q, qd, qdd = trajectories.table1(t)
    if not robot.hybrid.has_arm:
        q[:, 6:] = qd[:, 6:] = qdd[:, 6:] = 0.0
    try:
        return "Table 1", q, qd, qdd, inverse_dynamics(robot, q, qd, qdd, gravity=gravity)
    except WorkspaceError:
        pass
    rng = np.random.default_rng(0)
    scale = np.array([0.01, 0.01, 0.01, 0.05, 0.05, 0.05])
    near = rng.uniform(-1.0, 1.0, (20 * CHECK_SAMPLES, 6)) * scale
    near[:, 2] += robot.home_height
    trial = np.hstack([near, np.resize(q[:, 6:], (len(near), 3))])
    length = legs(robot, trial).length
    stroke = robot.hybrid.stroke
    inside = np.all((length > stroke[:, 0]) & (length < stroke[:, 1]), axis=1)
    n = min(CHECK_SAMPLES, int(inside.sum()))
    q[:n, :6] = trial[inside][:n, :6]
    q, qd, qdd = q[:n], qd[:n], qdd[:n]
    qd[:, :6] = rng.uniform(-0.3, 0.3, (n, 6))
    qdd[:, :6] = rng.uniform(-2.0, 2.0, (n, 6))
    return ("states near home (Table 1 leaves this robot's workspace)", q, qd, qdd,
            inverse_dynamics(robot, q, qd, qdd, gravity=gravity))


def _check(model, robot, gravity, say) -> int:
    """MuJoCo's forward dynamics of ``model`` against ours (printed): exit status 1 beyond
    :data:`~offshore_crane.outputs.export.mjcf.AGREEMENT`."""
    import numpy as np

    from offshore_crane import forward_dynamics
    from offshore_crane.conventions import COORDINATES
    from offshore_crane.outputs.export.mjcf import AGREEMENT, forward

    if robot.hybrid.cable is not None:
        return _check_hanging(model, robot, gravity, say)
    name, q, qd, qdd, X = _states(robot, gravity)
    ours = forward_dynamics(robot, q, qd, X, gravity=gravity)
    res = forward(model, robot, q, qd, X)
    ratio = res.agreement(ours)
    worst = int(np.argmax(ratio))
    ok = bool(ratio.max() <= AGREEMENT)
    say(f"MuJoCo vs Kane forward dynamics, {name} ({len(q)} samples, X from our inverse "
        f"dynamics): loops closed to {res.loop.max():.1e} m; max |Δq̈| / max constraint "
        f"acceleration = {ratio.max():.2e} ({COORDINATES[worst]}) "
        f"({'OK' if ok else 'FAIL'}, limit {AGREEMENT:g})")
    return 0 if ok else 1


def _check_hanging(model, robot, gravity, say) -> int:
    """With a hanging load: our swing along Table 1 (10 s at 100 Hz from a sway of
    (0.1, −0.05) rad, X from :func:`offshore_crane.dynamics.cable.inverse_dynamics`), every
    ``200 / CHECK_SAMPLES``-th sample set in MuJoCo: its accelerations against the
    prescribed q̈ and our sway accelerations (exit status 1 beyond AGREEMENT)."""
    import numpy as np

    from offshore_crane.dynamics import cable
    from offshore_crane.motion import trajectories
    from offshore_crane.conventions import COORDINATES
    from offshore_crane.outputs.export.mjcf import AGREEMENT, forward

    if robot.hybrid.drag > 0.0:                 # the model as written: without the drag
        from offshore_crane.robot import load_robot

        robot = load_robot(robot.description_path, {**robot.overrides,
                                                     "payload.drag_area": 0.0})
    t = trajectories.time_grid(10.0, 100.0)
    q, qd, qdd = trajectories.table1(t)
    run = cable.inverse_dynamics(robot, q, qd, qdd, reference=trajectories.table1,
                                 gravity=gravity, initial=(0.1, -0.05), t=t)
    k = np.linspace(0, len(t) - 1, CHECK_SAMPLES).astype(int)
    res = forward(model, robot, q[k], qd[k], run.X[k], sway=run.sway[k],
                  sway_rate=run.sway_rate[k])
    ratio = res.agreement(qdd[k])
    sway = float(np.abs(res.qacc[:, 9:11] - run.sway_accel[k]).max()
                 / np.abs(run.sway_accel[k]).max())
    worst = int(np.argmax(ratio))
    ok = bool(ratio.max() <= AGREEMENT and sway <= AGREEMENT)
    say(f"MuJoCo vs our swing (offshore_crane.dynamics.cable), Table 1 with the hanging load "
        f"({len(k)} samples): loops closed to {res.loop.max():.1e} m; max |Δq̈| / max "
        f"constraint acceleration = {ratio.max():.2e} ({COORDINATES[worst]}), sway "
        f"accelerations {sway:.2e} of their largest "
        f"({'OK' if ok else 'FAIL'}, limit {AGREEMENT:g})")
    return 0 if ok else 1
