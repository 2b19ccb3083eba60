"""``offshore-crane show``: a picture of the robot at one pose, its frames labelled.

The pose is q1..q9 (``--pose``, comma-separated, [m, rad]; default the home pose with the
arm at zero). The main frames are drawn as axis triads (x red, y green, z blue) with
their URDF names, and the legs are numbered.
"""

from __future__ import annotations


def add_parser(sub) -> None:
    from offshore_crane.cli.common import add_robot_options

    doc = __doc__.splitlines()
    p = sub.add_parser("show", help="a still picture of one pose, frames labelled",
                       description=doc[0].split(": ", 1)[1] + " " + " ".join(
                           line.strip() for line in doc[2:5]))
    p.add_argument("--pose", metavar="Q1,...,Q9", help="q1..q9 [m, rad], comma-separated "
                   "(inside the workspace, as export --pose)")
    p.add_argument("--sway", metavar="PHI1,PHI2", help="sway angles [rad] of a hanging "
                   "load (default 0,0)")
    add_robot_options(p)
    p.add_argument("--scene", metavar="FILE.toml", help="scene whose robot is drawn")
    p.add_argument("--camera", metavar="AZ,EL[,DIST]", help="view from azimuth AZ and "
                   "elevation EL [deg] (default 35,25), at DIST [m] (default: fitted)")
    p.add_argument("--size", default="800x600", metavar="WxH", help="picture size "
                   "[pixels] (default 800x600)")
    p.add_argument("--no-labels", action="store_true", help="leave the frames unlabelled")
    p.add_argument("--out", required=True, help="the picture (.png, .jpg, .webp, ...)")
    p.set_defaults(run=run)


#: Picture types Pillow writes, by suffix.
STILL_FORMATS = ("png", "jpg", "jpeg", "webp", "bmp", "tif", "tiff", "gif")


def run(args) -> int:
    import numpy as np

    from offshore_crane import scenes
    from offshore_crane.io import plan_outputs
    from offshore_crane.outputs.visual.animate import still
    from offshore_crane.outputs.visual.poses import has_cable
    from offshore_crane.outputs.visual.render import parse_camera
    from offshore_crane.cli.common import comma_numbers, robot_scene
    from offshore_crane.cli.animate import parse_size

    width, height = parse_size(args.size)
    camera = parse_camera(args.camera)
    scene = robot_scene(args, scenes.load_scene(args.scene) if args.scene else scenes.Scene())
    outputs = plan_outputs({"--out": args.out}, [args.scene, *scene.inputs()],
                           {"--out": STILL_FORMATS})
    q = None if args.pose is None else comma_numbers(args.pose, 9, "--pose")
    robot = scenes.load_robot(scene)
    if q is None:
        q = [0.0, 0.0, robot.home_height or 0.0] + [0.0] * 6
    else:                               # as export --pose: no picture of a broken robot
        from offshore_crane.robot.kinematics import check_workspace

        check_workspace(robot, np.array(q), pose="--pose")
    sway = None
    if has_cable(robot.description) or args.sway is not None:
        sway = np.array(comma_numbers(args.sway or "0,0", 2, "--sway"))
    still(robot, np.array(q), outputs["--out"], width=width, height=height, camera=camera,
          sway=sway, labels=not args.no_labels)
    print(f"wrote {args.out}")
    return 0
