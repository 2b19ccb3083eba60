"""``offshore-crane animate``: a GIF or MP4 of the robot following a motion.

The motion comes from a scene (``--scene``), a trajectory (``--trajectory table1|sea|F.csv``)
or a run's CSV (``--from``: ``offshore-crane simulate --out`` or a trajectory CSV). The
robot is drawn from the URDF's shapes, headless; ``--color-by`` paints the legs by their
actuator force (computed by inverse dynamics when the source has none).
"""

from __future__ import annotations

from offshore_crane.errors import InputError

#: Default picture size [pixels] and frame rate [1/s].
SIZE = "640x480"


def add_source_options(p) -> None:
    """``--scene``, ``--trajectory``, ``--from``, ``--duration``, the robot and gravity
    (shared by ``animate`` and ``view``)."""
    from offshore_crane.cli.common import add_robot_options

    p.add_argument("--scene", metavar="FILE.toml", help="scene file: robot, trajectory "
                   "(e.g. scenes/sea_state_crane.toml)")
    p.add_argument("--trajectory", help="'table1', 'sea' (with a scene's [sea]) or a CSV "
                   "t_s,q1..q9[,qd..,qdd..]")
    p.add_argument("--from", dest="run_csv", metavar="RUN.csv",
                   help="a run's CSV: offshore-crane simulate --out (q and forces), or a "
                   "trajectory CSV; with a hanging load, phi1_rad,phi2_rad are read too")
    p.add_argument("--duration", type=float, metavar="S", help="motion time to show from "
                   "its start [s] (default: all of it)")
    add_robot_options(p)
    p.add_argument("--gravity", type=float, nargs=3, metavar=("GX", "GY", "GZ"),
                   help="gravity in the base frame [m/s²] (default: the scene's, else 0 0 "
                   "-9.81)")


def scene_of(args):
    """The scene of ``--scene`` / ``--trajectory`` with ``--robot``, ``--set``,
    ``--gravity`` applied."""
    from offshore_crane import scenes
    from offshore_crane.cli.common import robot_scene

    if args.run_csv is not None and args.trajectory is not None:
        raise InputError("--from and --trajectory both give the motion: choose one",
                         name="--from")
    scene = robot_scene(args, scenes.load_scene(args.scene) if args.scene else scenes.Scene())
    where = f"{args.scene} with the command-line options" if args.scene else "command line"
    scene = scenes.with_trajectory(scene, where, args.trajectory)
    if args.gravity is not None:
        scene = scenes.with_overrides(scene, where, gravity=tuple(args.gravity))
    return scene


def inputs_of(args, scene) -> list:
    """Files the command reads (an output may not overwrite one)."""
    return [args.scene, args.run_csv, *scene.inputs()]


def load_motion(args, scene):
    """``(robot, motion)`` of the scene, or of ``--from``. A scene whose cable varies (a
    winch, an elastic cable, a compensation, a lift) is run first
    (:func:`offshore_crane.scenes.run_swing`), a lift's deck or a ship-to-ship target's
    moving aim drawn as a plate; ``--from`` with one is refused."""
    from offshore_crane import scenes
    from offshore_crane.outputs.visual import motion as mo

    from dataclasses import replace

    later = scene.varying_cable
    if later and args.run_csv is not None:
        raise InputError(f"{', '.join(later)}: --from reads a rigid cable's run only (a "
                         "varying or slack cable is drawn from --scene, its lift run "
                         "first)", name="--from")
    robot = scenes.load_robot(scene)
    water = scenes.still_water_level(scene, robot)
    if later:
        traj = scenes.load_trajectory(scene, robot)
        run = scenes.run_swing(scene, robot, traj, "kane")
        motion = mo.varying_cable(robot, run.cable, f"{scene.name} ({traj.name})", water,
                                  scenes.lift_deck(scene) if scene.lift else None)
        if "target" in scene.control:              # ship-to-ship: the load's moving aim
            from offshore_crane.simulation.compensation import compensated_motion

            comp = compensated_motion(robot, traj, scene.compensation,
                                      float(scene.control.get("delay", 0.0)),
                                      scenes.target_deck(scene), scene.gravity)
            motion = replace(motion, deck=comp.aim)
        return robot, motion
    if args.run_csv is not None:
        motion = mo.read_run(args.run_csv)
    else:
        motion = mo.from_trajectory(scenes.load_trajectory(scene, robot))
    return robot, replace(motion, water=water)


def parse_size(text: str) -> tuple[int, int]:
    """``"WxH"`` [pixels] as ``(W, H)``."""
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise InputError(f"--size {text}: give WIDTHxHEIGHT in pixels, e.g. 640x480",
                         name="--size") from None
    if not (16 <= w <= 8192 and 16 <= h <= 8192):
        raise InputError(f"--size {text}: width and height must lie in 16..8192 pixels",
                         name="--size")
    return w, h


def add_parser(sub) -> None:
    doc = __doc__.splitlines()
    p = sub.add_parser("animate", help="GIF or MP4 of the robot moving (headless)",
                       description=doc[0].split(": ", 1)[1] + " " + " ".join(
                           line.strip() for line in doc[2:6]))
    add_source_options(p)
    p.add_argument("--out", required=True, help="the animation: .gif (Pillow) or .mp4 "
                   "(imageio-ffmpeg)")
    p.add_argument("--fps", type=float, default=None, help="frames per second (default "
                   "10 for a GIF: exact in GIF's centiseconds, and small; 30 for an MP4)")
    p.add_argument("--speed", type=float, default=1.0, help="motion seconds per second of "
                   "the animation (default 1: real time)")
    p.add_argument("--color-by", choices=("force", "utilisation"),
                   help="colour the legs by their actuator force (blue pull, red push) or "
                   "by force / capacity (the robot description's actuators)")
    p.add_argument("--camera", metavar="AZ,EL[,DIST]", help="view from azimuth AZ and "
                   "elevation EL [deg] (default 35,25), at DIST [m] (default: fitted), "
                   "e.g. --camera -30,20")
    p.add_argument("--size", default=SIZE, metavar="WxH", help=f"picture size [pixels] "
                   f"(default {SIZE})")
    p.set_defaults(run=run)


def run(args) -> int:
    from offshore_crane.io import plan_outputs
    from offshore_crane.outputs.visual import animate as an
    from offshore_crane.outputs.visual import motion as mo
    from offshore_crane.outputs.visual.render import parse_camera

    for name, value in (("--fps", args.fps), ("--speed", args.speed)):
        if value is not None and (not value > 0 or value == float("inf")):
            raise InputError(f"{name} {value:g} must be a finite number > 0", name=name)
    width, height = parse_size(args.size)
    camera = parse_camera(args.camera)
    scene = scene_of(args)
    outputs = plan_outputs({"--out": args.out}, inputs_of(args, scene),
                           {"--out": an.FORMATS})
    target = outputs["--out"]
    fmt = an.output_format(args.out)
    robot, motion = load_motion(args, scene)
    if args.color_by is not None and motion.X is None:
        print(f"offshore-crane animate: computing the actuator forces for --color-by "
              f"({len(motion.t)} samples)")
    done = an.animate(robot, motion, target, fps=args.fps, speed=args.speed,
                      duration=args.duration, color_by=args.color_by, gravity=scene.gravity,
                      leg_model=scene.leg_model, width=width, height=height, camera=camera,
                      fmt=fmt, cable=scene.cable)
    say = print if target.kind != "stdout" else (lambda *a: None)
    say(f"offshore-crane animate: {motion.name}, {done.frames} frames {width} x {height} at "
        f"{done.fps:g} fps (speed {args.speed:g}), "
        f"t = {motion.t[0]:.2f}..{mo.frame_times(motion, done.fps, args.speed, args.duration)[-1]:.2f} s"
        + (f", legs by {args.color_by} (scale {done.scale:.4g}"
           f"{' N' if args.color_by == 'force' else ''})" if args.color_by else "")
        + f", {done.seconds:.1f} s")
    say(f"wrote {args.out}")
    return 0
