"""``python -m offshore_crane``: the command line (:mod:`offshore_crane.cli`)."""

from __future__ import annotations

import sys

from offshore_crane.cli import main

__all__ = ["main", "entry"]


def entry() -> None:
    """The ``offshore-crane`` program: :func:`main`, then exit with its status.

    Once the command is over its outputs are final (a sweep has stopped its worker pool
    itself, where a Ctrl-C is the usual one-line interruption); a Ctrl-C while the
    interpreter then shuts down has nothing left to stop and is ignored, instead of an
    "Exception ignored ... KeyboardInterrupt" traceback from a thread join at exit."""
    import signal

    status = main()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    sys.exit(status)


if __name__ == "__main__":
    entry()
