"""Regenerate the measured figures of README.md and docs/ from the benchmarks' saved results.

    python benchmarks/NAME.py --save      # -> benchmarks/results/NAME.json, for NAME in
                                          #    RENDERERS (sweep needs the sweep extra,
                                          #    mjcf_agreement the mjcf extra)
    python scripts/figures.py             # rewrites the figures below
    python scripts/figures.py --check     # exit 1 if a figure differs

Each figure row of a Markdown table is found by its first cell (a fixed label) and
replaced whole; a figure inside prose sits between ``<!-- figure KEY -->`` and
``<!-- /figure -->`` (invisible in the rendered page) and is replaced between them. So the
documents say what the last saved run measured, not what someone remembered
(``tests/test_docs_figures.py`` runs the check, and fails on a measured figure typed
outside what this script writes). ``benchmarks/bench.py --out docs/bench`` writes its own
``docs/bench/summary.md``, which is its saved result here (:data:`SOURCES`);
``benchmarks/ci.py`` runs the whole CI on a fresh clone (CI does not run it).
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"

sys.path.insert(0, str(Path(__file__).resolve().parent))        # the renderers beside it
from figures_kernels import (animate_rows, bench_rows, bench_serial_rows,  # noqa: E402
                             cable_swing_rows, ci_rows, compile_rows, lift_rows,
                             mjcf_agreement_rows, passes_rows, pinocchio_fd_rows,
                             read_summary,
                             roofline_rows, sea_synthesis_rows, simulation_rows,
                             stepper_rows, gym_rows)
from figures_studies import (compensation_rows, design_rows, extremes_rows,  # noqa: E402
                             identification_memory_rows, identification_rows,
                             operability_rows, sweep_rows)


#: Each saved result and the figures it renders.
RENDERERS = {"sweep": sweep_rows, "animate": animate_rows, "cable_swing": cable_swing_rows,
             "sea_synthesis": sea_synthesis_rows, "pinocchio_fd": pinocchio_fd_rows,
             "mjcf_agreement": mjcf_agreement_rows, "lift": lift_rows,
             "roofline": roofline_rows, "compile": compile_rows, "ci": ci_rows,
             "bench_serial": bench_serial_rows, "bench": bench_rows,
             "identification": identification_rows,
             "identification_memory": identification_memory_rows, "extremes": extremes_rows,
             "compensation": compensation_rows, "operability": operability_rows,
             "simulation": simulation_rows, "design": design_rows, "passes": passes_rows,
             "stepper": stepper_rows, "gym": gym_rows}

#: Saved results that are not ``benchmarks/results/NAME.json``, and how to read them.
SOURCES = {"bench": (ROOT / "docs" / "bench" / "summary.md", read_summary)}


def source(name: str) -> Path:
    """Where renderer ``name``'s saved result is."""
    return SOURCES[name][0] if name in SOURCES else RESULTS / f"{name}.json"

#: A figure inside prose: ``<!-- figure KEY -->text<!-- /figure -->``.
MARKED = re.compile(r"<!-- figure (\S+) -->(.*?)<!-- /figure -->", re.S)


def rows() -> dict:
    """Every generated row, from the results present."""
    out: dict = {}
    for name, render in RENDERERS.items():
        path = source(name)
        if path.is_file():
            read = SOURCES[name][1] if name in SOURCES else json.loads
            out.update(render(read(path.read_text(encoding="utf-8"))))
    return out


def apply(write: bool) -> list[str]:
    """Replace each generated row in its file (``write``) or list the rows that differ.

    Returns:
        ``["file: first cell", ...]`` of rows that differed (or were missing).
    """
    changed = []
    by_file: dict = {}
    for (name, label), row in rows().items():
        by_file.setdefault(name, []).append((label, row))
    for name, items in by_file.items():
        path = ROOT / name
        lines = path.read_text(encoding="utf-8").splitlines(keepends=True)
        text = "".join(lines)
        for label, row in items:
            if label.startswith("figure "):
                key = label.split(" ", 1)[1]
                found = [m for m in MARKED.finditer(text) if m.group(1) == key]
                if len(found) != 1:
                    changed.append(f"{name}: '{label}' found {len(found)} times (need 1)")
                elif found[0].group(2) != row:
                    changed.append(f"{name}: {label}")
                    m = found[0]
                    text = text[:m.start(2)] + row + text[m.end(2):]
                continue
        lines = text.splitlines(keepends=True)
        for label, row in items:
            if label.startswith("figure "):
                continue
            hits = [i for i, ln in enumerate(lines) if ln.startswith(f"| {label}")]
            if len(hits) != 1:
                changed.append(f"{name}: '{label}' found {len(hits)} times (need 1)")
                continue
            if lines[hits[0]].rstrip("\n") != row:
                changed.append(f"{name}: {label}")
                lines[hits[0]] = row + "\n"
        if write:
            path.write_text("".join(lines), encoding="utf-8")
    return changed


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--check", action="store_true", help="change nothing; exit 1 if a row "
                   "differs from the saved results")
    args = p.parse_args()
    changed = apply(write=not args.check)
    for c in changed:
        print(("differs: " if args.check else "updated: ") + c)
    return 1 if args.check and changed else 0


if __name__ == "__main__":
    sys.exit(main())
