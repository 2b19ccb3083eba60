"""Regenerate the measured figures of README.md and docs/ from the benchmarks' saved results.

    PYTHONPATH=src python benchmarks/sweep.py --save      # -> benchmarks/results/sweep.json
    PYTHONPATH=src python benchmarks/animate.py --save    # -> benchmarks/results/animate.json
    python scripts/figures.py                             # rewrites the rows below
    python scripts/figures.py --check                     # exit 1 if a row differs

Each figure row of a Markdown table is found by its first cell (a fixed label) and
replaced whole, so the documents say what the last saved run measured, not what someone
remembered (``tests/test_docs_figures.py`` runs the check). Rows of benchmarks that save
no results yet are written by hand.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"


def _met(ok: bool) -> str:
    return "met" if ok else "NOT met"


def sweep_rows(r: dict) -> dict:
    """``{(file, first cell): row}`` of benchmarks/sweep.py's figures."""
    o1, o2 = r["overhead_1"], r["overhead_2"]
    sh, fo, he, st = r["shipped"], r["forty"], r["heavy"], r["store"]
    same = all(x["identical"] for x in (sh, fo, he))

    def ratio(x):
        return f"{x['speedup']:.2f} × ({x['two']:.2f} s against {x['one']:.2f} s)"

    sizing = "docs/sizing.md"
    return {
        (sizing, "per-case overhead, serial"):
            f"| per-case overhead, serial ({o1['cases']} cases of `sweep_crane.toml`, 1001 "
            f"samples; own computation {o1['compute'] * 1e3:.1f} ms a case) | "
            f"{o1['overhead'] * 1e3:.2f} ms a case | ≤ 20 ms ({_met(o1['overhead'] <= 0.02)}) |",
        (sizing, "per-case overhead, 2 workers"):
            f"| per-case overhead, 2 workers (same cases; worker time not computing, idle "
            f"tail included) | {o2['overhead'] * 1e3:.2f} ms a case | ≤ 20 ms "
            f"({_met(o2['overhead'] <= 0.02)}) |",
        (sizing, "2 workers over 1, the shipped sweep"):
            f"| 2 workers over 1, the shipped sweep (`scenes/grids/sweep_grid.toml`, "
            f"{sh['cases']} cases; `sweep.run` whole, best of {r['repeat']}) | {ratio(sh)}"
            f"{'; rows identical' if same else '; ROWS DIFFER'} | ≥ 1.4 × "
            f"({_met(sh['speedup'] >= 1.4)}) |",
        (sizing, "2 workers over 1, 40 cases"):
            f"| 2 workers over 1, 40 cases of the shipped scene | {ratio(fo)} | 2 workers "
            f"≤ 1.05 × one worker's time ({_met(fo['two'] <= 1.05 * fo['one'])}) |",
        (sizing, "2 workers over 1, 8 cases"):
            f"| 2 workers over 1, 8 cases of ~0.5 s (1700 s at 100 Hz, 170 001 samples) | "
            f"{ratio(he)} | ≥ 1.8 × ({_met(he['speedup'] >= 1.8)}) |",
        (sizing, "slowest first case of 2 fresh workers"):
            f"| slowest first case of 2 fresh workers | {r['first_case_s']:.2f} s (forked "
            "with the kernels loaded) | workers never compile |",
        (sizing, "results store"):
            f"| results store: {st['cases']:,} cases of 11 samples | {st['files']} files, "
            f"{st['per_row']:.0f} B a row, `read_results` {st['read']:.2f} s | ≤ 20 files, "
            f"≤ 1 KB, ≤ 1 s ({_met(st['files'] <= 20 and st['per_row'] <= 1024 and st['read'] <= 1)}) |",
        ("README.md", "sweep overhead a case"):
            f"| sweep overhead a case (everything but the case's own computation, the row's "
            f"write included) | `benchmarks/sweep.py` | {o1['overhead'] * 1e3:.1f} ms (1 "
            f"worker), {o2['overhead'] * 1e3:.1f} ms (2) | ≤ 20 ms "
            f"({_met(max(o1['overhead'], o2['overhead']) <= 0.02)}) |",
        ("README.md", "sweep on 2 workers against 1"):
            f"| sweep on 2 workers against 1, the shipped {sh['cases']} cases / 8 cases of "
            f"0.5 s, rows identical | `benchmarks/sweep.py` | {sh['speedup']:.2f} × / "
            f"{he['speedup']:.2f} × | ≥ 1.4 × / ≥ 1.8 × "
            f"({_met(sh['speedup'] >= 1.4 and he['speedup'] >= 1.8)}) |",
        ("README.md", "sweep results store"):
            f"| sweep results store, 10⁴ cases | `benchmarks/sweep.py` | {st['files']} files, "
            f"{st['per_row']:.0f} B a row, read in {st['read']:.2f} s | ≤ 20 files, ≤ 1 KB a "
            f"row, ≤ 1 s ({_met(st['files'] <= 20 and st['per_row'] <= 1024 and st['read'] <= 1)}) |",
    }


def animate_rows(r: dict) -> dict:
    """``{(file, first cell): row}`` of benchmarks/animate.py's figures."""
    p, f, s = r["plain"], r["force"], r["stages"]
    drawing = s.get("drawing (1,800 frames, no encoding)", float("nan"))
    visual = "docs/visual.md"
    return {
        (visual, "plain"):
            f"| plain | {p['median_s']:.1f} s ({p['min_s']:.1f}–{p['max_s']:.1f}), "
            f"{p['mb']:.1f} MB | ≤ 30 s, {_met(p['max_s'] <= 30)} |",
        (visual, "`--color-by force`"):
            f"| `--color-by force` (inverse dynamics of the 6,001 samples included) | "
            f"{f['median_s']:.1f} s ({f['min_s']:.1f}–{f['max_s']:.1f}), {f['mb']:.1f} MB | "
            f"≤ 30 s, {_met(f['max_s'] <= 30)} |",
        (visual, "stages:"):
            "| stages: " + ", ".join(f"{k.split(' (')[0]} {v:.2f} s" for k, v in s.items())
            + f" ({drawing / 1800 * 1e3:.1f} ms a frame drawn) | | |",
        ("README.md", "a 60 s run at 30 fps"):
            f"| a 60 s run at 30 fps, 640 × 480 MP4 (1,801 frames) | `benchmarks/animate.py` "
            f"| {p['median_s']:.1f} s ({f['median_s']:.1f} s with legs coloured by force) | "
            f"≤ 30 s ({_met(max(p['max_s'], f['max_s']) <= 30)}) |",
    }


#: Each saved result and the rows it renders.
RENDERERS = {"sweep": sweep_rows, "animate": animate_rows}


def rows() -> dict:
    """Every generated row, from the results present."""
    out: dict = {}
    for name, render in RENDERERS.items():
        path = RESULTS / f"{name}.json"
        if path.is_file():
            out.update(render(json.loads(path.read_text())))
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
        for label, row in items:
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
