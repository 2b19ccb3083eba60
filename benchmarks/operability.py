"""The example sweep of docs/sizing.md as a user runs it: its operability, its failed cases,
its time, and the diagram the page shows.

    python benchmarks/operability.py [--workers 2] [--save]

``offshore-crane sweep --scene scenes/sweep_crane.toml --grid scenes/grids/sweep_grid.toml
--workers 2 --out DIR --plot DIR --scatter scenes/grids/scatter_illustrative.csv`` with the
default records (each case a stationary 3-hour record: ``scenes.exposure``), timed whole in
this process; then its verdicts and operability read back from the results directory
(``sweep.read_results``, ``sweep.verdicts``, ``sweep.operability``). ``--save`` writes
``benchmarks/results/operability.json`` (rendered into docs/sizing.md by
``scripts/figures.py``) and copies the run's ``operability.png`` to ``docs/``.
"""

from __future__ import annotations

import contextlib
import io
import math
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from _saved import benchmark_parser, cpu_busy, save, stamp  # noqa: E402
from offshore_crane import scenes  # noqa: E402
from offshore_crane.cli import main as cli  # noqa: E402
from offshore_crane.studies import sweep  # noqa: E402

SCENE = ROOT / "scenes" / "sweep_crane.toml"
GRID = ROOT / "scenes" / "grids" / "sweep_grid.toml"
SCATTER = ROOT / "scenes" / "grids" / "scatter_illustrative.csv"


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "operability")
    parser.add_argument("--workers", type=int, default=2, help="sweep workers (2)")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        out, plots = Path(tmp) / "results", Path(tmp) / "plots"
        command = ["sweep", "--scene", str(SCENE), "--grid", str(GRID), "--workers",
                   str(args.workers), "--out", str(out), "--plot", str(plots), "--scatter",
                   str(SCATTER), "--no-progress"]
        t0, busy0 = time.perf_counter(), cpu_busy()
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            status = cli(command)
        wall = time.perf_counter() - t0
        other = max(0.0, (cpu_busy() - busy0) / wall - args.workers)
        print(printed.getvalue())
        if status != 0:
            raise SystemExit(f"the sweep exited {status}")
        scene = scenes.load_scene(SCENE)
        df = sweep.read_results(out)
        verdicts = sweep.verdicts(df, scene)
        table = sweep.operability(verdicts, sweep.load_scatter(SCATTER), scene)
        by = {("overall" if math.isnan(h) else f"{h:g}"): float(p)
              for h, p in zip(table["heading"], table["operability_pct"])}
        failed = df[df["status"] != "ok"]
        figures = {**stamp(), "workers": args.workers, "wall_s": wall, "other_load": other,
                   "cases": len(df), "failed": len(failed),
                   "failed_errors": sorted(set(failed["error_type"])),
                   "sea_states": len(verdicts),
                   "bases": sorted(set(verdicts["basis"])),
                   "record_s": float(df.loc[df["status"] == "ok", "duration_s"].iloc[0]),
                   "operability_pct": by}
        print(f"{len(df)} cases ({len(failed)} failed: {', '.join(figures['failed_errors'])})"
              f" in {wall:.1f} s on {args.workers} workers (other load {other:.2f} cores); "
              f"operability {by}")
        if args.save:
            save("operability", figures)
            shutil.copyfile(plots / "operability.png", ROOT / "docs" / "operability.png")
            print("wrote docs/operability.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
