"""``offshore-crane excite``: an excitation trajectory for identifying a built platform.

A finite Fourier series in the nine coordinates, its amplitudes optimised for the
condition number of the base regressor (docs/identification.md) inside the workspace and
the actuators' speed and force capacities; written as a trajectory CSV with its analytic
rates and accelerations (``t_s, q1..q9, qd1..qd9, qdd1..qdd9``), which the other commands
read as ``--trajectory FILE.csv``. Printed: its condition number beside Table 1's.
"""

from __future__ import annotations

from offshore_crane.errors import InputError


def add_parser(sub) -> None:
    from offshore_crane.cli.common import add_robot_options

    doc = __doc__.splitlines()
    p = sub.add_parser("excite", help="an optimised excitation trajectory (identification)",
                       description=doc[0].split(": ", 1)[1])
    p.add_argument("--duration", type=float, required=True, metavar="S",
                   help="length of the excitation [s]")
    p.add_argument("--out", required=True, metavar="FILE.csv",
                   help="the trajectory CSV to write")
    p.add_argument("--rate", type=float, default=100.0, metavar="HZ",
                   help="samples per second (default 100)")
    p.add_argument("--harmonics", type=int, default=10, metavar="H",
                   help="harmonics of the Fourier series (default 10)")
    p.add_argument("--period", type=float, default=10.0, metavar="S",
                   help="its fundamental period [s] (default 10)")
    p.add_argument("--seeds", type=int, default=4, metavar="N",
                   help="random coefficient sets tried before the optimisation (default 4)")
    p.add_argument("--iterations", type=int, default=60, metavar="N",
                   help="cost evaluations of the amplitude optimisation (default 60)")
    add_robot_options(p)
    p.set_defaults(run=run)


def run(args) -> int:
    import math

    import numpy as np

    from offshore_crane import scenes
    from offshore_crane.cli.common import robot_scene
    from offshore_crane.io import plan_outputs, write_csv
    from offshore_crane.errors import WorkspaceError
    from offshore_crane.motion.trajectories import load, time_grid
    from offshore_crane.motion.trajectories.files import CSV_COLUMNS_DERIVATIVES
    from offshore_crane.studies import identification as ident

    for name, value, low in (("--duration", args.duration, 0.0), ("--rate", args.rate, 0.0),
                             ("--period", args.period, 0.0)):
        if not (value > low and value < float("inf")):
            raise InputError(f"{name} {value:g}: give a finite number > 0", name=name)
    for name, value in (("--harmonics", args.harmonics), ("--seeds", args.seeds),
                        ("--iterations", args.iterations)):
        if value < 1:
            raise InputError(f"{name} {value}: give an integer >= 1", name=name)
    scene = robot_scene(args, scenes.Scene())
    target = plan_outputs({"--out": args.out}, scene.inputs())["--out"]
    robot = scenes.load_robot(scene)
    base = ident.base_parameters(robot)
    _enough(args, len(time_grid(args.duration, args.rate)), base.rank,
            len(ident.actuator_rows(robot)))
    traj, cond = ident.optimise_excitation(
        robot, base, args.duration, args.rate, args.harmonics, args.period,
        seeds=range(args.seeds), iterations=args.iterations, gravity=scene.gravity)
    if not math.isfinite(cond):
        raise InputError(f"--duration {args.duration:g}: the excitation's base regressor is "
                         f"rank-deficient (it excites {ident.excited(robot, traj, base)} of "
                         f"the {base.rank} base parameters): lengthen --duration (e.g. one "
                         f"--period, {args.period:g} s)", name="--duration")
    try:
        reference = ident.excitation_condition(robot, load("table1"), base)
        against = f"Table 1: {reference:.4g}, {reference / cond:.3g}× larger"
    except WorkspaceError:
        against = "Table 1 leaves this robot's workspace: no comparison"
    write_csv(target, ",".join(CSV_COLUMNS_DERIVATIVES),
              np.column_stack([traj.t, traj.q, traj.qd, traj.qdd]))
    print(f"offshore-crane excite: {traj.name}, {len(traj.t)} samples at {args.rate:g} Hz; "
          f"base regressor ({base.rank} parameters) condition number {cond:.4g} "
          f"({against}); inside the workspace and the actuators' speed and force capacities")
    print(f"wrote {args.out}")
    return 0


def _enough(args, samples: int, rank: int, rows: int) -> None:
    """Refuse, before optimising, an excitation with no more equations (samples × the
    robot's actuators) than base parameters: no excitation that short determines them."""
    if samples * rows <= rank:
        need = (rank // rows) / args.rate               # rank // rows + 1 samples
        raise InputError(f"--duration {args.duration:g} at {args.rate:g} Hz: {samples} "
                         f"samples, {samples * rows} equations for the {rank} base "
                         f"parameters: give --duration ≥ {need:g} s (one --period, "
                         f"{args.period:g} s, excites them well)", name="--duration")
