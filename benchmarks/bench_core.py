"""``offshore-crane bench``: run time against error for every inverse-dynamics path.

For the full crane on the paper's Table 1 (sampled at 100 Hz, ``t = k / 100`` s, so N
samples span N/100 s, many periods for large N), the time per sample [µs] (median, min
and max of repeated runs) for N = 1, 10, ..., 10⁶ of:

- ``kane``: :func:`offshore_crane.dynamics.solve` as is (exact, checks and limits on);
- ``kane (no checks)``: the same with ``checks=False, limits=False``;
- ``kane thin-rod``, ``kane massless``: the leg-model approximations (checks on);
- ``kane-explicit``: ``method="kane-explicit"``; ``rnea path``: ``method="rnea"``;
- ``kane (numpy backend)``, ``rnea path (numpy backend)``: ``backend="numpy"``, what
  runs without Numba (the two above use Numba when it is installed);
- ``kane float32 kernel``: the NumPy kernel on float32 inputs and constants
  (:func:`..dynamics.fused.prepare` with ``np.float32``);
- ``floor: rneaInParallel``: Pinocchio's bare ``rneaInParallel`` (1 thread) on the
  equivalent tree with tree states computed beforehand (:func:`..dynamics.rnea.tree_state`,
  outside the timing). It does not close the loops: it is the floor to beat, not a solver;
- ``kane public API (9,)``: :func:`offshore_crane.inverse_dynamics` on one ``(9,)`` sample
  (N = 1 only).

Above ``stream`` samples (default 10⁵) every variant is run chunk by chunk on views of
the inputs, so its working memory stays O(chunk); the peak memory of one call is
measured with :mod:`tracemalloc` (NumPy and Python allocations; Numba's and Pinocchio's
internal scratch memory is not traced and is O(1) per call).

The error axis compares each variant's X with a reference on the same samples (max
relative error ``max |ΔX| / max |X_ref|``): the RNEA path in float64 for the solvers;
the exact variants also against each other and, on the first samples, against the
extended-precision reference of :mod:`..dynamics.extended` (mpmath) when available; for
a trajectory given only as sampled q (CSV at 1 kHz, 200, 100 and 50 Hz, derivatives by
finite differences of order 2, 4 and 6), Kane's X against Kane's with the analytic
derivatives at the same times: the error a user gets from their own sampled data.

Outputs (in ``--out DIR``): ``bench.csv`` (all timing points), ``errors.csv``,
``pareto.png`` (time per sample against max relative error, log-log), ``summary.md``
(a short table for the README and the targets of issue 5, met or not, computed from the
numbers), ``profiles.txt`` (cProfile of ``solve`` at N = 10⁴, of the public API at
N = 1, and of a cold ``offshore-crane id`` process). Speed never sets the exit status;
exit status 1 means the default path is not exact (Kane vs RNEA above 1e-9).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

SIZES = (1, 10, 100, 1_000, 10_000, 100_000, 1_000_000)
QUICK_SIZES = (1, 10, 100, 1_000, 10_000)
#: Sampling rate of Table 1 in the timing sweep [Hz].
RATE = 100.0
GRAVITY = (0.0, 0.0, -9.81)
FD_RATES = (1000.0, 200.0, 100.0, 50.0)
FD_ORDERS = (2, 4, 6)
#: Table 1 repeats after 20π s (q7, q8 at 0.5 rad/s, the rest at 0.2 and 0.4 rad/s).
FD_DURATION = 20.0 * math.pi
FLOOR = "floor: rneaInParallel"
API = "kane public API (9,)"
EXACT_LIMIT = 1e-9
#: Targets of issue 5: Kane and the RNEA path against the floor (N ≥ 10⁴), one sample
#: through the public API [µs], start-up against ``python -c "import numpy"``.
TARGETS = {"kane_over_floor": 0.5, "rnea_over_floor": 2.0, "api_us": 100.0,
           "startup_over_numpy": 3.0, "exact": EXACT_LIMIT}


@dataclass(frozen=True)
class Config:
    """What to measure and how long to spend.

    Attributes:
        sizes: Sample counts N of the timing sweep.
        target_s: Aim for each timing point to take about this long in total [s].
        min_repeats, max_repeats: Bounds on the timed calls per point.
        budget_s: Skip a point whose single call is estimated (from the variant's time
            per sample at the previous N) above this [s].
        stream: Above this N, variants run chunk by chunk (chunks of ``stream``).
        error_n: Samples of the error comparison (and of the Pareto plot's time axis).
        extended_n: Samples compared with the extended-precision reference (0: none).
        fd_rates, fd_orders, fd_duration: The sampled-data study: rates [Hz], orders,
            span [s].
        startup_runs: Cold processes per start-up command (0: skip start-up).
        profile: Write cProfile tables (``profiles.txt``).
        only: Run only variants whose name contains one of these (the floor always runs).
        out: Output directory.
    """

    sizes: tuple = SIZES
    target_s: float = 0.5
    min_repeats: int = 5
    max_repeats: int = 2000
    budget_s: float = 10.0
    stream: int = 100_000
    error_n: int = 10_000
    fd_rates: tuple = FD_RATES
    fd_orders: tuple = FD_ORDERS
    fd_duration: float = FD_DURATION
    extended_n: int = 64
    startup_runs: int = 5
    profile: bool = True
    only: tuple = ()
    out: Path = Path("bench")


QUICK = dict(sizes=QUICK_SIZES, target_s=0.05, min_repeats=3, max_repeats=50, startup_runs=3,
             fd_duration=10.0 * math.pi)


# --------------------------------------------------------------------------- inputs
def table1_samples(n: int):
    """Table 1 at ``t = k / RATE``, ``k = 0..n-1``: ``t (n,)`` [s], ``q, qd, qdd (n, 9)``."""
    import numpy as np

    from .trajectories import table1

    t = np.arange(n) / RATE
    return (t, *table1(t))


class Context:
    """The robot, Table 1 inputs for the largest N and buffers shared by the variants.

    Smaller N use the first N samples (views), so every variant sees the same data.
    """

    def __init__(self, robot, n_max: int, stream: int):
        import numpy as np

        self.robot = robot
        self.n_max = n_max
        self.stream = stream
        self.t, self.q, self.qd, self.qdd = table1_samples(n_max)
        self.out = np.empty((n_max, 9))
        self._cache: dict = {}
        self.notes: list[str] = []

    def cached(self, key, build):
        if key not in self._cache:
            self._cache[key] = build()
        return self._cache[key]

    def streamed(self, n: int, call, out=None):
        """``call(slice) -> (m, 9)`` on rows ``[0, n)``, chunk by chunk above ``stream``."""
        if n <= self.stream:
            return call(slice(0, n))
        out = self.out if out is None else out
        for s in range(0, n, self.stream):
            sl = slice(s, min(s + self.stream, n))
            out[sl] = call(sl)
        return out[:n]


def tree_arrays(robot, q, qd, qdd, chunk: int = 50_000):
    """Tree positions, rates, accelerations as Fortran ``(nv, N)`` arrays.

    Computed by :func:`..dynamics.rnea.tree_state` chunk by chunk (its leg arrays are
    ~1 kB per sample).
    """
    import numpy as np

    from .dynamics.rnea import tree_state

    N = q.shape[0]
    nv = robot.pinocchio_model.nv
    Q, V, A = (np.empty((nv, N), order="F") for _ in range(3))
    for s in range(0, N, chunk):
        sl = slice(s, min(s + chunk, N))
        qt, vt, at, _, _ = tree_state(robot, q[sl], qd[sl], qdd[sl])
        Q[:, sl], V[:, sl], A[:, sl] = qt.T, vt.T, at.T
    return Q, V, A


# --------------------------------------------------------------------------- variants
@dataclass(frozen=True)
class Variant:
    """A timed path: ``make(ctx)`` returns ``run(n)``, which computes the first n samples.

    Attributes:
        name: Label in the tables and the plot.
        group: ``"exact"``, ``"approximation"``, ``"floor"`` or ``"api"``.
        make: ``make(ctx) -> run``; ``run(n)`` returns X ``(n, 9)`` (the floor: τ ``(nv, n)``).
        sizes: Restrict to these N (None: all).
        note: What is timed.
    """

    name: str
    group: str
    make: object
    sizes: tuple | None = None
    note: str = ""


def _solve(**kw):
    def make(ctx):
        from .dynamics import solve

        r = ctx.robot
        return lambda n: ctx.streamed(
            n, lambda sl: solve(r, ctx.q[sl], ctx.qd[sl], ctx.qdd[sl], **kw).X)
    return make


def _float32_kernel(ctx):
    import numpy as np

    from .dynamics.fused import Options, fused_inverse_dynamics, prepare

    fd, opts = prepare(ctx.robot.hybrid, np.float32), Options()
    q, qd, qdd = ctx.cached("float32", lambda: tuple(
        x.astype(np.float32) for x in (ctx.q, ctx.qd, ctx.qdd)))
    out = np.empty((ctx.n_max, 9), dtype=np.float32)
    return lambda n: ctx.streamed(n, lambda sl: fused_inverse_dynamics(
        fd, q[sl], qd[sl], qdd[sl], GRAVITY, opts)[0], out)


def _floor(ctx):
    import numpy as np
    import pinocchio as pin

    t0 = time.perf_counter()
    Q, V, A = ctx.cached("tree", lambda: tree_arrays(ctx.robot, ctx.q, ctx.qd, ctx.qdd))
    ctx.notes.append(f"floor: tree states of {ctx.n_max} samples by rnea.tree_state in "
                     f"{time.perf_counter() - t0:.1f} s (not timed), "
                     f"{4 * Q.nbytes / 1e6:.0f} MB for Q, V, A, τ")
    TAU = np.empty_like(Q, order="F")
    model = ctx.robot.pinocchio_model.copy()
    model.gravity.linear = np.asarray(GRAVITY, dtype=float)
    pool = pin.ModelPool(model, 1)

    def run(n):
        step = n if n <= ctx.stream else ctx.stream
        for s in range(0, n, step):
            e = min(s + step, n)
            pin.rneaInParallel(1, pool, Q[:, s:e], V[:, s:e], A[:, s:e], TAU[:, s:e])
        return TAU[:, :n]
    return run


def _api(ctx):
    from . import inverse_dynamics

    r, q, qd, qdd = ctx.robot, ctx.q[0].copy(), ctx.qd[0].copy(), ctx.qdd[0].copy()
    return lambda n: inverse_dynamics(r, q, qd, qdd)


VARIANTS = (
    Variant("kane", "exact", _solve(), note="solve(): exact, checks and limits"),
    Variant("kane (no checks)", "exact", _solve(checks=False, limits=False),
            note="solve(checks=False, limits=False)"),
    Variant("kane thin-rod", "approximation", _solve(leg_model="thin-rod"),
            note="solve(leg_model='thin-rod')"),
    Variant("kane massless", "approximation", _solve(leg_model="massless"),
            note="solve(leg_model='massless')"),
    Variant("kane-explicit", "exact", _solve(method="kane-explicit"),
            note="solve(method='kane-explicit')"),
    Variant("rnea path", "exact", _solve(method="rnea"),
            note="solve(method='rnea'): tree states + RNEA + projection"),
    Variant("kane (numpy backend)", "exact", _solve(backend="numpy"),
            note="solve(backend='numpy'): what runs without Numba"),
    Variant("rnea path (numpy backend)", "exact", _solve(method="rnea", backend="numpy"),
            note="solve(method='rnea', backend='numpy'): what runs without Numba"),
    Variant("kane float32 kernel", "approximation", _float32_kernel,
            note="prepare(float32) + fused_inverse_dynamics (NumPy kernel) on float32 "
                 "inputs, no checks"),
    Variant(FLOOR, "floor", _floor,
            note="pin.rneaInParallel(1 thread) on pre-computed tree states; no loop closure"),
    Variant(API, "api", _api, sizes=(1,), note="inverse_dynamics(robot, q, qd, qdd), (9,)"),
)


# --------------------------------------------------------------------------- timing
def _warm(fn, est: float | None) -> float:
    """Call ``fn()`` once unless it is estimated above 0.5 s (then the variant was warmed
    at a smaller N); return the estimated time of one call [s]."""
    if est is None or est < 0.5:
        t0 = time.perf_counter()
        fn()
        est = time.perf_counter() - t0
    return est


def _repeats(est: float, cfg: Config) -> int:
    """Timed calls aiming at ``cfg.target_s`` in all, within the configured bounds."""
    return int(min(cfg.max_repeats,
                   max(cfg.min_repeats, math.ceil(cfg.target_s / max(est, 1e-9)))))


def time_call(fn, est: float | None, cfg: Config) -> list[float]:
    """Wall times [s] of repeated calls of ``fn()`` (garbage collector off), after a
    warm-up call (see :func:`_warm`)."""
    est = _warm(fn, est)
    return time_round_robin([(fn, _repeats(est, cfg), est)])[0]


#: Round-robin turn length [s]: short calls run in blocks of about this long.
TURN_S = 0.02


def time_round_robin(jobs) -> list[list[float]]:
    """Wall times [s] of each call of ``[(fn, repeats, estimated seconds per call), ...]``.

    The jobs take turns, so that all see the same machine load: a turn is one call of a
    long job, or a block of about :data:`TURN_S` of consecutive calls of a short one,
    preceded by one untimed call (caches and branch predictors warm again after the
    other jobs, as they are for a caller that repeats the same call). Garbage collector
    off.
    """
    import gc

    times = [[] for _ in jobs]
    enabled = gc.isenabled()
    gc.disable()
    try:
        while any(len(out) < reps for (_, reps, _), out in zip(jobs, times)):
            for (fn, reps, est), out in zip(jobs, times):
                block = min(reps - len(out), max(1, int(TURN_S / max(est, 1e-9))))
                if block <= 0:
                    continue
                if block > 1:
                    fn()
                for _ in range(block):
                    t0 = time.perf_counter()
                    fn()
                    out.append(time.perf_counter() - t0)
    finally:
        if enabled:
            gc.enable()
    return times


def peak_memory(fn) -> float:
    """Peak traced memory [MB] allocated during one call of ``fn()`` (:mod:`tracemalloc`)."""
    import tracemalloc

    tracemalloc.start()
    try:
        fn()
        return tracemalloc.get_traced_memory()[1] / 1e6
    finally:
        tracemalloc.stop()


def sweep(ctx: Context, variants, cfg: Config, log=print) -> tuple[list[dict], dict]:
    """Time every variant at every N.

    For each N, all variants are timed in turns (:func:`time_round_robin`, each with its
    own number of repeats), so that they are measured side by side under the same load.
    Returns the rows of ``bench.csv`` and ``{name: run}``.
    """
    import statistics

    runs = {}
    for v in variants:          # build, then prime (Numba cache loads, first-call setup)
        runs[v.name] = v.make(ctx)
        sizes = [n for n in cfg.sizes if v.sizes is None or n in v.sizes]
        for _ in range(2 if sizes else 0):
            runs[v.name](min(sizes))
    per_sample: dict = {}
    largest: dict = {}
    rows = []
    log(f"{'variant':<24}{'N':>9}{'median':>11}{'min':>11}{'max':>11}{'reps':>6}"
        f"{'/floor':>8}   [µs per sample]")
    for n in cfg.sizes:
        this, batch, jobs = [], [], []
        for v in variants:
            if v.sizes is not None and n not in v.sizes:
                continue
            est = per_sample.get(v.name)
            est = None if est is None else est * n
            row = dict(variant=v.name, group=v.group, N=n, median_us=math.nan,
                       min_us=math.nan, max_us=math.nan, repeats=0,
                       ratio_to_floor=math.nan, ratio_min_to_floor=math.nan,
                       streamed=n > ctx.stream, peak_MB=math.nan, skipped="")
            rows.append(row)
            this.append(row)
            if est is not None and est > cfg.budget_s:
                row["skipped"] = f"estimated {est:.0f} s per call > budget {cfg.budget_s:g} s"
                continue
            fn = (lambda run: lambda: run(n))(runs[v.name])
            batch.append(row)
            est = _warm(fn, est)
            jobs.append((fn, _repeats(est, cfg), est))
        for row, times in zip(batch, time_round_robin(jobs)):
            us = [1e6 * x / n for x in times]
            row.update(median_us=statistics.median(us), min_us=min(us), max_us=max(us),
                       repeats=len(us))
            per_sample[row["variant"]] = row["median_us"] * 1e-6
            largest[row["variant"]] = row
        floor = next((r for r in batch if r["variant"] == FLOOR), None)
        for row in this:
            if floor is not None and row["repeats"]:
                row["ratio_to_floor"] = row["median_us"] / floor["median_us"]
                row["ratio_min_to_floor"] = row["min_us"] / floor["min_us"]
            if row["skipped"]:
                log(f"{row['variant']:<24}{n:>9}   skipped: {row['skipped']}")
            else:
                log(f"{row['variant']:<24}{n:>9}{row['median_us']:>11.3f}"
                    f"{row['min_us']:>11.3f}{row['max_us']:>11.3f}{row['repeats']:>6}"
                    f"{row['ratio_to_floor']:>8.2f}", flush=True)
    for name, row in largest.items():   # memory of one call at the largest N measured
        row["peak_MB"] = peak_memory(lambda: runs[name](row["N"]))
    return rows, runs


# --------------------------------------------------------------------------- errors
def rel_error(X, ref) -> float:
    """``max |X − ref| / max |ref|`` over all samples and actuators."""
    import numpy as np

    X, ref = np.asarray(X, dtype=float), np.asarray(ref, dtype=float)
    return float(np.abs(X - ref).max() / np.abs(ref).max())


def _us_at(rows, name, n):
    for r in rows:
        if r["variant"] == name and r["N"] == n and r["repeats"]:
            return r["median_us"]
    return None


def errors(ctx: Context, runs: dict, rows: list, cfg: Config, log=print) -> list[dict]:
    """The error table: each variant against its reference on ``cfg.error_n`` samples.

    Rows with ``primary=True`` (each variant once, against the RNEA path, or for the RNEA
    path against explicit Kane, or for sampled data against Kane with analytic
    derivatives) are the Pareto plot's points; the others cross-check.
    """
    import statistics
    import tempfile

    import numpy as np

    from . import trajectories
    from .dynamics import solve

    n = cfg.error_n
    X = {name: np.array(runs[name](n), dtype=float, copy=True)
         for name in runs if name not in (FLOOR, API)}

    def us(name):
        u = _us_at(rows, name, n)
        if u is None:
            u = 1e6 * statistics.median(time_call(lambda: runs[name](n), None, cfg)) / n
        return u

    out = []

    def add(variant, reference, group, primary, note=""):
        out.append(dict(variant=variant, reference=reference, group=group,
                        max_rel_error=rel_error(X[variant], X[reference]),
                        us_per_sample=us(variant), N=n, primary=primary, note=note,
                        fd_us_per_sample=math.nan, csv_read_us_per_sample=math.nan))

    ref = "rnea path"
    group = {v.name: v.group for v in VARIANTS}
    if ref in X:                    # each variant against the RNEA path (Pareto points)
        for name in X:
            if name != ref:
                add(name, ref, group[name], True)
        other = next((o for o in ("kane-explicit", "kane") if o in X), None)
        if other:
            add(ref, other, "exact", True)
    exact = [name for name in X if group[name] == "exact" and name != ref]
    for i, a in enumerate(exact):   # the exact variants against each other
        for b in exact[i + 1:]:
            add(a, b, "exact", False, "cross-check")
    for approx in ("kane thin-rod", "kane massless"):
        if approx in X and "kane" in X:
            add(approx, "kane", "approximation", False, "approximation alone")
    if "kane float32 kernel" in X and "kane (numpy backend)" in X:
        add("kane float32 kernel", "kane (numpy backend)", "approximation", False,
            "precision alone (the same kernel in float64)")

    # extended precision (mpmath, :mod:`..dynamics.extended`) on the first samples
    if cfg.extended_n:
        try:
            from .dynamics.extended import DPS, reference, to_float
        except ImportError:          # module or mpmath absent: no extended reference
            log("no extended-precision reference (offshore_crane.dynamics.extended or "
                "mpmath missing)")
        else:
            m = min(cfg.extended_n, n)
            Xe = to_float(reference(ctx.robot, ctx.q[:m], ctx.qd[:m], ctx.qdd[:m], GRAVITY))
            label = f"extended precision (mpmath, {DPS} digits), first {m} samples"
            for name in X:
                out.append(dict(variant=name, reference=label, group=group[name],
                                max_rel_error=rel_error(X[name][:m], Xe),
                                us_per_sample=us(name), N=m, primary=False,
                                note="reference rounded to float64", fd_us_per_sample=math.nan,
                                csv_read_us_per_sample=math.nan))

    # sampled data: Table 1 q written to CSV, read back, derivatives by finite differences
    if cfg.fd_rates:
        kane_us = us("kane") if "kane" in X else None
        with tempfile.TemporaryDirectory(prefix="offshore-crane-bench-") as tmp:
            for rate in cfg.fd_rates:
                t = trajectories.time_grid(cfg.fd_duration, rate)
                q, qd, qdd = trajectories.table1(t)
                path = Path(tmp) / f"table1_{rate:g}Hz.csv"
                trajectories.write_csv(path, t, q)
                X_ref = solve(ctx.robot, q, qd, qdd).X
                for order in cfg.fd_orders:
                    t0 = time.perf_counter()
                    traj = trajectories.load(path, fd_order=order)
                    load_s = time.perf_counter() - t0
                    fd_s = statistics.median(time_call(
                        lambda: trajectories.finite_difference(traj.t, traj.q, order),
                        None, replace(cfg, target_s=min(cfg.target_s, 0.1), max_repeats=20)))
                    Xfd = solve(ctx.robot, traj.q, traj.qd, traj.qdd).X
                    N = len(t)
                    name = f"CSV q @ {rate:g} Hz, FD{order}"
                    fd_us = 1e6 * fd_s / N
                    out.append(dict(
                        variant=name, reference="kane, analytic derivatives", group="data",
                        max_rel_error=rel_error(Xfd, X_ref),
                        us_per_sample=(kane_us or math.nan) + fd_us, N=N, primary=True,
                        note=f"{N} samples over {cfg.fd_duration:.4g} s; time = kane at "
                             f"N={n} + finite differences", fd_us_per_sample=fd_us,
                        csv_read_us_per_sample=1e6 * max(load_s - fd_s, 0.0) / N))
    for r in out:
        log(f"{r['variant']:<26} vs {r['reference']:<28} {r['max_rel_error']:>10.2e}"
            f"  {r['us_per_sample']:>9.3f} µs/sample")
    return out


# --------------------------------------------------------------------------- start-up
def _child_env() -> dict:
    """The environment of child processes, with this package importable."""
    env = dict(os.environ)
    src = str(Path(__file__).resolve().parents[1])
    env["PYTHONPATH"] = src + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


def console_script() -> str | None:
    """The installed ``offshore-crane`` script: next to the interpreter, or on PATH."""
    import shutil

    here = Path(sys.executable).parent / "offshore-crane"
    return str(here) if here.is_file() else shutil.which("offshore-crane")


def startup(cfg: Config, log=print) -> list[dict]:
    """Wall time [s] of cold processes: ``offshore-crane id --trajectory table1`` and
    ``python -c "import numpy"`` (``cfg.startup_runs`` each, after one untimed run of each
    that also fills the URDF and Numba caches and the OS file cache)."""
    import statistics
    import subprocess

    env = _child_env()
    cmds = [("python -c \"import numpy\"", [sys.executable, "-c", "import numpy"]),
            ("python -m offshore_crane id --trajectory table1",
             [sys.executable, "-m", "offshore_crane", "id", "--trajectory", "table1"])]
    script = console_script()
    if script:
        cmds.append(("offshore-crane id --trajectory table1",
                     [script, "id", "--trajectory", "table1"]))
    else:
        log("start-up: no installed 'offshore-crane' console script found; "
            "timing 'python -m offshore_crane' only")
    rows = []
    for label, cmd in cmds:
        # one untimed run warms the caches; a failing command is reported, not timed
        res = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             text=True)
        if res.returncode:
            last = (res.stderr.strip().splitlines() or ["?"])[-1]
            log(f"start-up: '{label}' failed with status {res.returncode}: {last}")
            continue
        times = []
        for _ in range(cfg.startup_runs):
            t0 = time.perf_counter()
            subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
            times.append(time.perf_counter() - t0)
        rows.append(dict(command=label, median_s=statistics.median(times), min_s=min(times),
                         max_s=max(times), runs=len(times)))
    if len(rows) < 2 or not rows[0]["command"].startswith("python -c"):
        return []
    base = rows[0]["median_s"]
    for r in rows:
        r["ratio_to_numpy"] = r["median_s"] / base
        log(f"start-up {r['command']:<48} median {r['median_s'] * 1e3:7.0f} ms "
            f"(min {r['min_s'] * 1e3:.0f}, max {r['max_s'] * 1e3:.0f}), "
            f"{r['ratio_to_numpy']:.2f} × import numpy")
    return rows


# --------------------------------------------------------------------------- profiles
def _pstats_text(prof, sort: str, limit: int) -> str:
    import io
    import pstats

    s = io.StringIO()
    st = prof if isinstance(prof, pstats.Stats) else pstats.Stats(prof, stream=s)
    st.stream = s
    st.strip_dirs().sort_stats(sort).print_stats(limit)
    lines = s.getvalue().strip().splitlines()
    return "\n".join(line for line in lines if line.strip())


def profiles(ctx: Context, cfg: Config, startup_profile: bool = True) -> str:
    """cProfile tables (top 15 by tottime) of ``solve`` at N = min(10⁴, N_max) and of the
    public API at N = 1, and of a cold ``id`` process (import times and top 25 by
    cumulative time)."""
    import cProfile
    import subprocess
    import tempfile

    from . import inverse_dynamics
    from .dynamics import solve

    n = min(10_000, ctx.n_max)
    q, qd, qdd = ctx.q[:n], ctx.qd[:n], ctx.qdd[:n]
    solve(ctx.robot, q, qd, qdd)
    reps = max(1, int(0.5 / max(1e-6, 3e-6 * n)))
    pr = cProfile.Profile()
    pr.enable()
    for _ in range(reps):
        solve(ctx.robot, q, qd, qdd)
    pr.disable()
    text = [f"## cProfile: solve(robot, q, qd, qdd) at N = {n}, {reps} calls, top 15 by "
            "tottime", _pstats_text(pr, "tottime", 15)]
    solve(ctx.robot, q, qd, qdd, method="rnea")
    pr = cProfile.Profile()
    pr.enable()
    solve(ctx.robot, q, qd, qdd, method="rnea")
    pr.disable()
    text += ["", f"## cProfile: solve(robot, q, qd, qdd, method='rnea') at N = {n}, 1 call, "
             "top 15 by tottime", _pstats_text(pr, "tottime", 15)]
    q1, qd1, qdd1 = ctx.q[0].copy(), ctx.qd[0].copy(), ctx.qdd[0].copy()
    inverse_dynamics(ctx.robot, q1, qd1, qdd1)
    pr = cProfile.Profile()
    pr.enable()
    for _ in range(2000):
        inverse_dynamics(ctx.robot, q1, qd1, qdd1)
    pr.disable()
    text += ["", "## cProfile: inverse_dynamics(robot, q, qd, qdd), one (9,) sample, 2000 "
             "calls, top 15 by tottime", _pstats_text(pr, "tottime", 15)]
    if startup_profile:
        env = _child_env()
        cmd = ["-m", "offshore_crane", "id", "--trajectory", "table1"]
        res = subprocess.run([sys.executable, "-X", "importtime", *cmd], env=env, check=True,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        top = []
        for line in res.stderr.splitlines():
            if line.startswith("import time:") and "|" in line:
                parts = line[len("import time:"):].split("|")
                try:
                    self_us, cum_us = int(parts[0]), int(parts[1])
                except ValueError:
                    continue
                name = parts[2]
                if name.startswith(" ") and not name.startswith("  "):   # top level
                    top.append((cum_us, name.strip()))
        top.sort(reverse=True)
        total = sum(c for c, _ in top)
        text += ["", f"## cold process `python -m offshore_crane id --trajectory table1`: "
                 f"top-level imports (-X importtime), {total / 1e3:.0f} ms in all",
                 *(f"{c / 1e3:8.1f} ms  {name}" for c, name in top[:12])]
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "startup.prof"
            subprocess.run([sys.executable, "-m", "cProfile", "-o", str(out), *cmd], env=env,
                           check=True, stdout=subprocess.DEVNULL)
            import pstats

            text += ["", "## cProfile of that cold process, top 25 by cumulative time",
                     _pstats_text(pstats.Stats(str(out)), "cumulative", 25)]
    return "\n".join(text)


# --------------------------------------------------------------------------- outputs
BENCH_COLUMNS = ("variant", "group", "N", "median_us", "min_us", "max_us", "repeats",
                 "ratio_to_floor", "ratio_min_to_floor", "streamed", "peak_MB", "skipped")
ERROR_COLUMNS = ("variant", "reference", "group", "max_rel_error", "us_per_sample", "N",
                 "primary", "pareto", "fd_us_per_sample", "csv_read_us_per_sample", "note")


def _write_csv(path: Path, rows, columns) -> None:
    import csv

    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v)
                        for k, v in r.items() if k in columns})


def mark_pareto(points: list[dict]) -> None:
    """Set ``pareto`` on each point: no other point is both faster and more accurate."""
    for p in points:
        p["pareto"] = not any(
            (o["us_per_sample"] <= p["us_per_sample"] and o["max_rel_error"] <= p["max_rel_error"]
             and (o["us_per_sample"] < p["us_per_sample"] or o["max_rel_error"] < p["max_rel_error"]))
            for o in points if o is not p)


def _label_positions(xs, ys, widths, height: float) -> list[float]:
    """Label heights (log10) that do not overlap: label i spans ``[xs[i], xs[i] +
    widths[i]]`` and ``height`` (log10 units); a label that would cover one already
    placed (lowest first) moves up."""
    placed, out = [], [0.0] * len(xs)
    for i in sorted(range(len(xs)), key=lambda i: ys[i]):
        y = ys[i]
        moved = True
        while moved:
            moved = False
            for x0, w0, y0 in placed:
                if xs[i] < x0 + w0 and x0 < xs[i] + widths[i] and abs(y - y0) < 0.999 * height:
                    y, moved = y0 + height, True
        placed.append((xs[i], widths[i], y))
        out[i] = y
    return out


def plot_pareto(path: Path, points: list[dict], floor_us: float | None, title: str) -> None:
    """Log-log plot of time per sample [µs] against max relative error, labelled points."""
    import matplotlib
    import numpy as np

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    style = {"exact": dict(marker="o", color="tab:blue", label="exact"),
             "approximation": dict(marker="^", color="tab:red", label="approximation"),
             "data": dict(marker="s", color="tab:green",
                          label="Kane on sampled q from CSV (finite differences)")}
    fig, ax = plt.subplots(figsize=(10, 6.5), dpi=120)
    xs = [p["us_per_sample"] for p in points]
    ys = [max(p["max_rel_error"], 1e-17) for p in points]
    seen = set()
    for p, x, y in zip(points, xs, ys):
        st = style[p["group"]]
        ax.scatter(x, y, s=46, zorder=3, marker=st["marker"], edgecolors=st["color"],
                   facecolors=st["color"] if p["group"] != "data" else "none",
                   label=None if st["label"] in seen else st["label"])
        seen.add(st["label"])
    front = sorted((p for p in points if p.get("pareto")), key=lambda p: p["us_per_sample"])
    if front:
        ax.step([p["us_per_sample"] for p in front],
                [max(p["max_rel_error"], 1e-17) for p in front], where="post",
                color="0.5", lw=0.8, ls=":", label="Pareto front")
    if floor_us:
        ax.axvline(floor_us, color="k", ls="--", lw=1,
                   label=f"floor: rneaInParallel, 1 thread ({floor_us:.2f} µs; no loop closure)")
    ax.axhline(EXACT_LIMIT, color="tab:purple", ls="-.", lw=0.8, label="1e-9 (exact limit)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    lx = [math.log10(x) for x in xs + ([floor_us] if floor_us else [])]
    ly = [math.log10(y) for y in ys]
    ax.set_xlim(10 ** (min(lx) - 0.08), 10 ** (max(lx) + 0.35))
    ax.set_ylim(10 ** (min(ly) - 0.6), 10 ** (max(ly) + 0.6))
    (x0, x1), (y0, y1) = (np.log10(ax.get_xlim()), np.log10(ax.get_ylim()))
    texts = [p["variant"].replace("CSV q @ ", "q @ ") for p in points]
    label_y = _label_positions([math.log10(x) for x in xs], [math.log10(y) for y in ys],
                               [(0.006 * len(t) + 0.02) * (x1 - x0) for t in texts],
                               0.03 * (y1 - y0))
    for p, text, x, y, yl in zip(points, texts, xs, ys, label_y):
        moved = abs(yl - math.log10(y)) > 1e-9
        ax.annotate(text, (x, y), xytext=(x * 1.04, 10 ** yl), fontsize=7, va="center",
                    arrowprops=dict(arrowstyle="-", color="0.6", lw=0.5) if moved else None)
    ax.set_xlabel("time per sample [µs]")
    ax.set_ylabel("max relative error  max|ΔX| / max|X_ref|")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def machine() -> dict:
    """This machine and the versions measured."""
    import platform
    from datetime import datetime
    from importlib import metadata

    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            cpu = next((line.split(":", 1)[1].strip() for line in f
                        if line.startswith("model name")), cpu)
    except OSError:
        pass
    versions = {}
    for dist in ("numpy", "pin", "numba"):
        try:
            versions[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            versions[dist] = "absent"
    return dict(date=datetime.now().astimezone().isoformat(timespec="seconds"),
                platform=platform.platform(), cpu=cpu, cores=os.cpu_count(),
                python=platform.python_version(), **versions)


def _n(n: int) -> str:
    """``10⁴`` for powers of ten, else the number."""
    k = round(math.log10(n)) if n > 0 else 0
    if n >= 100 and 10 ** k == n:
        return "10" + str(k).translate(str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹"))
    return str(n)


def _fmt_us(x) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    return f"{x:.3g}" if x < 100 else f"{x:.0f}"


def targets(bench_rows, error_rows, startup_rows) -> list[dict]:
    """Issue 5's targets against the measured numbers (None: not measured)."""
    big = sorted({r["N"] for r in bench_rows if r["N"] >= 10_000})
    out = []
    for name, key, label in (("kane", "kane_over_floor", "Kane (default solve) / floor"),
                             ("rnea path", "rnea_over_floor", "RNEA path / floor")):
        ratios = {n: (r["ratio_to_floor"], r["ratio_min_to_floor"]) for n in big
                  for r in bench_rows if r["variant"] == name and r["N"] == n
                  and r["repeats"] and not math.isnan(r["ratio_to_floor"])}
        worst = max(m for m, _ in ratios.values()) if ratios else None
        out.append(dict(target=f"{label}, N ≥ 10⁴", limit=f"≤ {TARGETS[key]:g}",
                        measured=", ".join(f"{m:.2f} (N={_n(n)}; of minima {b:.2f})"
                                           for n, (m, b) in ratios.items())
                        or "not measured",
                        met=None if worst is None else worst <= TARGETS[key]))
    api = next((r for r in bench_rows if r["variant"] == API and r["repeats"]), None)
    out.append(dict(target="one sample through inverse_dynamics (Kane), N = 1",
                    limit=f"≤ {TARGETS['api_us']:g} µs",
                    measured="not measured" if api is None else
                    f"{api['median_us']:.1f} µs (min {api['min_us']:.1f} µs)",
                    met=None if api is None else api["median_us"] <= TARGETS["api_us"]))
    if startup_rows:
        worst = max(startup_rows[1:], key=lambda r: r["ratio_to_numpy"])
        out.append(dict(target="`offshore-crane id --trajectory table1` wall time / "
                        "`python -c \"import numpy\"`", limit=f"≤ {TARGETS['startup_over_numpy']:g}",
                        measured=f"{worst['ratio_to_numpy']:.2f} ({worst['median_s'] * 1e3:.0f} ms"
                                 f" vs {startup_rows[0]['median_s'] * 1e3:.0f} ms)",
                        met=worst["ratio_to_numpy"] <= TARGETS["startup_over_numpy"]))
    else:
        out.append(dict(target="start-up", limit=f"≤ {TARGETS['startup_over_numpy']:g}",
                        measured="not measured", met=None))
    ex = [r for r in error_rows if r["variant"] == "kane" and r["reference"] == "rnea path"]
    out.append(dict(target="default path exact: kane vs RNEA path (max rel. error)",
                    limit=f"≤ {EXACT_LIMIT:g}",
                    measured=f"{ex[0]['max_rel_error']:.2e}" if ex else "not measured",
                    met=ex[0]["max_rel_error"] <= EXACT_LIMIT if ex else None))
    return out


def summary_markdown(info, cfg, bench_rows, error_rows, startup_rows, target_rows,
                     notes) -> str:
    """``summary.md``: machine, a short table for the README, the Pareto points, targets."""
    sizes = [n for n in (1, 10_000, 1_000_000) if n in cfg.sizes]
    n_ratio = 10_000 if 10_000 in cfg.sizes else max(cfg.sizes)
    err = {r["variant"]: r for r in error_rows if r["primary"]}
    head = (["variant"] + [f"µs/sample N={_n(n)}" for n in sizes]
            + [f"÷ floor (N={_n(n_ratio)})", "max rel. error", "reference",
               "peak memory of one call"])
    lines = [f"Benchmark on {info['cpu']} ({info['cores']} cores), {info['platform']}, "
             f"Python {info['python']}, NumPy {info['numpy']}, Pinocchio {info['pin']}, "
             f"Numba {info['numba']}; {info['date']}; load average {info['load_before']} "
             f"before, {info['load_after']} after. Table 1 at 100 Hz; medians of "
             "repeated runs (min/max in bench.csv).", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for v in VARIANTS:
        if not any(r["variant"] == v.name for r in bench_rows):
            continue
        cells = [v.name]
        for n in sizes:
            r = next((r for r in bench_rows if r["variant"] == v.name and r["N"] == n), None)
            cells.append("–" if r is None else ("skipped" if r["skipped"] else
                                                _fmt_us(r["median_us"])))
        r = next((r for r in bench_rows if r["variant"] == v.name and r["N"] == n_ratio), None)
        cells.append("–" if r is None or math.isnan(r["ratio_to_floor"])
                     else f"{r['ratio_to_floor']:.2f}")
        e = err.get(v.name)
        cells += ["–", "no loop closure"] if v.group == "floor" else (
            [f"{e['max_rel_error']:.1e}", e["reference"]] if e else ["–", ""])
        r = next((r for r in bench_rows if r["variant"] == v.name
                  and not math.isnan(r["peak_MB"])), None)
        cells.append("–" if r is None else
                     f"{r['peak_MB']:.3g} MB (N={_n(r['N'])}"
                     + (f", chunks of {_n(cfg.stream)})" if r["streamed"] else ")"))
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "Sampled data (Table 1 q written to CSV, derivatives by finite "
              "differences), max relative error of Kane's X against analytic derivatives:", "",
              "| rate | " + " | ".join(f"FD order {o}" for o in cfg.fd_orders) + " |",
              "|---|" + "---|" * len(cfg.fd_orders)]
    for rate in cfg.fd_rates:
        cells = [f"{rate:g} Hz"]
        for o in cfg.fd_orders:
            e = err.get(f"CSV q @ {rate:g} Hz, FD{o}")
            cells.append("–" if e is None else f"{e['max_rel_error']:.1e}")
        lines.append("| " + " | ".join(cells) + " |")
    if startup_rows:
        lines += ["", "Start-up (cold process, URDF cache warm), median of "
                  f"{startup_rows[0]['runs']}:", ""]
        lines += [f"- {r['command']}: {r['median_s'] * 1e3:.0f} ms "
                  f"({r['ratio_to_numpy']:.2f} × import numpy)" for r in startup_rows]
    lines += ["", "Targets (issue 5), computed from the numbers above:", "",
              "| target | limit | measured | met |", "|---|---|---|---|"]
    for t in target_rows:
        met = "not measured" if t["met"] is None else ("yes" if t["met"] else "**no**")
        lines.append(f"| {t['target']} | {t['limit']} | {t['measured']} | {met} |")
    lines += ["", "Pareto plot points (time per sample at N="
              f"{_n(cfg.error_n)}, max relative error):", "",
              "| point | µs/sample | max rel. error | on the front |", "|---|---|---|---|"]
    for r in sorted((r for r in error_rows if r["primary"]), key=lambda r: r["us_per_sample"]):
        lines.append(f"| {r['variant']} | {r['us_per_sample']:.3g} | "
                     f"{r['max_rel_error']:.2e} | {'yes' if r.get('pareto') else ''} |")
    if notes:
        lines += ["", "Notes:", ""] + [f"- {n}" for n in notes]
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- driver
@dataclass
class Results:
    """Everything one run measured."""

    info: dict
    bench: list
    errors: list
    startup: list
    targets: list
    profiles: str = ""
    notes: list = field(default_factory=list)
    files: list = field(default_factory=list)


def run_bench(cfg: Config, log=print) -> Results:
    """Run the benchmark with ``cfg`` and write its files to ``cfg.out``."""
    import resource

    from .model import load_robot

    out = Path(cfg.out)
    out.mkdir(parents=True, exist_ok=True)
    info = machine()
    info["load_before"] = "%.2f %.2f %.2f" % os.getloadavg()
    log(f"offshore-crane bench: {info['date']}, {info['cpu']} ({info['cores']} cores), "
        f"load average {info['load_before']}")
    log(f"Python {info['python']}, NumPy {info['numpy']}, Pinocchio {info['pin']}, "
        f"Numba {info['numba']}")
    robot = load_robot()                 # also fills the URDF cache for the start-up runs
    variants = [v for v in VARIANTS if v.group == "floor" or not cfg.only
                or any(s in v.name for s in cfg.only)]
    n_max = max(max(cfg.sizes), cfg.error_n)
    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    ctx = Context(robot, n_max, cfg.stream)
    notes = [f"inputs: Table 1 q, qd, qdd for N = {n_max} samples, "
             f"{3 * ctx.q.nbytes / 1e6:.0f} MB; N ≤ {cfg.stream} in one call, larger N "
             f"streamed in chunks of {cfg.stream} (views of the inputs)",
             "peak_MB in bench.csv: peak memory traced by tracemalloc during one call at "
             "the variant's largest N (NumPy/Python allocations, inputs excluded)"]
    log(f"µs per sample, Table 1 at {RATE:g} Hz; N > {cfg.stream} streamed in chunks")
    bench_rows, runs = sweep(ctx, variants, cfg, log)
    notes += ctx.notes
    skipped = [f"{r['variant']} at N={r['N']}: {r['skipped']}" for r in bench_rows
               if r["skipped"]]
    notes += [f"skipped {s}" for s in skipped]
    log("errors (max |ΔX| / max |X_ref|) at N = %d, and time per sample" % cfg.error_n)
    error_rows = errors(ctx, runs, bench_rows, cfg, log)
    points = [r for r in error_rows if r["primary"]]
    mark_pareto(points)
    startup_rows = startup(cfg, log) if cfg.startup_runs else []
    if startup_rows:
        notes.append("start-up: the URDF and Numba caches were warm (one untimed run of "
                     "each command first)")
        if os.environ.get("PYTHONDONTWRITEBYTECODE"):
            notes.append("start-up: PYTHONDONTWRITEBYTECODE is set here, so every cold "
                         "process compiles the package's sources (an installed wheel has "
                         "its .pyc files)")
    prof = profiles(ctx, cfg, startup_profile=bool(cfg.startup_runs)) if cfg.profile else ""
    info["load_after"] = "%.2f %.2f %.2f" % os.getloadavg()
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    notes.append(f"process peak RSS {rss / 1e3:.0f} MB ({(rss - rss0) / 1e3:.0f} MB above "
                 "the robot and imports)")
    target_rows = targets(bench_rows, error_rows, startup_rows)
    floor_us = _us_at(bench_rows, FLOOR, cfg.error_n)
    files = []
    _write_csv(out / "bench.csv", bench_rows, BENCH_COLUMNS)
    _write_csv(out / "errors.csv", error_rows, ERROR_COLUMNS)
    files += [out / "bench.csv", out / "errors.csv"]
    plot_pareto(out / "pareto.png", points, floor_us,
                f"offshore-crane, full crane, Table 1: time per sample at N={cfg.error_n} vs "
                f"error ({info['cpu']}, {info['date'][:10]})")
    files.append(out / "pareto.png")
    summary = summary_markdown(info, cfg, bench_rows, error_rows, startup_rows, target_rows,
                               notes)
    (out / "summary.md").write_text(summary, encoding="utf-8")
    files.append(out / "summary.md")
    if prof:
        (out / "profiles.txt").write_text(prof + "\n", encoding="utf-8")
        files.append(out / "profiles.txt")
    log("")
    log(summary)
    if prof:
        log(prof)
    log("wrote " + ", ".join(str(f) for f in files))
    return Results(info, bench_rows, error_rows, startup_rows, target_rows, prof, notes,
                   files)


def default_out() -> Path:
    """``docs/bench`` of the source checkout when run from inside it, else ``./bench``."""
    root = Path(__file__).resolve().parents[2]
    cwd = Path.cwd().resolve()
    if (root / "pyproject.toml").is_file() and (cwd == root or root in cwd.parents):
        return root / "docs" / "bench"
    return cwd / "bench"


DESCRIPTION = ("Time per sample against error of every inverse-dynamics path of the full "
               "crane on Table 1, start-up time and profiles; writes bench.csv, errors.csv, "
               "pareto.png, summary.md and profiles.txt.")


def _arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--quick", action="store_true",
                   help="N up to 10⁴, few repeats (about half a minute)")
    p.add_argument("--out", metavar="DIR",
                   help="directory of bench.csv, errors.csv, pareto.png, summary.md, "
                        "profiles.txt (default docs/bench in the source checkout, else ./bench)")
    p.add_argument("--sizes", type=int, nargs="+", metavar="N", help="sample counts to time")
    p.add_argument("--budget", type=float, metavar="S",
                   help="skip points whose single call is estimated above S seconds "
                        "(default 10)")
    p.add_argument("--only", metavar="NAMES",
                   help="comma-separated substrings of variant names to run (the floor "
                        "always runs)")
    p.add_argument("--no-startup", action="store_true", help="skip the start-up timing")
    p.add_argument("--no-profile", action="store_true", help="skip the cProfile tables")


def add_parser(subparsers):
    """Register the ``bench`` sub-command on an argparse ``subparsers`` object."""
    p = subparsers.add_parser("bench", help="time per sample against error, all methods",
                              description=DESCRIPTION)
    _arguments(p)
    p.set_defaults(run=run)
    return p


def config_from_args(args) -> Config:
    """The :class:`Config` of parsed command-line arguments."""
    cfg = Config(**QUICK) if args.quick else Config()
    changes = {"out": Path(args.out) if args.out else default_out()}
    if args.sizes:
        if any(n < 1 for n in args.sizes):
            from .errors import InputError

            raise InputError("--sizes must be positive sample counts", name="--sizes")
        changes["sizes"] = tuple(sorted(set(args.sizes)))
    if args.budget is not None:
        changes["budget_s"] = args.budget
    if args.only:
        changes["only"] = tuple(s.strip() for s in args.only.split(",") if s.strip())
    if args.no_startup:
        changes["startup_runs"] = 0
    if args.no_profile:
        changes["profile"] = False
    return replace(cfg, **changes)


def run(args) -> int:
    """Run ``offshore-crane bench``; exit status 1 when the default path is not exact."""
    res = run_bench(config_from_args(args))
    exact = [t for t in res.targets if t["target"].startswith("default path exact")]
    return 1 if exact and exact[0]["met"] is False else 0


def main(argv=None) -> int:
    """``scripts/bench.py``: the same as ``offshore-crane bench``."""
    p = argparse.ArgumentParser(prog="bench.py", description=DESCRIPTION)
    _arguments(p)
    args = p.parse_args(argv)
    return run(args)
