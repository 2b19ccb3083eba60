"""Draw the package's columns and the imports between them (docs/architecture.png).

Reads the import graph of the installed ``offshore_crane`` with grimp (what import-linter
reads), groups modules by column (the top-level sub-package, or the ground-floor module),
counts the imports from one column into another and draws the columns in the order of
the layers contract in ``pyproject.toml``, arrows pointing from importer to imported.
An arrow drawn in red runs against the layers (the tests fail on it too).

    python scripts/architecture_drawing.py [--out docs/architecture.png]

It also prints the table of column-to-column import counts.
"""

from __future__ import annotations

import argparse
import tomllib
from collections import Counter
from pathlib import Path

import grimp

ROOT = Path(__file__).resolve().parents[1]


def layers() -> list[list[str]]:
    """The layers contract, top first: each a list of the columns on that floor."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())
    for contract in config["tool"]["importlinter"]["contracts"]:
        if contract["type"] == "layers":
            return [[c.strip() for c in layer.split("|")] for layer in contract["layers"]]
    raise SystemExit("pyproject.toml has no layers contract")


def column_edges() -> Counter:
    """``{(importer column, imported column): number of module imports}``."""
    graph = grimp.build_graph("offshore_crane", cache_dir=None)
    counts: Counter = Counter()
    for module in graph.modules:
        parts = module.split(".")
        if len(parts) < 2:
            continue
        for target in graph.find_modules_directly_imported_by(module):
            tparts = target.split(".")
            if len(tparts) >= 2 and tparts[1] != parts[1]:
                counts[(parts[1], tparts[1])] += 1
    return counts


def draw(floors: list[list[str]], edges: Counter, out: Path) -> None:
    """Columns left to right from the bottom of the layers up (a floor of two columns
    stacked), the ground floor as one band beneath them (every column may use it; its
    arrows are left out); an arrow per column pair that imports, width by count."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ground = {name for columns in floors[-2:] for name in columns}
    columns = [c for c in floors[:-2]][::-1]                  # bottom (robot) first
    pos = {}
    for k, floor in enumerate(columns):
        for j, name in enumerate(floor):
            pos[name] = (k, 0.55 * (j - (len(floor) - 1) / 2))
    rank = {name: level for level, floor in enumerate(floors) for name in floor}
    fig, ax = plt.subplots(figsize=(12, 5.6))
    for (a, b), n in sorted(edges.items()):
        if a not in pos or b not in pos:
            continue
        wrong = rank[b] <= rank[a]
        span = abs(pos[a][0] - pos[b][0])
        ax.annotate("", xy=pos[b], xytext=pos[a],
                    arrowprops=dict(arrowstyle="->", lw=0.5 + 0.2 * min(n, 10),
                                    color="tab:red" if wrong else "0.5", shrinkA=16,
                                    shrinkB=16,
                                    connectionstyle=f"arc3,rad={0.08 + 0.05 * span:.2f}"))
    for name, (x, y) in pos.items():
        ax.text(x, y, name, ha="center", va="center", fontsize=10,
                bbox=dict(boxstyle="round", fc="white", ec="0.3"))
    ax.text((len(columns) - 1) / 2, -1.25, "ground floor, used by every column:  "
            + "  ".join(sorted(ground)), ha="center", va="center", fontsize=10,
            bbox=dict(boxstyle="square", fc="0.93", ec="0.5"))
    ax.set_xlim(-0.6, len(columns) - 0.4)
    ax.set_ylim(-1.6, 3.4)
    ax.axis("off")
    ax.set_title("offshore_crane: each arrow an import from one column into another "
                 "(grey: allowed, red: against the layers)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "architecture.png")
    args = parser.parse_args()
    floors = layers()
    edges = column_edges()
    print(f"{'importer':<12} {'imported':<12} imports")
    for (a, b), n in sorted(edges.items()):
        print(f"{a:<12} {b:<12} {n}")
    draw(floors, edges, args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
