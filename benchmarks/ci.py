"""Benchmark of the whole CI: ``bash .ci/run`` on a fresh clone of the committed tree, as
CI runs it (a fresh virtual environment, ``pip install ".[test]"``, every test, the
Numba kernels compiled cold), timed.

Saved: the total wall time (as ``.ci/run`` reports it: install and tests), the tests
passed, skipped and failed, the tests' own time (pytest's), the cold compile of the
kernels (the test session reports it), the commit, the machine's cores and the other
processes' load meanwhile (``/proc/stat`` less this run's own CPU time, in cores). CI
itself does not run this; it takes as long as CI (about ten minutes on 2 cores).

    python benchmarks/ci.py [--save]

``--save`` writes ``benchmarks/results/ci.json``, from which ``python scripts/figures.py``
writes the README's CI figure.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

from _saved import add_save_option, cpu_busy, save, stamp  # noqa: E402  (benchmarks/ is on the path)

#: pytest's last line: "1233 passed, 4 skipped, 2 warnings in 380.12s (0:06:20)".
SUMMARY = re.compile(r"=+ (.*?) in ([\d.]+)s")
COMPILE = re.compile(r"Numba kernels compiled or loaded in ([\d.]+) s")
TOTAL = re.compile(r"^CI: total (\d+) s$", re.M)


def counts(summary: str) -> dict:
    """``{"passed": 1233, "skipped": 4, ...}`` from pytest's summary words."""
    return {word: int(n) for n, word in re.findall(r"(\d+) (\w+)", summary)}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_save_option(parser, "ci")
    args = parser.parse_args()
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], check=True,
                            capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory(prefix="oc-ci-") as tmp:
        clone = Path(tmp) / "clone"
        subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
        env = {**os.environ, "CI": "true"}
        for name in ("PYTHONPATH", "VIRTUAL_ENV", "NUMBA_CACHE_DIR", "OFFSHORE_CRANE_CACHE"):
            env.pop(name, None)
        c0 = os.times()
        w0, a0 = time.perf_counter(), cpu_busy()
        proc = subprocess.run(["bash", ".ci/run"], cwd=clone, env=env, stdin=subprocess.DEVNULL,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        wall = time.perf_counter() - w0
        c1 = os.times()
        cpu = (c1.children_user + c1.children_system) - (c0.children_user + c0.children_system)
        others = max(0.0, ((cpu_busy() - a0) - cpu) / wall)
    out = proc.stdout
    (Path(tempfile.gettempdir()) / "offshore-crane-ci.log").write_text(out)
    if proc.returncode != 0:
        print(out[-3000:])
        print(f"CI failed (exit {proc.returncode}); nothing saved", file=sys.stderr)
        return 1
    summary = [m for m in SUMMARY.finditer(out)][-1]
    saved = {**stamp(), "commit": commit[:12], "total_s": int(TOTAL.search(out).group(1)),
             "wall_s": wall, "cpu_s": cpu, "others_cores": others,
             "tests": counts(summary.group(1)), "pytest_s": float(summary.group(2)),
             "compile_s": float(COMPILE.search(out).group(1))}
    print(f"CI on {commit[:12]}: {saved['total_s']} s in all, pytest {saved['pytest_s']:.0f} s "
          f"({saved['tests']}), cold compile {saved['compile_s']:.1f} s; {saved['cores']} "
          f"cores, other processes {others:.2f} core meanwhile")
    if args.save:
        save("ci", saved)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
