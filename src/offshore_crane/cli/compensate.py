"""``offshore-crane compensate``: a lift uncompensated, with the arm compensating, and with
the arm and the winch, side by side.

The scene's sea moves the platform; its ``[operation]`` is the crane's motion on a still
ship. The arm then holds the tip over the still-ship point and the winch holds the
payload's height (docs/cable.md) — or, with ``[control] target``, track a point on a
second vessel's deck in the same sea (ship-to-ship transfer) — acting on the platform's motion measured ``--delay``
seconds late (the scene's ``[control] delay``). Printed per mode: the payload's residual
motion (RMS and largest, per axis, base frame), the cable's largest angle, the tension
against m g, the worst actuator and the winch against their capacities, and the joints
that met their limits. Exit status 1 when an actuator or the winch exceeds a capacity.
"""

from __future__ import annotations


def add_parser(sub) -> None:
    from offshore_crane.cli.common import add_extremes_options, add_robot_options

    doc = __doc__.splitlines()
    p = sub.add_parser("compensate", help="compare uncompensated and motion-compensated "
                       "lifts", description=doc[0].split(": ", 1)[1])
    p.add_argument("--scene", required=True, metavar="TOML",
                   help="a sea scene with a payload on a cable ([payload] cable_length)")
    p.add_argument("--delay", type=float, metavar="S",
                   help="the measurement's delay [s] (default: the scene's [control] "
                   "delay, else 0)")
    p.add_argument("--plot", metavar="FIGURE", help="write the payload's residual motion "
                   "per mode to this figure (PNG, PDF, SVG)")
    add_extremes_options(p, "each mode's run")
    add_robot_options(p)
    p.set_defaults(run=run)


def run(args) -> int:
    from offshore_crane import scenes
    from offshore_crane.cli.common import extremes_scene, plan, robot_scene
    from offshore_crane.studies.compensation import compare_compensation, format_comparison

    scene = robot_scene(args, scenes.load_scene(args.scene))
    args.out = None
    outputs, say = plan(args, scene)
    target = outputs.get("--plot")
    from offshore_crane.errors import InputError

    if scene.trajectory != "sea":
        raise InputError(f"compensate cancels the ship's motion: {args.scene} has no sea "
                         f"(its trajectory is {scene.trajectory!r}); give a scene with "
                         "[trajectory] source = \"sea\"", name="--scene")
    scene = extremes_scene(args, scene)
    delay = args.delay if args.delay is not None else scene.control.get("delay", 0.0)
    if args.delay is not None:
        from offshore_crane.scenes.bounds import check_delay

        check_delay(scene, args.delay, "--delay")
    runs = compare_compensation(scene, delay=delay)
    run = runs[0].run
    say(f"offshore-crane compensate: {scene.name} ({args.scene}), {run.trajectory.name}, "
        f"{len(runs[0].residual)} samples judged, measurement delay {delay:g} s")
    if run.exposure is not None:
        say(f"records: {run.exposure.describe()}; each mode's figures are observed over "
            f"that one record (seed {scene.sea.get('seed', 0)}): `size` judges the extremes "
            "over seeds")
    if "target" in scene.control:
        deck_point = scene.control["target"]
        vessel = deck_point.get("vessel", scene.sea.get("vessel", "supply"))
        say(f"tracking a point on a second vessel's deck: point "
            f"({', '.join(f'{x:g}' for x in deck_point['point'])}) m full scale, seed "
            f"{deck_point['seed']}, {vessel}; "
            f"the residual is the payload's motion relative to that deck")
    say(format_comparison(runs))
    if target is not None:
        from offshore_crane.outputs.report import compensation_plot

        plan = run.exposure
        compensation_plot(target, runs, span=None if plan is None else plan.cycle,
                          title=f"{scene.name}: payload motion, delay {delay:g} s" + (
                              "" if plan is None else f" (first {plan.cycle:g} s of "
                              f"{plan.exposure / 3600:g} h full scale; RMS over all)"))
        say(f"wrote {args.plot}")
    over = [r.mode for r in runs if r.worst[0] > 1.0 or any(
        v > 1.0 for v in r.winch.values() if v == v)]
    if over:
        say(f"OVER CAPACITY in {', '.join(over)}")
    return 1 if over else 0
