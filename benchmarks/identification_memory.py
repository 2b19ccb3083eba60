"""identify's memory on long logs (issue 36): a 30-minute rig log at 1 kHz under a memory
limit, and the 200 s log that took 6.9 GB before the fit was blocked.

    python benchmarks/identification_memory.py [--durations 200 1800] [--limit 2e9] [--save]

Each log: a 5-harmonic Fourier excitation (period 10 s) of the robot of ``--set
platform.mass=48 --set arm.link1.mass=4.6`` at 1 kHz, Kane's forces, in the columns
``simulate --out`` writes (t, q1..q9, q1_ref..q9_ref, T1..Fl6; no rates: ``identify``
low-passes and differentiates the positions), written as CSV. Then ``identify --log``
in a fresh process with ``OFFSHORE_CRANE_MEMORY_LIMIT=--limit``, the kernels compiled.
Measured per log: the child's peak resident set (its own ``ru_maxrss``), its CPU and wall
time, the estimate identify checked against the limit (cli/logs.py: FIXED_BYTES +
BYTES_PER_SAMPLE × rows), the CSV's size. Saved: benchmarks/results/identification_memory.json.
"""

from __future__ import annotations

import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from _saved import benchmark_parser, save, stamp  # noqa: E402  (benchmarks/ is on the path)

#: The child: identify in-process, then its own peak resident set [kB] on standard error.
CHILD = ("import resource, sys\nfrom offshore_crane.__main__ import main\n"
         "status = main(sys.argv[1:])\n"
         "print('maxrss_kb', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, "
         "file=sys.stderr)\nsys.exit(status)\n")


def write_log(path: Path, duration: float, rate: float = 1000.0) -> int:
    """The log of ``duration`` [s] at ``rate`` [Hz] (the module docstring's); its rows."""
    import numpy as np

    import offshore_crane as oc
    from offshore_crane.conventions import Q_COLUMNS, coordinate_column
    from offshore_crane.io import write_csv
    from offshore_crane.outputs.visual.motion import FORCE_COLUMNS
    from offshore_crane.studies import identification as ident

    robot = oc.load_robot()
    heavy = oc.load_robot(overrides={"platform.mass": 48.0, "arm.link1.mass": 4.6})
    ex = ident.fourier_excitation(robot, duration, rate, harmonics=5, period=10.0, seed=1)
    X = oc.inverse_dynamics(heavy, ex.q, ex.qd, ex.qdd)
    ref = tuple(coordinate_column(k, tag="_ref") for k in range(9))
    write_csv(path, ",".join(("t_s",) + Q_COLUMNS + ref + FORCE_COLUMNS),
              np.column_stack([ex.t, ex.q, ex.q, X]))
    return len(ex.t)


def identify(log: Path, limit: float) -> dict:
    """identify on ``log`` in a fresh process: its peak RSS, CPU and wall time, output."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"),
           "OFFSHORE_CRANE_MEMORY_LIMIT": repr(float(limit))}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", CHILD, "identify", "--log", str(log)],
                          env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"identify failed ({proc.returncode}): {proc.stderr.strip()}")
    rss = float(re.search(r"maxrss_kb (\d+)", proc.stderr).group(1)) * 1024.0
    samples = int(re.search(r", (\d+) samples, t =", proc.stdout).group(1))
    return {"peak_rss_bytes": rss, "cpu_s": (after.ru_utime - before.ru_utime)
            + (after.ru_stime - before.ru_stime), "wall_s": wall, "fitted_samples": samples,
            "consistent": "every body physically consistent: yes" in proc.stdout}


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "identification_memory")
    parser.add_argument("--durations", type=float, nargs="+", default=[200.0, 1800.0],
                        help="the logs' durations [s] (default 200 1800)")
    parser.add_argument("--limit", type=float, default=2e9,
                        help="OFFSHORE_CRANE_MEMORY_LIMIT of the runs [bytes] (default 2e9)")
    args = parser.parse_args(argv)
    from offshore_crane.cli.logs import BYTES_PER_SAMPLE, FIXED_BYTES

    load = os.getloadavg()[0]
    subprocess.run([sys.executable, "-m", "offshore_crane", "compile"], check=True,
                   env={**os.environ, "PYTHONPATH": str(ROOT / "src")}, capture_output=True)
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        for duration in args.durations:
            log = Path(tmp) / f"log{duration:g}.csv"
            rows = write_log(log, duration)
            r = identify(log, args.limit)
            r.update(duration_s=duration, rows=rows, csv_bytes=log.stat().st_size,
                     estimate_bytes=FIXED_BYTES + BYTES_PER_SAMPLE * rows)
            log.unlink()
            runs.append(r)
            print(f"{duration:g} s at 1 kHz ({rows} rows, {r['csv_bytes'] / 1e9:.2f} GB of "
                  f"CSV): peak RSS {r['peak_rss_bytes'] / 1e9:.2f} GB (limit "
                  f"{args.limit / 1e9:.2f} GB, estimate {r['estimate_bytes'] / 1e9:.2f} GB), "
                  f"CPU {r['cpu_s']:.0f} s, wall {r['wall_s']:.0f} s, consistent "
                  f"{r['consistent']}")
    print(f"{os.cpu_count()} cores, load average {load:.1f} at the start")
    if args.save:
        save("identification_memory", {**stamp(), "load_average": load,
                                       "limit_bytes": args.limit, "runs": runs})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
