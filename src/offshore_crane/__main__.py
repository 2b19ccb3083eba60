"""``python -m offshore_crane``: the command line (:mod:`offshore_crane.cli`)."""

from __future__ import annotations

import sys

from offshore_crane.cli import main

__all__ = ["main"]

if __name__ == "__main__":
    sys.exit(main())
