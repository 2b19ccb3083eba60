"""Command line: ``offshore-crane id``, ``offshore-crane serial-id``.

``main(argv=None)`` returns the exit status, so tests call it directly. Errors of the
library (:class:`OffshoreCraneError`) become one line on stderr and exit status 2.
"""

from __future__ import annotations

import argparse
import sys

from .errors import InputError, OffshoreCraneError
from .conventions import ACTUATOR_UNITS, ACTUATORS, AGREEMENT_RTOL

RELATIVE_LIMIT = AGREEMENT_RTOL


def _parse_set(items) -> dict:
    out = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        if not sep or not name:
            raise InputError(f"--set expects name=value, got '{item}'", name="--set")
        out[name.strip()] = value.strip()
    return out


def _id_parser(sub) -> None:
    p = sub.add_parser("id", help="inverse dynamics along a trajectory",
                       description="Actuator forces of the hybrid crane along a trajectory. "
                       "With --scene, the scene file sets the defaults of --trajectory, "
                       "--duration, --rate, --fd-order, --method, --leg-model, --outputs, "
                       "--gravity and the robot (--set is applied on top); flags given "
                       "explicitly override the scene.")
    p.add_argument("--scene", metavar="FILE.toml",
                   help="scene file: sub-systems, leg model, payload, gravity, trajectory, "
                   "outputs, methods (see scenes/)")
    p.add_argument("--trajectory",
                   help="'table1' (paper Table 1, analytic derivatives; default) or a CSV "
                   "t_s,q1..q9")
    p.add_argument("--backend", choices=("numpy", "numba", "auto"), default="numpy",
                   help="kernel of kane/rnea: numpy (default: starts fastest), numba "
                   "(compiled, ~2x faster per sample, ~0.6 s to load; needs the 'fast' "
                   "extra) or auto (numba when installed)")
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
    p.add_argument("--plot", help="write a figure like the paper's Fig. 3 (PNG, PDF, SVG)")
    p.add_argument("--set", action="append", metavar="NAME=VALUE",
                   help="override a robot parameter (xacro argument); repeatable")
    p.add_argument("--gravity", type=float, nargs=3, metavar=("GX", "GY", "GZ"),
                   help="gravity in the base frame [m/s²] (default 0 0 -9.81)")
    p.add_argument("--no-limits", action="store_true",
                   help="do not stop at leg strokes, U-joint or arm joint limits")
    p.add_argument("--warn-cond", type=float, default=1e5,
                   help="warn above this condition number (default 1e5)")
    p.add_argument("--error-cond", type=float, default=1e8,
                   help="stop above this condition number (default 1e8)")
    p.add_argument("--compare-fidelity", action="store_true",
                   help="also run every leg model (kane) and print its run time and "
                   "largest deviation from 'full' per actuator")
    p.set_defaults(run=_run_id)


def _thresholds(args):
    from .kinematics.workspace import Thresholds

    try:
        return Thresholds(warn=args.warn_cond, error=args.error_cond)
    except ValueError as exc:
        raise InputError(str(exc), name="--warn-cond") from None


_METHOD_LABELS = {"kane": "Kane", "kane-explicit": "Kane (explicit)", "rnea": "RNEA"}


def _scene(args):
    """The scene to run: ``--scene`` (or the default one) with the explicit flags applied."""
    from .scenes import Scene, load_scene, with_overrides

    scene = load_scene(args.scene) if args.scene else Scene()
    methods = None
    if args.method:
        methods = ("kane", "rnea") if args.method == "both" else (args.method,)
    outputs = None if not args.outputs else tuple(o.strip() for o in args.outputs.split(","))
    unknown = [o for o in outputs or () if o not in ACTUATORS]
    if unknown:
        raise InputError(f"--outputs: unknown {', '.join(map(repr, unknown))}: choose among "
                         f"{', '.join(ACTUATORS)}", name="--outputs")
    where = f"{args.scene} with the command-line options" if args.scene else "command line"
    return with_overrides(scene, where, trajectory=args.trajectory, duration=args.duration,
                          rate=args.rate, fd_order=args.fd_order, methods=methods,
                          leg_model=args.leg_model, outputs=outputs,
                          gravity=None if args.gravity is None else tuple(args.gravity))


def _run_id(args) -> int:
    from . import scenes
    from .report import check_output, format_summary, plot, summary_rows, write_csv

    for path, is_plot in ((args.out, False), (args.plot, True)):
        if path:
            check_output(path, plot=is_plot)
    scene = _scene(args)
    robot = scenes.load_robot(scene, **_parse_set(args.set))
    traj = scenes.load_trajectory(scene, robot)
    options = dict(limits=not args.no_limits, thresholds=_thresholds(args),
                   backend=args.backend)
    done = scenes.run(scene, robot, traj, **options)
    res, t = done.result, traj.t
    X = res.X
    if args.scene:
        print(f"scene {scene.name} ({args.scene}): {scene.describe()}")
    print(f"offshore-crane id: trajectory {traj.name}, {len(t)} samples, "
          f"t = {t[0]:.2f}..{t[-1]:.2f} s, method "
          f"{'both' if scene.methods == ('kane', 'rnea') else ' + '.join(scene.methods)} "
          f"({', '.join(f'{m} {s * 1e3:.1f} ms' for m, s in done.seconds.items())})")
    print(f"model: {'exact' if not res.approximations else 'APPROXIMATE: ' + '; '.join(res.approximations)}"
          + (f"; skipped: {'; '.join(res.pruned)}" if res.pruned else ""))
    cols = [k for k, name in enumerate(ACTUATORS) if name in res.outputs]
    print(format_summary(summary_rows(t, X[:, cols], [ACTUATORS[k] for k in cols],
                                      [ACTUATOR_UNITS[k] for k in cols])))
    for kind, kappa, k in res.worst():
        print(f"worst {kind} condition number: {kappa:.4g} at t = {t[k]:.2f} s (sample {k})")
    status = 0
    first = _METHOD_LABELS[scene.methods[0]]
    for m, diff, scale, rel, i, j in scenes.compare_methods(done):
        ok = rel <= RELATIVE_LIMIT
        print(f"{first} vs {_METHOD_LABELS[m]}: max |ΔX| = {diff:.3e} (sample {i}, "
              f"t = {t[i]:.2f} s, column {j + 1}); relative to max |X| = {scale:.4g}: "
              f"{rel:.3e} "
              f"({'OK' if ok else 'FAIL'}, limit {RELATIVE_LIMIT:g})")
        status = status if ok else 1
    if args.compare_fidelity:
        names, scale, rows = scenes.compare_fidelity(scene, robot, traj, **options)
        print()
        print(scenes.format_fidelity(names, scale, rows, len(t)))
    if args.out:
        write_csv(args.out, t, X)
        print(f"wrote {args.out}")
    if args.plot:
        plot(args.plot, t, X, title=f"offshore-crane: {traj.name}, {scene.methods[0]}")
        print(f"wrote {args.plot}")
    return status


#: Modules adding sub-commands: each has ``add_parser(subparsers)``, which registers its
#: parser with ``set_defaults(run=...)``; ``run(args) -> int`` is its exit status. They
#: must import nothing heavy at module level (the CLI imports them all to build --help).
SUBCOMMANDS = ("offshore_crane.serial.cli",)


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are :class:`InputError` (one line, exit status 2)."""

    def error(self, message):
        raise InputError(f"{self.prog}: {message} (see --help)", name="argv")


def build_parser() -> argparse.ArgumentParser:
    import importlib

    parser = _Parser(
        prog="offshore-crane",
        description="Inverse dynamics of a 9-DOF Stewart-platform + SCARA crane robot.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    _id_parser(sub)
    for name in SUBCOMMANDS:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name and name.startswith(exc.name):
                continue            # sub-command not part of this build
            raise
        module.add_parser(sub)
    return parser


def main(argv=None) -> int:
    """Run the command line with ``argv`` (default ``sys.argv[1:]``); return exit status."""
    import warnings

    from .kinematics.workspace import OffshoreCraneWarning

    def one_line(message, category, filename, lineno, file=None, line=None):
        print(f"offshore-crane: warning: {message}", file=sys.stderr)

    try:
        args = build_parser().parse_args(argv)
        with warnings.catch_warnings():
            warnings.simplefilter("always", OffshoreCraneWarning)
            warnings.showwarning = one_line
            return args.run(args)
    except OffshoreCraneError as exc:
        print(f"offshore-crane: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
