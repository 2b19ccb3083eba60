"""Benchmark of the hybrid crane: time per sample against error (issue 5).

The same code as ``offshore-crane bench`` (:mod:`offshore_crane.bench`)::

    python scripts/bench.py [--quick] [--out DIR] [--sizes N ...] [--budget S]
                            [--only NAMES] [--no-startup] [--no-profile]

writes bench.csv, errors.csv, pareto.png, summary.md and profiles.txt to DIR (default
docs/bench when run from the checkout, else ./bench) and prints the tables.
"""

from __future__ import annotations

import sys
from pathlib import Path

try:
    from offshore_crane.bench import main
except ImportError:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
    from offshore_crane.bench import main

if __name__ == "__main__":
    sys.exit(main())
