"""Measure what each exact pruning of issue 4 saves, and print the fidelity tables.

Run: ``python benchmarks/pruning_speedups.py [--repeat 7]``.

Every timing is the median of ``--repeat`` runs after one untimed warm-up, on the
Table 1 default span (10π s at 100 Hz: 3142 samples). "kernel" rows time the Kane
kernel alone (an entry of :data:`offshore_crane.dynamics.REGISTRY`) with the options
:func:`offshore_crane.dynamics.solve` would pass it (condition numbers when the legs are
evaluated), pruned against unpruned, for each backend; "solve" rows time the whole call (checks included). Import
costs are measured in fresh interpreters. The pruned and unpruned results are compared
too (max relative difference), to show that each pruning is exact.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

import offshore_crane as oc  # noqa: E402
from offshore_crane import scenes
from offshore_crane.motion import trajectories
from offshore_crane.dynamics import REGISTRY, numba_available, solve  # noqa: E402
from offshore_crane.dynamics.kernels import Options  # noqa: E402
from offshore_crane.robot.kinematics.formulas import MASSLESS  # noqa: E402

G = np.array([0.0, 0.0, -9.81])
ARM = ("T1", "T2", "Fs")


def median_time(fn, repeat: int) -> float:
    """Median wall time [s] of ``fn()`` over ``repeat`` runs after one warm-up."""
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def rel(a, b) -> float:
    finite = np.isfinite(a) & np.isfinite(b)
    return float(np.abs(a[finite] - b[finite]).max() / np.abs(b[finite]).max())


def row(label: str, t_unpruned: float, t_pruned: float, err: float | None = None) -> str:
    tail = "" if err is None else f"{err:>12.1e}"
    return (f"{label:<58}{t_unpruned * 1e3:>10.3f}{t_pruned * 1e3:>10.3f}"
            f"{t_unpruned / t_pruned:>9.2f}{tail}")


def kernel_rows(label, robot, q, qd, qdd, unpruned: Options, pruned: Options, repeat,
                cols=None):
    backends = ("numpy", "numba") if numba_available() else ("numpy",)
    out = []
    for b in backends:
        def run(opts):
            return REGISTRY[("kane", b)](robot, q, qd, qdd, G, opts, 1)[0]
        X0, X1 = run(unpruned), run(pruned)
        c = slice(None) if cols is None else cols
        out.append(row(f"{label} [kernel, {b}]", median_time(lambda: run(unpruned), repeat),
                       median_time(lambda: run(pruned), repeat), rel(X1[:, c], X0[:, c])))
    return out


def import_cost(module: str, repeat: int) -> float:
    """Median extra time [s] of importing ``module`` in a fresh interpreter."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}

    def spawn(code):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True, env=env)
        return time.perf_counter() - t0

    base = statistics.median(spawn("import offshore_crane") for _ in range(repeat))
    full = statistics.median(spawn(f"import offshore_crane, {module}") for _ in range(repeat))
    return full - base


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7, help="timed runs per figure (median)")
    args = ap.parse_args()
    n = args.repeat
    robot = oc.load_robot()
    t = trajectories.time_grid()
    q, qd, qdd = trajectories.table1(t)
    full_opts = Options(conditioning=True)
    print(f"Table 1 default span: {len(t)} samples; median of {n} runs after a warm-up; "
          f"Numba {'installed' if numba_available() else 'absent'}")
    print(f"{'pruning':<58}{'full [ms]':>10}{'pruned':>10}{'speed-up':>9}{'max rel.':>12}")
    lines = []
    # 1. arm-only outputs: no leg kinematics or dynamics
    lines += kernel_rows("arm-only outputs (T1, T2, Fs)", robot, q, qd, qdd, full_opts,
                         Options(legs=False), n, cols=slice(0, 3))
    Xf, Xa = solve(robot, q, qd, qdd).X, solve(robot, q, qd, qdd, outputs=ARM).X
    lines.append(row("arm-only outputs (T1, T2, Fs) [solve]",
                     median_time(lambda: solve(robot, q, qd, qdd), n),
                     median_time(lambda: solve(robot, q, qd, qdd, outputs=ARM), n),
                     rel(Xa[:, :3], Xf[:, :3])))
    # 2. static platform: q1..q6 held at home, no platform velocity/acceleration terms
    qs, qds, qdds = q.copy(), qd.copy(), qdd.copy()
    qs[:, :6] = (0.0, 0.0, 0.5, 0.0, 0.0, 0.0)
    qds[:, :6] = qdds[:, :6] = 0.0
    lines += kernel_rows("static platform (all outputs)", robot, qs, qds, qdds, full_opts,
                         Options(static=True, conditioning=True), n)
    lines += kernel_rows("static platform + arm-only (fixed deck)", robot, qs, qds,
                         qdds, full_opts, Options(legs=False, static=True), n,
                         cols=slice(0, 3))
    deck, crane = scenes.load_scene(ROOT / "scenes/arm_fixed_deck.toml"), scenes.Scene()
    deck_traj = scenes.load_trajectory(deck, robot)
    lines.append(row("fixed-deck scene vs full crane, same data [solve]",
                     median_time(lambda: scenes.run(crane, robot, deck_traj), n),
                     median_time(lambda: scenes.run(deck, robot, deck_traj), n),
                     rel(scenes.run(deck, robot, deck_traj).result.X[:, :3],
                         scenes.run(crane, robot, deck_traj).result.X[:, :3])))
    # 3. massless legs (a robot whose legs weigh nothing): no leg inertia terms
    light = oc.load_robot(leg_lower_mass=0.0, leg_upper_mass=0.0)
    lines += kernel_rows("massless-leg robot (leg inertia terms)", light, q, qd, qdd,
                         full_opts, Options(leg_model=MASSLESS, conditioning=True), n)
    for line in lines:
        print(line)

    # 4. lazy imports, 5. URDF cache
    print(f"\nimports skipped (extra time of a fresh interpreter, median of {n}):")
    for module in ("pinocchio", "matplotlib.pyplot", "xacro", "yourdfpy"):
        print(f"  {module:<20}{import_cost(module, n) * 1e3:>9.1f} ms")
    from offshore_crane.robot import Robot
    from offshore_crane.robot.description import resolve
    from offshore_crane.robot.xacro_cache import expand

    spec = resolve()
    data = spec.xacro_data()
    with tempfile.TemporaryDirectory() as tmp:
        def miss():
            os.environ["OFFSHORE_CRANE_CACHE"] = tempfile.mkdtemp(dir=tmp)
            return expand(data)

        t_miss = median_time(miss, n)
        t_hit = median_time(lambda: expand(data), n)
        os.environ.pop("OFFSHORE_CRANE_CACHE")
    urdf, path = expand(data)
    t_resolve = median_time(resolve, n)
    t_parse = median_time(lambda: Robot(urdf, path, spec), n)
    t_memo = median_time(lambda: oc.load_robot(), n)
    print(f"robot: description resolved and checked {t_resolve * 1e3:.1f} ms, xacro "
          f"expansion {t_miss * 1e3:.1f} ms, cache hit {t_hit * 1e3:.2f} ms, "
          f"URDF parse + model {t_parse * 1e3:.2f} ms, load_robot memo hit "
          f"{t_memo * 1e6:.1f} µs")

    # fidelity tables of the example scenes
    for name in ("full_crane", "platform_only", "arm_fixed_deck", "crane_with_payload"):
        scene = scenes.load_scene(ROOT / "scenes" / f"{name}.toml")
        robot_s = scenes.load_robot(scene)
        traj = scenes.load_trajectory(scene, robot_s)
        names, scale, rows = scenes.compare_fidelity(scene, robot_s, traj, repeat=n)
        print(f"\n== scenes/{name}.toml")
        print(scenes.format_fidelity(names, scale, rows, len(traj), repeat=n))
    return 0


if __name__ == "__main__":
    sys.exit(main())
