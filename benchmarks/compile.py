"""Benchmark of the cold compile of the Numba kernels: the whole set in one process, and
with ``offshore-crane compile`` (its kernel groups in parallel processes, one per core);
and the wait of a first ``simulate`` on a cold cache (the rigid robot along Table 1, the
elastic compensated lift), which issue 37 asks to be at most 15 s and told ahead.

Each run starts from nothing compiled, as a fresh install does: the package's sources
are copied to a new temporary folder (Numba caches beside them, the generated block
programs in their ``__pycache__``; ``models/`` and ``scenes/`` linked beside them as in a
checkout) with an empty URDF cache, and the compile runs in a
new Python process on that copy. Measured: the wall time, the CPU time of the process
and its children, the machine's cores and the other processes' load meanwhile (read from
``/proc/stat``: every process's CPU time minus the benchmark's children's, in cores),
since on a shared machine the same compile takes twice as long when the cores are busy.

    python benchmarks/compile.py [--save]

``--save`` writes ``benchmarks/results/compile.json``, from which ``python
scripts/figures.py`` writes the compile figures of README.md, and the package's table of
cold compile times (``src/offshore_crane/compile_times.json``: each kernel that started a
compile in these runs, and how long that compile took), from which a first compile on a
machine without its own record says how long it will wait
(:mod:`offshore_crane.compile_times`).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

from _saved import add_save_option, cpu_busy, save, stamp  # noqa: E402  (benchmarks/ is on the path)

#: The two ways of compiling, as Python code run in a fresh process on a fresh copy.
#: Both print one line ``NAME: SECONDS s`` per kernel as it is ready.
WAYS = {
    "one_process": "from offshore_crane.cli.compile import compile_all; "
                   "[print(f'{n}: {s:.1f} s') for n, s in compile_all(jobs=1)]",
    "parallel": "from offshore_crane.__main__ import main; raise SystemExit(main(['compile']))",
}
#: First commands on a cold cache (run in the copy's folder, output dropped): the wait
#: of a user's first simulation.
FIRST = {
    "first_simulate": ["simulate", "--trajectory", "table1", "--duration", "1"],
    "first_simulate_elastic": ["simulate", "--scene", "scenes/compensated_lift.toml",
                               "--duration", "1"],
    "first_simulate_hanging": ["simulate", "--scene", "scenes/hanging_load.toml",
                               "--duration", "1"],
}
#: The issue's bound on a first simulate's wait [s].
FIRST_TARGET = 15.0
PACKAGE_TABLE = ROOT / "src" / "offshore_crane" / "compile_times.json"
KERNEL_LINE = re.compile(r"^(.+): (\d+(?:\.\d+)?) s$", re.M)


def children_cpu() -> float:
    """CPU seconds of this process's finished children."""
    t = os.times()
    return t.children_user + t.children_system


def cold_compile(code: str) -> dict:
    """Run ``code`` in a new process on a fresh copy of the sources: wall and CPU [s],
    other processes' load [cores], each kernel group's own compile time [s] as the
    process reported it, and the copy's compile-time record (``records``: the kernels
    that started a compile and how long it took, :mod:`offshore_crane.compile_times`)."""
    with tempfile.TemporaryDirectory(prefix="oc-compile-") as tmp:
        src = Path(tmp) / "src"
        shutil.copytree(ROOT / "src" / "offshore_crane", src / "offshore_crane",
                        ignore=shutil.ignore_patterns("__pycache__"))
        for shared in ("models", "scenes"):            # read where a source checkout has them
            (Path(tmp) / shared).symlink_to(ROOT / shared)
        env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
        env.update(PYTHONPATH=str(src), OFFSHORE_CRANE_CACHE=str(Path(tmp) / "urdf"),
                   PYTHONDONTWRITEBYTECODE="1", XDG_CACHE_HOME=str(Path(tmp) / "xdg"))
        w0, c0, a0 = time.perf_counter(), children_cpu(), cpu_busy()
        out = subprocess.run([sys.executable, "-c", code], env=env, check=True, cwd=tmp,
                             stdout=subprocess.PIPE, text=True).stdout
        wall = time.perf_counter() - w0
        cpu = children_cpu() - c0
        others = max(0.0, ((cpu_busy() - a0) - cpu) / wall)
        record = Path(tmp) / "xdg" / "offshore-crane" / "compile_times.json"
        records = json.loads(record.read_text())["kernels"] if record.exists() else {}
    kernels = {m.group(1): float(m.group(2)) for m in KERNEL_LINE.finditer(out)}
    return {"wall_s": wall, "cpu_s": cpu, "others_cores": others, "kernels": kernels,
            "records": records}


def machine() -> str:
    """The machine in words: its cores and CPU model (``/proc/cpuinfo``)."""
    model = ""
    try:
        found = re.search(r"^model name\s*:\s*(.+)$", Path("/proc/cpuinfo").read_text(), re.M)
        model = f", {found.group(1).strip()}" if found else ""
    except OSError:
        pass
    return f"a {os.cpu_count()}-core machine{model}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_save_option(parser, "compile")
    args = parser.parse_args()
    saved = stamp()
    for name, code in WAYS.items():
        saved[name] = cold_compile(code)
        r = saved[name]
        print(f"{name}: {', '.join(f'{k} {s:.1f} s' for k, s in r['kernels'].items())}")
        print(f"{name}: {r['wall_s']:.1f} s ({r['cpu_s']:.1f} s of CPU; other processes "
              f"used {r['others_cores']:.2f} of {saved['cores']} cores meanwhile)",
              flush=True)
    for name, argv in FIRST.items():
        code = ("import sys, contextlib, io; from offshore_crane.__main__ import main\n"
                f"with contextlib.redirect_stdout(io.StringIO()): code = main({argv!r})\n"
                "raise SystemExit(code)")
        saved[name] = r = cold_compile(code)
        print(f"{name} ({' '.join(argv)}): {r['wall_s']:.1f} s on a cold cache (other "
              f"processes used {r['others_cores']:.2f} cores; target <= {FIRST_TARGET:g} "
              f"s: {'met' if r['wall_s'] <= FIRST_TARGET else 'NOT met'})", flush=True)
    if args.save:
        save("compile", saved)
        table = {}
        for name in (*WAYS, *FIRST):                 # a first command's own wait wins
            table.update(saved[name]["records"])
        PACKAGE_TABLE.write_text(json.dumps({"date": saved["date"], "machine": machine(),
                                             "kernels": table}, indent=1, sort_keys=True)
                                 + "\n")
        print(f"wrote {PACKAGE_TABLE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
