"""The identification commands' time (issue 35): ``excite --duration 20`` and
``identify`` on a 20 s log of it, each run as a user runs it (a fresh process, the
kernels already compiled), wall-clock and CPU time (user + system of the child).

    python benchmarks/identification.py [--repeats 3] [--save]

The log: the robot of ``--set platform.mass=48 --set arm.link1.mass=4.6`` simulated
along the excitation (``simulate --out``: t, q and the applied forces at 1 kHz, no
rates: ``identify`` differentiates the positions). Printed and saved: the median and
range over ``--repeats`` of each command, the excitation's condition number and Table
1's (from ``excite``'s own line), the machine's cores and its load average when
measured (the project's machine is shared: a busy machine is slower).
"""

from __future__ import annotations

import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from _saved import benchmark_parser, save, stamp  # noqa: E402  (benchmarks/ is on the path)

HEAVY = ["--set", "platform.mass=48", "--set", "arm.link1.mass=4.6"]


def timed(args: list[str]) -> tuple[float, float, str]:
    """``(wall [s], CPU [s], standard output)`` of ``offshore-crane ARGS`` in a fresh
    process (CPU: the child's user + system time)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "offshore_crane", *args], env=env,
                         check=True, capture_output=True, text=True).stdout
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, out


def summary(runs: list[tuple[float, float, str]]) -> dict:
    """Median and range of the wall and CPU times."""
    wall, cpu = [r[0] for r in runs], [r[1] for r in runs]
    return {"wall_s": statistics.median(wall), "cpu_s": statistics.median(cpu),
            "cpu_min_s": min(cpu), "cpu_max_s": max(cpu)}


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "identification")
    parser.add_argument("--repeats", type=int, default=3, help="runs of each command (3)")
    args = parser.parse_args(argv)
    load = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        ex, log = str(Path(tmp) / "ex.csv"), str(Path(tmp) / "run.csv")
        timed(["compile"])                                    # the kernels, once
        excite = [timed(["excite", "--duration", "20", "--out", ex])
                  for _ in range(args.repeats)]
        timed(["simulate", "--trajectory", ex, *HEAVY, "--out", log])
        identify = [timed(["identify", "--log", log]) for _ in range(args.repeats)]
    line = excite[-1][2]
    cond = float(re.search(r"condition number ([\d.e+]+) \(Table 1", line).group(1))
    table1 = float(re.search(r"\(Table 1: ([\d.e+]+),", line).group(1))
    samples = int(re.search(r", (\d+) samples, t =", identify[-1][2]).group(1))
    figures = {**stamp(), "load_average": load, "repeats": args.repeats,
               "excite": summary(excite), "identify": summary(identify),
               "condition": cond, "table1_condition": table1, "log_samples": samples}
    for name in ("excite", "identify"):
        s = figures[name]
        print(f"{name:<9}: CPU {s['cpu_s']:.1f} s ({s['cpu_min_s']:.1f}-{s['cpu_max_s']:.1f}), "
              f"wall {s['wall_s']:.1f} s; median of {args.repeats}")
    print(f"excitation condition number {cond:.4g} (Table 1: {table1:.4g}); the log "
          f"{samples} samples; {os.cpu_count()} cores, load average {load:.1f}")
    if args.save:
        save("identification", figures)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
