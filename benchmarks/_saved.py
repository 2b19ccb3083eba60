"""Where the benchmarks keep their figures: ``--save`` writes ``benchmarks/results/NAME.json``,
from which ``python scripts/figures.py`` writes the measured figures of README.md and
docs/ (``tests/test_docs_figures.py`` checks that the documents say what was saved)."""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"


def add_save_option(parser, name: str) -> None:
    """``--save``: write the figures to ``benchmarks/results/<name>.json``."""
    parser.add_argument("--save", action="store_true",
                        help=f"write the figures to benchmarks/results/{name}.json (then "
                        "python scripts/figures.py rewrites the documents' figures)")


def benchmark_parser(doc: str, name: str, *,
                     repeats: int | None = None) -> argparse.ArgumentParser:
    """A benchmark's command line: the first paragraph of its docstring ``doc`` as the
    description, ``--save`` (:func:`add_save_option`) and, given ``repeats``,
    ``--repeats`` (the timed repeats, ``repeats`` by default)."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    if repeats is not None:
        parser.add_argument("--repeats", type=int, default=repeats,
                            help=f"timed repeats ({repeats})")
    add_save_option(parser, name)
    return parser


def stamp() -> dict:
    """The date and the machine the figures were measured on."""
    return {"date": time.strftime("%Y-%m-%d"), "cores": os.cpu_count()}


def cpu_busy() -> float:
    """CPU seconds of every process on the machine (``/proc/stat``: all but idle, iowait),
    NaN where there is no ``/proc``: the other processes' load during a measurement is
    its change less the benchmark's own CPU time, over the wall time (the load average
    would count the benchmark itself)."""
    try:
        with open("/proc/stat") as fh:
            fields = [int(x) for x in fh.readline().split()[1:]]
    except OSError:
        return float("nan")
    return (sum(fields) - fields[3] - fields[4]) / os.sysconf("SC_CLK_TCK")


def save(name: str, figures: dict) -> Path:
    """Write ``figures`` (JSON-able; NumPy scalars as floats) whole, atomically."""
    RESULTS.mkdir(exist_ok=True)
    path = RESULTS / f"{name}.json"
    part = path.with_suffix(".json.part")
    part.write_text(json.dumps(figures, indent=1, default=float) + "\n")
    os.replace(part, path)
    print(f"wrote {path.relative_to(RESULTS.parents[1])}")
    return path
