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

from offshore_crane.lazy import submodule_getattr
from offshore_crane.errors import InputError, OffshoreCraneError

#: Modules adding sub-commands: each has ``add_parser(subparsers)``, which registers its
#: parser with ``set_defaults(run=...)``; ``run(args) -> int`` is its exit status. They
#: must import nothing heavy at module level (the CLI imports them all to build --help).
SUBCOMMANDS = ("offshore_crane.cli.id", "offshore_crane.cli.motion",
               "offshore_crane.cli.simulate", "offshore_crane.cli.serial_id",
               "offshore_crane.cli.describe", "offshore_crane.cli.compile",
               "offshore_crane.cli.size", "offshore_crane.cli.sweep",
               "offshore_crane.cli.design",
               "offshore_crane.cli.animate", "offshore_crane.cli.show",
               "offshore_crane.cli.view", "offshore_crane.cli.export",
               "offshore_crane.cli.compensate", "offshore_crane.cli.excite",
               "offshore_crane.cli.identify")


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

    from offshore_crane import progress
    from offshore_crane.io import Terminated, signals_as_exceptions
    from offshore_crane.robot.kinematics.workspace import OffshoreCraneWarning

    def one_line(message, category, filename, lineno, file=None, line=None):
        print(f"offshore-crane: warning: {message}", file=sys.stderr)

    try:
        with signals_as_exceptions(), warnings.catch_warnings():
            warnings.simplefilter("always", OffshoreCraneWarning)
            warnings.filterwarnings("ignore", category=RuntimeWarning)
            warnings.showwarning = one_line
            progress.configure(None)            # bars when stderr is a terminal
            progress.listen(lambda text: print(f"offshore-crane: {text}", file=sys.stderr,
                                               flush=True))
            args = build_parser().parse_args(_negative_numbers(argv))
            try:
                return args.run(args)
            finally:
                _stop_pool()            # interruptible here, not at the interpreter's exit
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


def _stop_pool() -> None:
    """Stop the joblib worker pool a command started (none started: nothing imported)."""
    if "joblib.externals.loky.reusable_executor" in sys.modules:
        from offshore_crane.studies.sweep.backends import shutdown_pool

        shutdown_pool()


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
    """argparse takes ``-9.81e0`` (its negative-number test misses the exponent form) and
    ``-0.01,0,0.6,...`` (a comma-separated list) for options: joining such values to
    their option with ``=`` is not possible for ``nargs=3``, so mark them with a leading
    space, which ``float()`` and the comma-list readers ignore."""
    import re

    argv = list(sys.argv[1:] if argv is None else argv)
    value = r"-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?"
    number = re.compile(rf"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?(,\s*{value})*$")
    return [f" {a}" if number.match(a) else a for a in argv]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
