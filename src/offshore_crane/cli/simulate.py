"""``offshore-crane simulate``: the robot under a controller, tracking a reference motion.

The scene (``--scene``) sets the robot, the trajectory and the ``[control]`` section;
explicit flags override them. The CSV holds ``t_s``, ``q1..q9``, ``q1_ref..q9_ref`` and the
applied actuator forces; on an early stop (workspace, singularity, divergence) it holds
every sample computed up to the stop, and the command exits with status 2 and one line.
"""

from __future__ import annotations

from offshore_crane.conventions import (ACTUATOR_UNITS, ACTUATORS, COORDINATE_UNITS, COORDINATES,
                                        Q_COLUMNS, coordinate_column)
from offshore_crane.errors import InputError

CSV_HEADER = ",".join(["t_s", *Q_COLUMNS, *(coordinate_column(k, tag="_ref") for k in range(9)),
                       *(f"{a}_{u.replace('·', '')}" for a, u in zip(ACTUATORS,
                                                                       ACTUATOR_UNITS))])
#: Columns added on an elastic cable: the payload (base frame), the tension, the length.
ELASTIC_COLUMNS = "payload_x_m,payload_y_m,payload_z_m,tension_N,L_m"


def add_parser(sub) -> None:
    from offshore_crane.simulation.control import LAWS
    from offshore_crane.cli.common import add_robot_options

    p = sub.add_parser("simulate", help="simulate the robot under a controller",
                       description=__doc__.splitlines()[0].split(": ", 1)[1] + " "
                       + " ".join(line.strip() for line in __doc__.splitlines()[2:6]))
    p.add_argument("--scene", metavar="FILE.toml", help="scene file (robot, trajectory, "
                   "[control])")
    p.add_argument("--trajectory", help="reference: 'table1' or a CSV t_s,q1..q9 "
                   "(interpolated between samples)")
    p.add_argument("--controller", metavar="LAW", help="control law, one of "
                   f"{', '.join(LAWS)} (default computed-torque)")
    p.add_argument("--kp", type=float, nargs="+", metavar="KP",
                   help="stiffness gains: one value or 9 (per coordinate for computed "
                   "torque [1/s²]; per actuator for PD [N·m/rad, N/m])")
    p.add_argument("--kd", type=float, nargs="+", metavar="KD", help="damping gains (as --kp)")
    p.add_argument("--ki", type=float, nargs="+", metavar="KI", help="integral gains of the "
                   "pid law, one value or 9 per actuator [N·m/(rad·s), N/(m·s)]")
    p.add_argument("--control-rate", type=float, metavar="HZ",
                   help="control rate with sample-and-hold (default: continuous, the law at "
                   "every integrator stage)")
    p.add_argument("--step", type=float, metavar="S", help="integration step [s] "
                   "(default 0.001)")
    p.add_argument("--duration", type=float, metavar="S", help="simulated time [s] "
                   "(default: the trajectory's span, 10π s for table1)")
    p.add_argument("--rate", type=float, metavar="HZ", help="output sampling rate [Hz] "
                   "(default: every step)")
    p.add_argument("--integrator", choices=("rk4", "dop853"), help="default rk4")
    p.add_argument("--initial-error", type=float, nargs=9, metavar="DQ",
                   help="initial state minus the reference's, q1..q9 [m, rad]")
    p.add_argument("--initial-sway", type=float, nargs=2, metavar=("PHI1", "PHI2"),
                   help="with a payload on a cable: the sway at the start [rad] (default "
                   "the scene's [cable] initial, else 0 0)")
    p.add_argument("--anti-sway", type=float, metavar="ZETA",
                   help="with a payload on a cable: damping ratio the anti-sway law adds "
                   "to the swing (computed torque; docs/cable.md)")
    add_robot_options(p)
    p.add_argument("--gravity", type=float, nargs=3, metavar=("GX", "GY", "GZ"))
    p.add_argument("--no-limits", action="store_true", help="do not stop at the workspace "
                   "limits")
    p.add_argument("--no-saturation", action="store_true", help="apply the commanded forces "
                   "unclipped (default: clipped to the actuators' capacities of the robot "
                   "description and [actuators], push and pull apart)")
    p.add_argument("--out", help="write the run to this CSV")
    p.add_argument("--plot", help="write tracking errors and forces to this figure")
    p.set_defaults(run=run)


def _gains(values, name):
    if values is None:
        return None
    if len(values) not in (1, 9):
        raise InputError(f"{name} takes one value or 9, got {len(values)}", name=name)
    return values[0] if len(values) == 1 else values


def run(args) -> int:
    from dataclasses import replace

    import numpy as np

    from offshore_crane import scenes
    from offshore_crane.errors import SimulationError
    from offshore_crane.simulation.rigid import simulate
    from offshore_crane.cli.common import plan, robot_scene

    scene = robot_scene(args, scenes.load_scene(args.scene) if args.scene else scenes.Scene())
    scene = scenes.with_trajectory(scene, "command line", args.trajectory)
    if args.gravity is not None:
        scene = scenes.with_overrides(scene, "command line", gravity=tuple(args.gravity))
    outputs, say = plan(args, scene)
    robot = scenes.load_robot(scene)
    traj = scenes.load_trajectory(scene, robot)
    controller = scenes.controller(scene, robot)
    flags = {"law": args.controller, "kp": _gains(args.kp, "--kp"),
             "kd": _gains(args.kd, "--kd"), "ki": _gains(args.ki, "--ki"),
             "rate": args.control_rate}
    flags = {k: v for k, v in flags.items() if v is not None}
    if args.no_saturation:
        flags.update(saturation=False, lower=None, upper=None)
    if args.anti_sway is not None:
        flags["anti_sway"] = args.anti_sway
    on_line = ("arm-compensation", "arm-winch-compensation")
    if flags.get("law") in on_line and "target" in scene.control:
        flags["target"] = scenes.target_deck(scene)        # the law's moving aim
    if flags:
        controller = replace(controller, _arrays={}, **flags)
    if controller.law_name in on_line and scene.compensation != "none":
        raise InputError(f"--controller {controller.law_name} solves the arm on line, but the "
                         f"scene's [control] compensation = \"{scene.compensation}\" "
                         "already commands it: drop one of them", name="--controller")
    extras = scenes.instruments(scene)
    c = scene.control
    traj, elastic, swing = scenes.plant_options(scene, robot, traj)
    if elastic is not None and args.initial_sway is not None:
        raise InputError("--initial-sway: the sway angles of a rigid cable; on an elastic "
                         "one the payload starts hanging at its static stretch",
                         name="--initial-sway")
    step = args.step if args.step is not None else c.get("step", 1e-3)
    span = float(traj.t[-1] - traj.t[0])
    duration = args.duration if args.duration is not None else span
    if duration > span + 1e-9:
        raise InputError(f"--duration {duration:g} s is longer than the trajectory "
                         f"({span:g} s)", name="--duration")
    # the reference's state at the start, which the run takes by itself (and a law may
    # move: arm-compensation starts the arm on its aim) unless an initial error shifts it
    q0 = qd0 = None
    error = args.initial_error if args.initial_error is not None else c.get("initial_error")
    if error is not None:
        q0, qd0, _ = (x[0].copy() for x in traj.reference(traj.t[:1]))
        q0 += np.asarray(error, dtype=float)
    if args.initial_sway is not None and robot.hybrid.cable is None:
        raise InputError("--initial-sway: applies to a payload on a cable; set "
                         "payload.cable_length > 0 (--set, or the scene's [payload])",
                         name="--initial-sway")
    if args.initial_sway is not None:
        swing["initial"] = tuple(args.initial_sway)
    stopped = None
    try:
        if elastic is not None:
            from offshore_crane.simulation.elastic import simulate_elastic

            res = simulate_elastic(robot, duration, traj.reference, q0=q0, qd0=qd0,
                                   controller=controller, gravity=scene.gravity, step=step,
                                   rate=args.rate, limits=not args.no_limits,
                                   t0=float(traj.t[0]), **elastic, **extras)
        else:
            res = simulate(robot, duration, traj.reference, q0=q0, qd0=qd0,
                           controller=controller, gravity=scene.gravity, step=step,
                           rate=args.rate,
                           integrator=args.integrator or c.get("integrator", "rk4"),
                           limits=not args.no_limits, t0=float(traj.t[0]), **swing,
                           **extras)
    except SimulationError as exc:
        res, stopped = exc.result, exc
        if res is None or len(res) == 0:         # nothing to report, write or plot
            raise
    say(f"offshore-crane simulate: {controller.law} control"
        + (f" at {controller.rate:g} Hz (sample-and-hold)" if controller.rate else
           " (continuous)") + f", {res.integrator} step {step:g} s, reference {traj.name}, "
        f"{len(res)} samples, t = {res.t[0]:.2f}..{res.t[-1]:.2f} s")
    say(summary(res, controller))
    if "--out" in outputs:
        from offshore_crane.io import write_csv
        from offshore_crane.outputs.report import CABLE_COLUMNS

        if "payload" in res.info:                      # the elastic cable
            winch = ([res.info["length_rate"], res.info["winch_force"]]
                     if "winch_force" in res.info else [])    # a commanded winch
            write_csv(outputs["--out"], f"{CSV_HEADER},{ELASTIC_COLUMNS}"
                      + (",Ld_m_s,Fw_N" if winch else ""),
                      np.column_stack([res.t, res.q, res.q_ref, res.X, res.info["payload"],
                                       res.tension, res.info["length"], *winch]))
        elif res.sway is None:
            write_csv(outputs["--out"], CSV_HEADER,
                      np.column_stack([res.t, res.q, res.q_ref, res.X]))
        elif "length" in res.info:                     # a rigid cable on a winch
            write_csv(outputs["--out"], f"{CSV_HEADER},{CABLE_COLUMNS},L_m",
                      np.column_stack([res.t, res.q, res.q_ref, res.X, res.sway, res.tension,
                                       res.info["length"]]))
        else:
            write_csv(outputs["--out"], f"{CSV_HEADER},{CABLE_COLUMNS}",
                      np.column_stack([res.t, res.q, res.q_ref, res.X, res.sway, res.tension]))
        say(f"wrote {args.out}" + (f" ({len(res)} samples, up to the stop)" if stopped else ""))
    if "--plot" in outputs:
        from offshore_crane.outputs.plots import simulation_figure

        simulation_figure(outputs["--plot"], res, title=f"offshore-crane simulate: {traj.name}, "
                          f"{controller.law}")
        say(f"wrote {args.plot}")
    if stopped is not None:
        raise stopped
    return 0


def summary(res, controller=None) -> str:
    """RMS and max tracking error per coordinate, peak forces, time saturated; with an
    anti-sway law, the platform's departure from its reference is its own command, and
    the table says so."""
    import numpy as np

    e = res.error
    damping = controller is not None and getattr(controller, "anti_sway", None) is not None
    head, peak = ("RMS departure", "max |depart.|") if damping else ("RMS error",
                                                                      "max |error|")
    w1, w2 = (14, 15) if damping else (12, 13)          # column widths
    lines = [f"{'coord':<6}{'unit':<5}{head:>{w1}}{peak:>{w2}}"]
    if damping:
        lines = [f"anti-sway (zeta = {controller.anti_sway:g}): the law moves the platform "
                 "on purpose to damp the swing, so q1..q6 depart from the reference by its "
                 "command, not by a tracking error", *lines]
    for j, (name, unit) in enumerate(zip(COORDINATES, COORDINATE_UNITS)):
        col = e[:, j]
        if np.isnan(col).all():
            continue
        lines.append(f"{name:<6}{unit:<5}{np.sqrt(np.mean(col ** 2)):>{w1}.3e}"
                     f"{np.abs(col).max():>{w2}.3e}")
    dt = np.diff(res.t).mean() if len(res.t) > 1 else 0.0
    lines.append(f"{'actuator':<9}{'unit':<5}{'peak |X|':>11}{'saturated [s]':>15}")
    for k, (name, unit) in enumerate(zip(ACTUATORS, ACTUATOR_UNITS)):
        lines.append(f"{name:<9}{unit:<5}{np.abs(res.X[:, k]).max():>11.2f}"
                     f"{res.saturated[:, k].sum() * dt:>15.3f}")
    if "payload" in res.info and len(res.t):
        T = res.tension
        slack = float(np.diff(res.t)[~(T[:-1] > 0.0)].sum()) if len(T) > 1 else 0.0
        lines.append(f"payload on an elastic cable: tension {T.min():.4g}..{T.max():.4g} N, "
                     f"slack for {slack:.3g} s; cable length "
                     f"{res.info['length'].min():.4g}..{res.info['length'].max():.4g} m "
                     f"(axial period {1e3 * res.info['axial_period']:.3g} ms)")
        if "winch_force" in res.info:
            F = res.info["winch_force"]
            lines.append(f"commanded winch: line pull {F.min():.4g}..{F.max():.4g} N, "
                         f"saturated {res.info['winch_saturated'].sum() * dt:.3f} s")
    if res.sway is not None and len(res.t):
        angle = np.arccos(np.clip(np.cos(res.sway[:, 0]) * np.cos(res.sway[:, 1]), -1, 1))
        k = int(np.argmax(angle))
        late = angle[res.t >= res.t[-1] - 1.0].max()
        lines.append(f"hanging load: max sway {np.degrees(angle[k]):.4g}° at t = "
                     f"{res.t[k]:.2f} s, {np.degrees(late):.4g}° over the last second; "
                     "cable tension "
                     f"{np.nanmin(res.tension):.4g}..{np.nanmax(res.tension):.4g} N")
    return "\n".join(lines)
