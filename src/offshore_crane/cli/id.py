"""``offshore-crane id``: inverse dynamics along a trajectory or a scene."""

from __future__ import annotations

from offshore_crane.conventions import ACTUATOR_UNITS, ACTUATORS, AGREEMENT_RTOL, NUMBA_MIN
from offshore_crane.cli.common import add_robot_options

RELATIVE_LIMIT = AGREEMENT_RTOL


def add_parser(sub) -> None:
    p = sub.add_parser("id", help="inverse dynamics along a trajectory",
                       description="Actuator forces of the hybrid crane along a trajectory. "
                       "With --scene, the scene file sets the defaults of --trajectory, "
                       "--duration, --rate, --fd-order, --method, --leg-model, --outputs, "
                       "--gravity and the robot (--set is applied on top); flags given "
                       "explicitly override the scene.")
    add_options(p)
    p.add_argument("--compare-fidelity", action="store_true",
                   help="also run every leg model (kane) and print its run time and "
                   "largest deviation from 'full' per actuator")
    p.set_defaults(run=run)


def add_options(p, plot_help: str = "write a figure like the paper's Fig. 3 (PNG, PDF, "
                "SVG)") -> None:
    """The flags of ``id`` (scene, trajectory, method, robot, checks, --out, --plot),
    shared with ``size``."""
    p.add_argument("--scene", metavar="FILE.toml",
                   help="scene file: sub-systems, leg model, payload, gravity, trajectory, "
                   "outputs, methods (see scenes/)")
    p.add_argument("--trajectory",
                   help="'table1' (paper Table 1, analytic derivatives; default) or a CSV "
                   "t_s,q1..q9")
    p.add_argument("--backend", choices=("numpy", "numba", "auto"),
                   help="kernels: numpy (starts fastest), numba (compiled: ~2x faster a "
                   f"sample, ~1.2 s to load) or auto; default: numpy below {NUMBA_MIN:,} "
                   "samples, numba from there")
    p.add_argument("--threads", type=int, default=1,
                   help="threads for the compiled kernels and a sea record's FFT and "
                   "workspace check (large trajectories; results bit-identical to 1 thread)")
    p.add_argument("--method", choices=("kane", "kane-explicit", "rnea", "both"),
                   help="default kane; 'both' runs kane and rnea and compares them")
    p.add_argument("--leg-model", choices=("full", "thin-rod", "massless"),
                   help="leg model (default full); thin-rod and massless are approximations "
                   "(kane only)")
    p.add_argument("--outputs", help="comma-separated actuators to compute, e.g. T1,T2,Fs "
                   "(without any Fl the legs are not evaluated)")
    p.add_argument("--duration", type=float, help="span of table1 [s] (default 10π)")
    p.add_argument("--rate", type=float, help="sampling rate of table1 [Hz] (default 100)")
    p.add_argument("--fd-order", type=int, choices=(2, 4, 6),
                   help="order of the central differences for a CSV trajectory (default 4)")
    p.add_argument("--out", help="write the actuator forces to this CSV")
    p.add_argument("--plot", help=plot_help)
    add_robot_options(p)
    p.add_argument("--gravity", type=float, nargs=3, metavar=("GX", "GY", "GZ"),
                   help="gravity in the base frame [m/s²] (default 0 0 -9.81)")
    p.add_argument("--no-limits", action="store_true",
                   help="do not stop at leg strokes, U-joint or arm joint limits")
    p.add_argument("--warn-cond", type=float, default=1e5,
                   help="warn above this condition number (default 1e5)")
    p.add_argument("--error-cond", type=float, default=1e8,
                   help="stop above this condition number (default 1e8)")
    p.add_argument("--initial-sway", type=float, nargs=2, metavar=("PHI1", "PHI2"),
                   help="with a payload on a cable (--set payload.cable_length=L): the sway "
                   "angles at the start [rad] (arm_tip frame; default the scene's [cable], "
                   "else 0 0)")
    p.add_argument("--slack", choices=("error", "warn"),
                   help="a slack cable (tension <= 0): stop with an error (default) or warn "
                   "and mark the samples")
    p.add_argument("--substeps", type=int, help="RK4 steps of the swing per sample interval "
                   "(default 1)")


_METHOD_LABELS = {"kane": "Kane", "kane-explicit": "Kane (explicit)", "rnea": "RNEA"}
#: With a payload on a cable, "rnea" runs the swing's Pinocchio reference.


def run(args) -> int:
    import numpy as np

    from offshore_crane import scenes
    from offshore_crane.outputs.report import format_summary, plot, summary_rows, write_csv
    from offshore_crane.cli.common import id_scene, plan, thresholds

    scene = id_scene(args)
    outputs, say = plan(args, scene)
    robot = scenes.load_robot(scene)
    limits = not args.no_limits           # the dynamics check a sea record's workspace
    traj = scenes.load_trajectory(scene, robot, threads=args.threads, check=not limits)
    from offshore_crane.dynamics import quick_backend
    from offshore_crane.errors import WorkspaceError

    backend = args.backend or quick_backend(len(traj.t))
    options = dict(limits=limits, thresholds=thresholds(args), backend=backend,
                   threads=args.threads)
    try:
        done = scenes.run(scene, robot, traj, **options)
    except WorkspaceError:
        scenes.sea_workspace_error(robot, traj, args.threads)   # names the scale that fits
        raise
    res, t = done.result, traj.t
    X = res.X
    cable = res.cable
    if args.scene:
        say(f"scene {scene.name} ({args.scene}): {scene.describe()}")
    elif args.robot or args.set:
        say(f"robot {robot.spec.name if robot.spec else 'urdf'}"
            f"{', --set ' + ' '.join(args.set) if args.set else ''}: {scene.describe()}")
    say(f"offshore-crane id: trajectory {traj.name}, {len(t)} samples, "
        f"t = {t[0]:.2f}..{t[-1]:.2f} s, method "
        f"{'both' if scene.methods == ('kane', 'rnea') else ' + '.join(scene.methods)} "
        f"({', '.join(f'{m} {s * 1e3:.1f} ms' for m, s in done.seconds.items())}"
        f"{_kernel_time(done)})")
    say(f"model: {'exact' if not res.approximations else 'APPROXIMATE: ' + '; '.join(res.approximations)}"
        + (f"; skipped: {'; '.join(res.pruned)}" if res.pruned else ""))
    cols = [k for k, name in enumerate(ACTUATORS) if name in res.outputs]
    table, names = X[:, cols], [ACTUATORS[k] for k in cols]
    units = [ACTUATOR_UNITS[k] for k in cols]
    if cable is not None and cable.hoist is not None:      # the winch: a tenth actuator
        table = np.column_stack([table, cable.tension])
        names, units = names + ["Fw"], units + ["N"]
    say(format_summary(summary_rows(t, table, names, units)))
    for kind, kappa, k in res.worst():
        say(f"worst {kind} condition number: {kappa:.4g} at t = {t[k]:.2f} s (sample {k})")
    if cable is not None:
        from offshore_crane.outputs.report import cable_summary

        say(cable_summary(cable, robot))
    status = 0
    first = _METHOD_LABELS[scene.methods[0]]
    for m, diff, scale, rel, i, j in scenes.compare_methods(done):
        ok = rel <= RELATIVE_LIMIT
        say(f"{first} vs {_METHOD_LABELS[m]}: max |ΔX| = {diff:.3e} (sample {i}, "
            f"t = {t[i]:.2f} s, {ACTUATORS[j]}); relative to max |X| = {scale:.4g}: "
            f"{rel:.3e} "
            f"({'OK' if ok else 'FAIL'}, limit {RELATIVE_LIMIT:g})")
        status = status if ok else 1
        other = done.results[m].cable
        if cable is not None and other is not None and hasattr(cable, "sway"):
            say(f"{first} vs {_METHOD_LABELS[m]}: max |Δsway| = "
                f"{np.abs(other.sway - cable.sway).max():.3e} rad, max |Δtension| = "
                f"{np.abs(other.tension - cable.tension).max():.3e} N")
    if args.compare_fidelity:
        names, scale, rows = scenes.compare_fidelity(scene, robot, traj, **options)
        say()
        say(scenes.format_fidelity(names, scale, rows, len(t)))
    if "--out" in outputs:
        write_csv(outputs["--out"], t, X, cable)
        say(f"wrote {args.out}")
    if "--plot" in outputs:
        plot(outputs["--plot"], t, X, title=f"offshore-crane: {traj.name}, {scene.methods[0]}",
             cable=cable, robot=robot)
        say(f"wrote {args.plot}")
    return status


def _kernel_time(done) -> str:
    """What the run spent before its timed part: compiling (the first time) or loading
    the kernels; never counted as the methods' run time."""
    ready = sum(done.prepare.values())
    if done.compiled:
        return f"; first compiled {done.compiled} kernels in {ready:.1f} s, cached for next time"
    if ready >= 0.05:
        return f"; kernels loaded in {ready:.2f} s"
    return ""
