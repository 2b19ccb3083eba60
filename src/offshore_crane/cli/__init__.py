"""The command line: one thin sub-command per stage.

``main(argv=None)`` returns the exit status, so tests call it directly. Errors of the
library (:class:`~offshore_crane.errors.OffshoreCraneError`) become one line on stderr
and exit status 2. Each sub-command is a module with ``add_parser(subparsers)``, which
registers its parser with ``set_defaults(run=...)``; ``run(args) -> int`` is its exit
status. Sub-command modules import nothing heavy at module level (the CLI imports them all
to build ``--help``).
"""

from __future__ import annotations

import argparse
import sys

from offshore_crane.errors import InputError, OffshoreCraneError

#: Modules adding sub-commands: each has ``add_parser(subparsers)``, which registers its
#: parser with ``set_defaults(run=...)``; ``run(args) -> int`` is its exit status. They
#: must import nothing heavy at module level (the CLI imports them all to build --help).
SUBCOMMANDS = ("offshore_crane.cli.id", "offshore_crane.cli.motion",
               "offshore_crane.cli.simulate", "offshore_crane.cli.serial_id",
               "offshore_crane.cli.describe", "offshore_crane.cli.compile",
               "offshore_crane.cli.size", "offshore_crane.cli.sweep",
               "offshore_crane.cli.animate", "offshore_crane.cli.show",
               "offshore_crane.cli.view", "offshore_crane.cli.export")


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
    for name in SUBCOMMANDS:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name and name.startswith(exc.name):
                continue            # sub-command not part of this build
            raise
        module.add_parser(sub)
    return parser


#: Exit statuses (docs/outputs.md): a check failed (e.g. Kane against RNEA), bad input or
#: output, interrupted by SIGINT / SIGTERM, standard output closed by the reader.
CHECK_FAILED, BAD_INPUT, INTERRUPTED, TERMINATED, BROKEN_PIPE = 1, 2, 130, 143, 141


def main(argv=None) -> int:
    """Run the command line with ``argv`` (default ``sys.argv[1:]``); return exit status.

    Every failure is one line on stderr, never a traceback: library errors exit 2, SIGINT
    130, SIGTERM 143 (temporary files removed), a closed standard output (``| head``) 141.
    NumPy's floating-point warnings are silenced: the kernels check their results and
    raise a named error instead.
    """
    import warnings

    from offshore_crane.io import Terminated, signals_as_exceptions
    from offshore_crane.robot.kinematics.workspace import OffshoreCraneWarning

    def one_line(message, category, filename, lineno, file=None, line=None):
        print(f"offshore-crane: warning: {message}", file=sys.stderr)

    try:
        with signals_as_exceptions(), warnings.catch_warnings():
            warnings.simplefilter("always", OffshoreCraneWarning)
            warnings.filterwarnings("ignore", category=RuntimeWarning)
            warnings.showwarning = one_line
            args = build_parser().parse_args(_negative_numbers(argv))
            return args.run(args)
    except OffshoreCraneError as exc:
        print(f"offshore-crane: error: {exc}", file=sys.stderr)
        return BAD_INPUT
    except KeyboardInterrupt:
        print("offshore-crane: interrupted (SIGINT); nothing half-written was left",
              file=sys.stderr)
        return INTERRUPTED
    except Terminated:
        print("offshore-crane: terminated (SIGTERM); nothing half-written was left",
              file=sys.stderr)
        return TERMINATED
    except BrokenPipeError:
        _quiet_stdout()
        return BROKEN_PIPE


def plan(args, scene):
    """Check ``--out`` and ``--plot`` of a scene-driven command before computing.

    Returns:
        ``(outputs, say)``: the :func:`~offshore_crane.io.plan_outputs` targets, and the
        function that prints the command's report (to standard error when an output goes
        to standard output).
    """
    from offshore_crane.io import FIGURE_FORMATS, plan_outputs

    inputs = [args.scene, scene.trajectory if scene.trajectory != "table1" else None,
              scene.robot_description]
    outputs = plan_outputs({"--out": args.out, "--plot": args.plot}, inputs,
                           {"--plot": FIGURE_FORMATS})
    if any(o.kind == "stdout" for o in outputs.values()):
        return outputs, lambda *a: print(*a, file=sys.stderr)
    return outputs, print


def add_robot_options(p) -> None:
    """``--robot PATH`` and ``--set NAME=VALUE`` (one path: :func:`robot_scene`)."""
    p.add_argument("--robot", metavar="FILE.toml",
                   help="robot description file (default: the scene's, else the shipped "
                   "lab design; see docs/robot-description.md)")
    p.add_argument("--set", action="append", metavar="NAME=VALUE",
                   help="override a robot field by its dotted name or alias, e.g. "
                   "legs.lower.mass=3.1, payload.com=[0,0,-0.05], with_arm=0; repeatable; "
                   "an override that contradicts the scene is an error")


def robot_scene(args, scene):
    """``scene`` with ``--robot`` and ``--set`` applied, both checked like the scene's
    own robot fields (:func:`offshore_crane.scenes.with_robot_overrides`).

    Raises:
        SceneError: ``--robot`` names another description than the scene's, or a
            ``--set`` contradicts the scene.
        DescriptionError: a bad ``--set`` (unknown name, not a number, ...).
    """
    import os
    from dataclasses import replace

    from offshore_crane.errors import SceneError
    from offshore_crane.robot.overrides import parse_set
    from offshore_crane.scenes import with_robot_overrides

    if args.robot is not None:
        given = os.path.abspath(args.robot)
        if not os.path.isfile(given):
            raise InputError(f"--robot {args.robot}: no such file (a robot description, "
                             "TOML)", name="--robot")
        own = scene.robot_description
        if own is not None and os.path.abspath(own) != given:
            raise SceneError(f"{scene.where()}: --robot {args.robot} contradicts the "
                             f"scene's [robot] description = {own}: give one",
                             path=scene.path, name="robot.description")
        scene = replace(scene, robot_description=args.robot, arm=None, payload=None)
    return with_robot_overrides(scene, parse_set(args.set))


def comma_numbers(text: str, n: int, option: str) -> list[float]:
    """``n`` finite numbers from ``"a,b,c"`` (``--pose``, ``--sway``).

    Raises:
        InputError: not ``n`` finite comma-separated numbers (naming the option).
    """
    import math

    try:
        values = [float(x) for x in text.replace(" ", "").split(",")]
    except ValueError:
        values = []
    if len(values) != n or not all(math.isfinite(v) for v in values):
        raise InputError(f"{option} {text}: give {n} finite comma-separated numbers",
                         name=option)
    return values


def _quiet_stdout() -> None:
    """After a BrokenPipeError: point stdout at /dev/null so that the interpreter's final
    flush does not fail again (the Python documentation's recipe)."""
    import os

    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass
    finally:
        os.close(devnull)


def _negative_numbers(argv):
    """argparse takes ``-9.81e0`` for an option (its negative-number test misses the
    exponent form): join such values to their option with ``=`` is not possible for
    ``nargs=3``, so mark them with a leading space, which ``float()`` ignores."""
    import re

    argv = list(sys.argv[1:] if argv is None else argv)
    number = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")
    return [f" {a}" if number.match(a) else a for a in argv]


