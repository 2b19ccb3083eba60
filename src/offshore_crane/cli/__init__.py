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

from ..errors import InputError, OffshoreCraneError

#: Modules adding sub-commands: each has ``add_parser(subparsers)``, which registers its
#: parser with ``set_defaults(run=...)``; ``run(args) -> int`` is its exit status. They
#: must import nothing heavy at module level (the CLI imports them all to build --help).
SUBCOMMANDS = ("offshore_crane.cli.id", "offshore_crane.serial.cli", "offshore_crane.cli.compile")


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


def main(argv=None) -> int:
    """Run the command line with ``argv`` (default ``sys.argv[1:]``); return exit status."""
    import warnings

    from ..kinematics.workspace import OffshoreCraneWarning

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


