"""``offshore-crane view``: the robot following a motion, in the browser.

Serves an interactive 3-D view (viser) with play / pause, a time slider and the playback
speed, on 127.0.0.1 (this machine only) unless ``--host`` says otherwise. The motion
comes from ``--scene``, ``--trajectory`` or ``--from`` as for ``animate``. Stop it with
Ctrl-C.
"""

from __future__ import annotations

from offshore_crane.errors import InputError


def add_parser(sub) -> None:
    from offshore_crane.cli.animate import add_source_options

    doc = __doc__.splitlines()
    p = sub.add_parser("view", help="interactive 3-D view in the browser (viser)",
                       description=doc[0].split(": ", 1)[1] + " " + " ".join(
                           line.strip() for line in doc[2:6]))
    add_source_options(p)
    p.add_argument("--port", type=int, default=8080, help="TCP port (default 8080; 0: any "
                   "free port)")
    p.add_argument("--host", default="127.0.0.1", help="address to listen on (default "
                   "127.0.0.1: this machine only; 0.0.0.0 opens it to the network)")
    p.add_argument("--speed", type=float, default=1.0, help="playback speed (default 1)")
    p.add_argument("--paused", action="store_true", help="start paused")
    p.add_argument("--color-by", choices=("force", "utilisation"),
                   help="colour the legs by their actuator force (blue pull, red push) or "
                   "by force / capacity, as animate does")
    p.set_defaults(run=run)


def run(args) -> int:
    import time

    from offshore_crane.outputs.visual import motion as mo
    from offshore_crane.outputs.visual.viewer import VIEW_RATE, Viewer, check_port
    from offshore_crane.cli.animate import load_motion, scene_of

    if not args.speed > 0 or args.speed == float("inf"):
        raise InputError(f"--speed {args.speed:g} must be a finite number > 0",
                         name="--speed")
    check_port(args.host, args.port)                 # before any computation
    scene = scene_of(args)
    robot, motion = load_motion(args, scene)
    motion = mo.hanging_load(robot, motion, scene.gravity, scene.cable)
    if args.color_by is not None:
        motion = mo.forces(robot, motion, scene.gravity, scene.leg_model)
    shown = mo.at(motion, mo.frame_times(motion, VIEW_RATE, 1.0, args.duration))
    viewer = Viewer(robot, shown, host=args.host, port=args.port, speed=args.speed,
                    play=not args.paused, title=f"offshore-crane: {motion.name}",
                    color_by=args.color_by)
    print(f"offshore-crane view: {motion.name}, t = {shown.t[0]:.2f}..{shown.t[-1]:.2f} s, "
          f"{len(shown.t)} frames; open {viewer.url} (Ctrl-C stops)", flush=True)
    try:
        while True:
            time.sleep(3600)
    finally:
        viewer.close()
