"""``offshore-crane motion``: the robot's motion from a ship in a sea state.

Writes the model-scale record ``t_s,q1..q9`` with its analytic rates and accelerations
``qd1..qd9,qdd1..qdd9`` (``id --trajectory`` uses them instead of differencing). The sea
is the scene's ``[sea]`` (``--scene``) with the flags on top; the record is checked
against the robot's workspace, and an error states the smallest Froude scale that fits.
"""

from __future__ import annotations

from offshore_crane.conventions import COORDINATES, COORDINATE_UNITS


def add_parser(sub) -> None:
    from offshore_crane.conventions import SPECTRA
    from offshore_crane.cli.common import add_robot_options

    doc = __doc__.splitlines()
    p = sub.add_parser("motion", help="platform and crane motion from a sea state",
                       description=doc[0].split(": ", 1)[1] + " " + " ".join(
                           line.strip() for line in doc[2:6]))
    p.add_argument("--scene", metavar="FILE.toml", help="scene whose [sea], [operation], "
                   "[trajectory] duration and rate and robot set the defaults")
    p.add_argument("--hs", type=float, metavar="M", help="significant wave height [m], "
                   "full scale")
    p.add_argument("--tp", type=float, metavar="S", help="peak period [s], full scale")
    p.add_argument("--heading", type=float, metavar="DEG",
                   help="wave heading [deg]: 180 head seas, 90 waves from starboard")
    p.add_argument("--scale", type=float, metavar="LAMBDA",
                   help="Froude scale: full-scale length / model length")
    p.add_argument("--vessel", metavar="NAME|PATH", help="shipped vessel (default supply) "
                   "or an RAO CSV (docs/sea.md)")
    p.add_argument("--kind", choices=SPECTRA, help="wave spectrum (default jonswap)")
    p.add_argument("--gamma", type=float, help="JONSWAP peak enhancement (default: "
                   "DNV-RP-C205's from Tp/sqrt(Hs))")
    p.add_argument("--spreading", type=float, metavar="S", help="cos-2s spreading exponent "
                   "(short-crested seas; default long-crested)")
    p.add_argument("--seed", type=int, help="random phases (default 0)")
    p.add_argument("--point", type=float, nargs=3, metavar=("X", "Y", "Z"),
                   help="the crane's base on the vessel [m], full scale, from the RAO "
                   "table's reference point")
    p.add_argument("--highpass", type=float, metavar="RAD_S", help="drop wave components "
                   "below this frequency [rad/s], full scale (slow drift, yaw)")
    p.add_argument("--duration", type=float, metavar="S", help="model-scale record [s] "
                   "(default 60)")
    p.add_argument("--rate", type=float, metavar="HZ", help="sampling rate [Hz] "
                   "(default 100)")
    p.add_argument("--no-derivatives", action="store_true",
                   help="write t_s,q1..q9 only (id then differences them)")
    add_robot_options(p)
    p.add_argument("--out", help="write the record to this CSV ('-': standard output)")
    p.add_argument("--plot", help="write the coordinates and the spectra to this figure")
    p.set_defaults(run=run)


def _scene(args):
    """The scene's sea (``--scene``, or none) with the flags on top, as a ``source =
    "sea"`` scene, its robot with ``--robot`` and ``--set``."""
    from dataclasses import replace

    from offshore_crane import scenes
    from offshore_crane.cli.common import robot_scene

    scene = scenes.load_scene(args.scene) if args.scene else scenes.Scene()
    sea = dict(scene.sea)
    flags = {"hs": args.hs, "tp": args.tp, "heading": args.heading, "scale": args.scale,
             "vessel": args.vessel, "kind": args.kind, "gamma": args.gamma,
             "spreading": args.spreading, "seed": args.seed, "highpass": args.highpass,
             "point": None if args.point is None else tuple(args.point)}
    sea.update({k: v for k, v in flags.items() if v is not None})
    missing = [k for k in ("hs", "tp", "heading", "scale") if k not in sea]
    if missing:                          # in the words of the command line, not a scene's
        from offshore_crane.errors import InputError

        raise InputError(f"a sea state needs {' '.join('--' + k for k in missing)} "
                         "(full scale) or a --scene with a [sea], e.g. motion --hs 2.5 "
                         "--tp 8 --heading 90 --scale 20", name="--" + missing[0])
    where = f"{args.scene} with the command-line options" if args.scene else "command line"
    changes = dict(trajectory="sea", sea=sea, duration=args.duration, rate=args.rate)
    if scene.trajectory == "sea":        # keep the scene's record unless the flags say
        changes = {k: v for k, v in changes.items() if v is not None}
    scene = replace(scene, origin=where, **changes)   # table1's span does not carry over
    return robot_scene(args, scene)


def _statistics(q, arm: bool) -> str:
    """Mean, standard deviation, min and max of each coordinate (q7..q9 with an
    operation only)."""
    import numpy as np

    n = 9 if arm else 6
    lines = [f"{'coordinate':<11}{'unit':<5}{'mean':>12}{'std':>12}{'min':>12}{'max':>12}"]
    for k in range(n):
        x = q[:, k]
        lines.append(f"{COORDINATES[k]:<11}{COORDINATE_UNITS[k]:<5}{x.mean():>12.5g}"
                     f"{x.std():>12.5g}{x.min():>12.5g}{x.max():>12.5g}")
    return "\n".join(lines)


def run(args) -> int:
    import sys

    import numpy as np

    from offshore_crane import scenes
    from offshore_crane.motion import trajectories
    from offshore_crane.io import FIGURE_FORMATS, plan_outputs

    scene = _scene(args)
    outputs = plan_outputs({"--out": args.out, "--plot": args.plot},
                           [args.scene, *scene.inputs()], {"--plot": FIGURE_FORMATS})
    to_stdout = any(o.kind == "stdout" for o in outputs.values())

    def say(*a):
        print(*a, file=sys.stderr if to_stdout else sys.stdout)

    robot = scenes.load_robot(scene)
    traj = scenes.load_trajectory(scene, robot)
    motion = traj.source
    ship, t = motion.ship, traj.t
    sea = ship.sea
    gamma = "" if sea["gamma"] is None else f", gamma {sea['gamma']:.3g}"
    say(f"offshore-crane motion: {traj.name}, {len(t)} samples, t = {t[0]:.2f}..{t[-1]:.2f} s "
        f"at {motion.rate:g} Hz (full scale {t[-1] * np.sqrt(motion.scale):.1f} s, "
        f"{ship.harmonics.size} wave components, no repetition for "
        f"{ship.repetition_period:.1f} s full scale)")
    vessel = scene.sea.get("vessel", "supply")
    say(f"vessel {vessel}, {sea['kind']}{gamma}, seed {sea['seed']}; every sample inside "
        "the workspace")
    say(_statistics(traj.q, motion.operation is not None))
    if "--out" in outputs:
        if args.no_derivatives:
            trajectories.write_csv(outputs["--out"], t, traj.q)
        else:
            trajectories.write_csv(outputs["--out"], t, traj.q, traj.qd, traj.qdd)
        say(f"wrote {args.out}")
    if "--plot" in outputs:
        from offshore_crane.outputs.plots import sea_motion_figure

        sea_motion_figure(outputs["--plot"], scene, traj)
        say(f"wrote {args.plot}")
    return 0
