"""Benchmark of the inverse dynamics: time per sample, error, memory, start-up, threads.

Every path is timed side by side in one run against a *floor*: Pinocchio's bare
``rneaInParallel`` on the equivalent tree (1 thread, tree states given, loops not closed),
on the same smooth multi-sine trajectory (Table 1's frequencies, N samples over N/100 s).
Ratios are judged on the minimum of repeated runs (this shared machine varies by ±20 %);
medians are reported beside them.

    python benchmarks/bench.py [--quick] [--out DIR] [--sizes N ...]

prints the tables and writes ``bench.csv`` and ``summary.md`` to DIR (default
``./bench-results``; ``--out docs/bench`` refreshes the figures the README quotes). The
targets of the issue that made the kernels one text are checked and printed.
"""

from __future__ import annotations

import argparse
import csv
import os
import platform
import statistics
import subprocess
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

import offshore_crane as oc
from offshore_crane.dynamics import solve, warm_up

SIZES = (1, 10_000, 100_000, 1_000_000)


def trajectory(n: int):
    """``n`` samples of Table 1 at 100 Hz (analytic derivatives), repeated past 20π s."""
    t = np.arange(n) / 100.0
    return oc.motion.trajectories.table1(t)


def timed(fn, budget: float, least: int = 5, most: int = 200) -> list[float]:
    """Seconds of repeated calls: at least ``least``, until ``budget`` seconds are spent."""
    fn()                                             # warm-up (caches, first touch)
    times, spent = [], 0.0
    while len(times) < least or (spent < budget and len(times) < most):
        t0 = time.perf_counter()
        fn()
        dt = time.perf_counter() - t0
        times.append(dt)
        spent += dt
    return times


def floor_call(robot, q, qd, qdd):
    """Bare rneaInParallel on precomputed tree states (the closure is not timed)."""
    import pinocchio as pin
    from offshore_crane.reference.rnea import tree_state

    Q, V, A, _, _ = tree_state(robot, q, qd, qdd)
    model = robot.pinocchio_model.copy()
    model.gravity.linear = np.array(oc.GRAVITY)
    pool = pin.ModelPool(model, 1)
    tau = np.empty_like(Q, order="F")
    return lambda: pin.rneaInParallel(1, pool, Q, V, A, tau)


def variants(robot):
    """name -> (callable(q, qd, qdd), largest N worth timing)."""
    return {
        "kane (default: checks, compiled)": (lambda *a: solve(robot, *a), None),
        "kane, no checks": (lambda *a: solve(robot, *a, checks=False, limits=False), None),
        "kane, NumPy backend": (lambda *a: solve(robot, *a, backend="numpy"), None),
        "kane, thin-rod legs": (lambda *a: solve(robot, *a, leg_model="thin-rod"), None),
        "kane, massless legs": (lambda *a: solve(robot, *a, leg_model="massless"), None),
        "kane, 2 threads": (lambda *a: solve(robot, *a, threads=2), None),
        "kane-explicit": (lambda *a: solve(robot, *a, method="kane-explicit"), None),
        "rnea reference path": (lambda *a: solve(robot, *a, method="rnea"), None),
    }


def bench_sizes(robot, sizes, budget, log) -> list[dict]:
    rows = []
    for n in sizes:
        q, qd, qdd = trajectory(n)
        floor = timed(floor_call(robot, q, qd, qdd), budget)
        fmin = min(floor) / n * 1e6
        rows.append(dict(variant="floor: rneaInParallel (1 thread, tree states given)", N=n,
                         median_us=statistics.median(floor) / n * 1e6, min_us=fmin,
                         ratio_min=1.0, ratio_median=1.0))
        for name, (fn, _) in variants(robot).items():
            ts = timed(lambda: fn(q, qd, qdd), budget)
            med, lo = statistics.median(ts) / n * 1e6, min(ts) / n * 1e6
            rows.append(dict(variant=name, N=n, median_us=med, min_us=lo, ratio_min=lo / fmin,
                             ratio_median=med / (statistics.median(floor) / n * 1e6)))
        for r in rows[-len(variants(robot)) - 1:]:
            log(f"N={n:>8}  {r['variant']:<52} median {r['median_us']:9.3f} µs  "
                f"min {r['min_us']:9.3f} µs  ÷ floor {r['ratio_min']:.2f}")
    return rows


def single_sample(robot, budget) -> dict:
    q, qd, qdd = (x[0] for x in trajectory(1))
    out = {}
    for label, kw in (("checks", {}), ("no checks", dict(checks=False, limits=False))):
        ts = timed(lambda: oc.inverse_dynamics(robot, q, qd, qdd, **kw), budget, least=2000,
                   most=20000)
        out[label] = (statistics.median(ts) * 1e6, min(ts) * 1e6)
    return out


def errors(robot) -> dict:
    """Largest relative difference of each path from the RNEA reference (10⁴ samples)
    and of the default path from the extended-precision reference (40 samples)."""
    from offshore_crane.dynamics import extended

    q, qd, qdd = trajectory(10_000)
    ref = solve(robot, q, qd, qdd, method="rnea").X
    scale = np.abs(ref).max()
    out = {name: float(np.abs(fn(q, qd, qdd).X - ref).max() / scale)
           for name, (fn, _) in variants(robot).items()}
    idx = np.linspace(0, 9999, 40).astype(int)
    refs = extended.reference(robot, q[idx], qd[idx], qdd[idx])
    out["kane vs mpmath (40 samples)"] = float(extended.relative_errors(
        solve(robot, q[idx], qd[idx], qdd[idx]).X, refs).max())
    return out


def memory(robot, n: int = 1_000_000) -> float:
    """tracemalloc peak of one default call at N = n, inputs excluded, output included,
    in doubles per sample."""
    q, qd, qdd = trajectory(n)
    solve(robot, q[:10], qd[:10], qdd[:10])
    tracemalloc.start()
    tracemalloc.reset_peak()
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    del X
    return peak / n / 8


def _cpu_busy() -> float:
    """Seconds of CPU time spent by every process of the machine (``/proc/stat``: all
    but idle and iowait), or NaN where there is no ``/proc``."""
    try:
        with open("/proc/stat") as fh:
            fields = [int(x) for x in fh.readline().split()[1:]]
    except OSError:
        return float("nan")
    busy = sum(fields) - fields[3] - (fields[4] if len(fields) > 4 else 0)
    return busy / os.sysconf("SC_CLK_TCK")


def threads(robot, budget, n: int = 1_000_000) -> dict:
    """Speed-up of 2 threads over 1, and how busy the rest of the machine was meanwhile.

    The load average would count this benchmark itself (one busy core, then two), so the
    machine counts as *otherwise idle* when the CPU time of every other process during the
    measurement, from ``/proc/stat`` minus this process's own, averages below 0.5 core
    (the issue's load < 0.5)."""
    q, qd, qdd = trajectory(n)
    wall0, mine0, all0 = time.perf_counter(), sum(os.times()[:2]), _cpu_busy()
    one = timed(lambda: solve(robot, q, qd, qdd), budget)
    two = timed(lambda: solve(robot, q, qd, qdd, threads=2), budget)
    others = ((_cpu_busy() - all0) - (sum(os.times()[:2]) - mine0)) / (
        time.perf_counter() - wall0)
    same = np.array_equal(solve(robot, q, qd, qdd).X, solve(robot, q, qd, qdd, threads=2).X)
    return dict(load=max(others, 0.0), speedup_min=min(one) / min(two),
                speedup_median=statistics.median(one) / statistics.median(two),
                identical=same, measurable=bool(others < 0.5))


def startup(repeat: int = 7) -> dict:
    exe = Path(sys.executable).with_name("offshore-crane")
    out = {}
    for label, cmd in (("python -c 'import numpy'", [sys.executable, "-c", "import numpy"]),
                       ("offshore-crane id --trajectory table1",
                        [str(exe), "id", "--trajectory", "table1"])):
        ts = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            ts.append(time.perf_counter() - t0)
        out[label] = (statistics.median(ts), min(ts))
    return out


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="short budgets, N up to 1e5")
    p.add_argument("--out", default="bench-results", help="output folder")
    p.add_argument("--sizes", type=int, nargs="+")
    args = p.parse_args(argv)
    budget = 0.3 if args.quick else 2.0
    sizes = args.sizes or (SIZES[:3] if args.quick else SIZES)
    robot = oc.load_robot()
    compile_times = warm_up(robot)
    log = print
    info = dict(date=time.strftime("%Y-%m-%d %H:%M"), machine=platform.processor() or
                platform.machine(), cores=os.cpu_count(), python=platform.python_version(),
                numpy=np.__version__, load=os.getloadavg()[0])
    log(f"machine: {info}")
    rows = bench_sizes(robot, sizes, budget, log)
    single = single_sample(robot, budget)
    errs = errors(robot)
    mem = memory(robot, max(sizes))
    thr = threads(robot, budget, max(sizes))
    start = startup()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "bench.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    big = [n for n in sizes if n >= 10_000]

    def r(name, n):
        return next(x for x in rows if x["variant"] == name and x["N"] == n)

    kane = "kane (default: checks, compiled)"
    numpy_t, cli_t = start["python -c 'import numpy'"], start["offshore-crane id --trajectory table1"]
    targets = [
        ("Kane with checks ≤ 0.5 × floor (N = " + ", ".join(f"{n:g}" for n in big) + ")",
         " / ".join(f"{r(kane, n)['ratio_min']:.2f}" for n in big),
         all(r(kane, n)["ratio_min"] <= 0.5 for n in big)),
        ("RNEA reference path ≤ 3 × floor", " / ".join(
            f"{r('rnea reference path', n)['ratio_min']:.2f}" for n in big),
         all(r("rnea reference path", n)["ratio_min"] <= 3 for n in big)),
        ("one sample ≤ 40 µs with checks", f"{single['checks'][0]:.1f} µs median, "
         f"{single['checks'][1]:.1f} min", single["checks"][0] <= 40),
        ("one sample ≤ 15 µs without checks", f"{single['no checks'][0]:.1f} µs median, "
         f"{single['no checks'][1]:.1f} min", single["no checks"][0] <= 15),
        ("CLI ≤ 3 × python -c 'import numpy'", f"{cli_t[1]:.3f} s vs {numpy_t[1]:.3f} s = "
         f"{cli_t[1] / numpy_t[1]:.2f} × (min)", cli_t[1] <= 3 * numpy_t[1]),
        (f"memory ≤ 20 doubles per sample (N = {max(sizes):g})", f"{mem:.1f}", mem <= 20),
        ("2 threads ≥ 1.6 × (idle machine)", f"{thr['speedup_min']:.2f} × (min), "
         f"{thr['speedup_median']:.2f} × (median), other processes {thr['load']:.2f} "
         f"core on average, bit-identical "
         f"{thr['identical']}", (thr["speedup_min"] >= 1.6 and thr["identical"])
         if thr["measurable"] else "not measurable (others ≥ 0.5 core)"),
        ("cold compile of every kernel ≤ 120 s (this run: "
         + ("warm cache" if sum(s for _, s in compile_times) < 10 else "cold") + ")",
         ", ".join(f"{n} {s:.1f} s" for n, s in compile_times), None),
    ]
    lines = [f"# Benchmark {info['date']}", "",
             f"{info['machine']}, {info['cores']} cores, Python {info['python']}, NumPy "
             f"{info['numpy']}, load average {info['load']:.2f} at the start.", "",
             "| variant | " + " | ".join(f"N = {n:g}" for n in sizes) + " | ÷ floor (min) |",
             "| --- | " + " | ".join("---" for _ in sizes) + " | --- |"]
    for name in ["floor: rneaInParallel (1 thread, tree states given)", *variants(robot)]:
        cells = [f"{r(name, n)['median_us']:.2f} ({r(name, n)['min_us']:.2f})" for n in sizes]
        ratios = " / ".join(f"{r(name, n)['ratio_min']:.2f}" for n in big)
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {ratios} |")
    lines += ["", "µs per sample, median (minimum).", "", "| error (max relative) | value |",
              "| --- | --- |"]
    lines += [f"| {k} vs RNEA reference | {v:.1e} |" if "mpmath" not in k else
              f"| {k} | {v:.1e} |" for k, v in errs.items()]
    lines += ["", "| target | measured | met |", "| --- | --- | --- |"]
    lines += [f"| {a} | {b} | {c} |" for a, b, c in targets]
    text = "\n".join(lines) + "\n"
    (out / "summary.md").write_text(text)
    print()
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
