"""The worked question of docs/design.md as a user runs it: "which arm lengths give the most
reach while every actuator stays <= 80 % of its capacity in Hs 2.5 m beam seas at 1:20?",
then the question the lab platform can answer (the arm's actuators and the legs' forces
<= 80 %), each one ``offshore-crane design`` command, timed whole in this process.

    python benchmarks/design.py [--budget 60] [--workers 2] [--save]

``--save`` writes ``benchmarks/results/design.json`` (rendered into docs/design.md by
``scripts/figures.py``) and copies the second run's front figure to ``docs/design_front.png``.
"""

from __future__ import annotations

import contextlib
import io
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from _saved import benchmark_parser, cpu_busy, save, stamp  # noqa: E402
from offshore_crane.cli import main as cli  # noqa: E402
from offshore_crane.studies import design  # noqa: E402

SCENE = ROOT / "scenes" / "sweep_crane.toml"
SPACES = {"every actuator": ROOT / "scenes" / "spaces" / "arm_reach.toml",
          "arm and leg forces": ROOT / "scenes" / "spaces" / "arm_reach_forces.toml"}


def _run(space: Path, out: Path, plots: Path, budget: int, workers: int) -> dict:
    command = ["design", "--scene", str(SCENE), "--space", str(space), "--budget",
               str(budget), "--workers", str(workers), "--out", str(out), "--plot",
               str(plots), "--no-progress"]
    t0, busy0 = time.perf_counter(), cpu_busy()
    printed, said = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(said):
        status = cli(command)
    wall = time.perf_counter() - t0
    print(printed.getvalue() + said.getvalue())
    if status not in (0, 1):
        raise SystemExit(f"the design exited {status}")
    figures = {"status": status, "wall_s": wall, "budget": budget, "workers": workers,
               "other_load": max(0.0, (cpu_busy() - busy0) / wall - workers),
               "message": said.getvalue().strip().removeprefix("offshore-crane: ")}
    if status == 0:
        rows = design.read_front(out / design.PARETO)
        reach = next(c for c in rows[0] if c.startswith("arm.link1.shape.size.x +"))
        best = max(rows, key=lambda r: r[reach])
        figures.update(front=len(rows), best={k: v for k, v in best.items()},
                       reach_column=reach)
    return figures


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "design")
    parser.add_argument("--budget", type=int, default=60, help="candidates (60)")
    parser.add_argument("--workers", type=int, default=2, help="sweep workers (2)")
    args = parser.parse_args(argv)
    figures = {**stamp()}
    with tempfile.TemporaryDirectory() as tmp:
        for name, space in SPACES.items():
            out, plots = Path(tmp) / name.replace(" ", "-"), Path(tmp) / "plots"
            plots.mkdir(exist_ok=True)
            figures[name] = _run(space, out, plots / name.replace(" ", "-"), args.budget,
                                 args.workers)
        if args.save:
            shutil.copyfile(plots / "arm-and-leg-forces" / "front.png",
                            ROOT / "docs" / "design_front.png")
            print("wrote docs/design_front.png")
    if args.save:
        save("design", figures)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
