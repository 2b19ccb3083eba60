"""Roofline of the compiled kernels: how far each is from what this machine can do.

For each kernel: the floating-point operations of one sample, counted by running its one
text on counting numbers (benchmarks/_flops.py: ``+ - * / sqrt``, the branch the sample
takes; ``sin``/``cos``/``atan2`` listed apart), the time of one sample measured in this
run (N samples, one thread, the default checks), hence the achieved GFLOP/s, against:

- the **peak of one core**: a dense float64 matrix product in NumPy/BLAS with one BLAS
  thread (2 n³ operations; vector units and fused multiply-adds: the machine's roof);
- the **scalar roof**: that peak over the vector width in doubles read from the CPU's
  flags (8 with AVX-512, 4 with AVX2, else 2): what code that does not use the vector
  units can reach at best;
- the **memory roof**: a large array copy's bandwidth times the kernel's arithmetic
  intensity (operations per byte of its inputs and outputs, 8 bytes a double).

Verdict per kernel, by rule: *memory-bound* when the memory roof at its intensity is
below the peak (left of the ridge point) and it reaches half of it; *compute-bound* when
it reaches half the peak; otherwise *latency-bound* under the scalar roof (scalar
dependency chains: the vector units idle), *partly vectorised* above it. Counts are of the text: LLVM may fold some operations (multiplications by
constant zeros or ones), so achieved rates are upper estimates by that share.

    python benchmarks/roofline.py [--n 100000] [--save]

``--save`` writes benchmarks/results/roofline.json (scripts/figures.py puts the table in
README.md).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import _flops  # noqa: E402
from _saved import add_save_option, save, stamp  # noqa: E402

_PEAK = """
import time, numpy as np
n = {n}
a, b = np.random.default_rng(0).random((2, n, n))
a @ b
best = min((lambda t0: (a @ b, time.perf_counter() - t0)[1])(time.perf_counter())
           for _ in range(5))
print(2.0 * n ** 3 / best / 1e9)
"""


def peak_gflops(n: int = 1500) -> float:
    """One core's float64 peak [GFLOP/s]: a matrix product with one BLAS thread (in a
    subprocess: the thread count is read when NumPy's BLAS starts)."""
    env = {**os.environ, **{k: "1" for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                             "MKL_NUM_THREADS", "BLIS_NUM_THREADS")}}
    out = subprocess.run([sys.executable, "-c", _PEAK.format(n=n)], env=env, check=True,
                         capture_output=True, text=True)
    return float(out.stdout.split()[-1])


def bandwidth_gbs(mb: int = 400) -> float:
    """Memory bandwidth [GB/s]: the best of 5 copies of an ``mb`` MB array (read + write)."""
    a = np.ones(mb * 1024 * 1024 // 8)
    b = np.empty_like(a)
    best = min(_timed_once(lambda: np.copyto(b, a)) for _ in range(5))
    return 2.0 * a.nbytes / best / 1e9


def vector_width() -> int:
    """Doubles per vector register, from the CPU's flags (Linux; 2 when unknown)."""
    try:
        flags = Path("/proc/cpuinfo").read_text().split("flags")[1].split("\n")[0].split()
    except (OSError, IndexError):
        return 2
    return 8 if "avx512f" in flags else 4 if "avx2" in flags else 2


def _timed_once(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def best_of(fn, repeat: int = 5) -> float:
    fn()
    return min(_timed_once(fn) for _ in range(repeat))


def kernels(robot, n: int) -> dict:
    """name -> (counted operations, seconds per sample, bytes per sample)."""
    import offshore_crane as oc
    from offshore_crane.dynamics import solve
    from offshore_crane.simulation import Controller

    t = np.arange(n) / 100.0
    q, qd, qdd = oc.motion.trajectories.table1(t)
    X = solve(robot, q, qd, qdd).X
    io = 36 * 8                                       # 27 doubles in, 9 out
    out = {
        "fused Kane": (_flops.fused_kane(robot),
                       best_of(lambda: solve(robot, q, qd, qdd)) / n, io),
        "explicit Kane": (_flops.explicit_kane(robot), best_of(
            lambda: solve(robot, q, qd, qdd, method="kane-explicit")) / n, io),
        "forward dynamics": (_flops.forward_dynamics(robot), best_of(
            lambda: oc.forward_dynamics(robot, q, qd, X)) / n, io),
    }
    duration = 2.0
    steps = int(round(duration / 1e-3))
    run = best_of(lambda: oc.simulate(robot, duration, oc.motion.trajectories.table1,
                                      controller=Controller()), repeat=3)
    out["RK4 step, computed torque"] = (_flops.rk4_step(robot), run / steps, 36 * 8)
    # (36 doubles a step: the state in and out; the record's row every tenth step)
    from offshore_crane import serial
    from bench_serial import ROBOTS_DIR

    chain = serial.load_chain(ROBOTS_DIR / "panda_description/urdf/panda.urdf",
                              tip="panda_hand")
    sq, sqd, sqdd = serial.random_states(chain, n, seed=0)
    out["serial Kane, Panda (7 joints)"] = (_flops.serial_kane(chain), best_of(
        lambda: serial.inverse_dynamics(chain, sq, sqd, sqdd)) / n, 4 * 7 * 8)
    out.update(swing(n))
    out.update(layouts(robot, n))
    return out


def swing(n: int) -> dict:
    """The hanging load's two compiled kernels, timed inside one ``cable.swing`` of the
    shipped sea-state scene with its payload on a 1 m cable (benchmarks/cable_swing.py's),
    ``n`` samples at 100 Hz: the sway's RK4 step and the robot's Kane with the payload
    swinging (the motion's synthesis at the stage points, NumPy, is not a kernel)."""
    from cable_swing import _scene

    from offshore_crane import scenes
    from offshore_crane.dynamics import cable

    scene = _scene(n / 100.0 / 3600.0, 100.0, 20.0, 1.0, 0.02)
    robot = scenes.load_robot(scene)
    traj = scenes.load_trajectory(scene, robot)
    spent: dict = {}
    inner = {"integrate": cable._integrate_kane, "kane": cable.kane_forces}

    def timed_as(name):
        def run(*args, **kwargs):
            t0 = time.perf_counter()
            result = inner[name](*args, **kwargs)
            spent[name] = min(spent.get(name, np.inf), time.perf_counter() - t0)
            if name == "integrate":
                spent["steps"] = (args[1].shape[0] - 1) // 2
            return result
        return run

    cable._integrate_kane, cable.kane_forces = timed_as("integrate"), timed_as("kane")
    try:
        for _ in range(3):
            cable.swing(robot, traj, **scene.cable)
    finally:
        cable._integrate_kane, cable.kane_forces = inner["integrate"], inner["kane"]
    samples = len(traj.t)
    return {"swing: sway RK4 step": (_flops.swing_step(robot),
                                     spent["integrate"] / spent["steps"], 8 * 8),
            "swing: Kane with the load": (_flops.cable_kane(robot), spent["kane"] / samples,
                                          (33 + 15) * 8)}
    # bytes: the sway step reads and writes its 4 states (8 doubles); the Kane reads 33
    # (q, q̇, q̈ of 11 coordinates) and writes 15 (X, the pull, tension and residuals)


def layouts(robot, n: int) -> dict:
    """Issue 25's question on one piece of the Kane text: the six legs' geometry
    (``formulas.leg_geometry``, compiled inlined as the kernels compile it; the attitude
    given) run per sample, the kernels' layout (a sample's numbers side by side), and on
    structure of arrays (each quantity a 1-D array over the samples, the views taken
    before the loop over samples, no branch in it). The same text, the same operations in
    the same order: the same numbers bit for bit (checked here, and against the NumPy
    backend of the text); LLVM vectorises the second across samples."""
    import numba

    from offshore_crane.dynamics.compiled import K
    from offshore_crane.dynamics.constants import robot_arrays
    from offshore_crane.robot.kinematics import formulas as F

    geometry = K.leg_geometry
    jit = numba.njit(nogil=True, error_model="numpy")
    C = robot_arrays(robot).kane
    S, P, X, Y, Z = C.leg_s, C.leg_P, C.leg_X, C.leg_Y, C.leg_Z

    @jit
    def per_sample(p, R, S, P, X, Y, Z, out):          # p (n, 3), R (n, 9), out (n, 6, 6)
        for k in range(p.shape[0]):
            pk = (p[k, 0], p[k, 1], p[k, 2])
            Rk = ((R[k, 0], R[k, 1], R[k, 2]), (R[k, 3], R[k, 4], R[k, 5]),
                  (R[k, 6], R[k, 7], R[k, 8]))
            for i in range(6):
                _, d, length, _, _, dx, dy, dz, h = geometry(
                    pk, Rk, (S[i, 0], S[i, 1], S[i, 2]), (P[i, 0], P[i, 1], P[i, 2]),
                    (X[i, 0], X[i, 1], X[i, 2]), (Y[i, 0], Y[i, 1], Y[i, 2]),
                    (Z[i, 0], Z[i, 1], Z[i, 2]))
                out[k, i, 0], out[k, i, 1], out[k, i, 2] = length, d[2], dx
                out[k, i, 3], out[k, i, 4], out[k, i, 5] = dy, dz, h

    @jit
    def arrays(p, R, S, P, X, Y, Z, out):              # p (3, n), R (9, n), out (6, 6, n)
        p0, p1, p2 = p[0], p[1], p[2]
        R0, R1, R2, R3, R4, R5, R6, R7, R8 = R[0], R[1], R[2], R[3], R[4], R[5], R[6], \
            R[7], R[8]
        for i in range(6):
            s, Pi = (S[i, 0], S[i, 1], S[i, 2]), (P[i, 0], P[i, 1], P[i, 2])
            Xi, Yi, Zi = (X[i, 0], X[i, 1], X[i, 2]), (Y[i, 0], Y[i, 1], Y[i, 2]), \
                (Z[i, 0], Z[i, 1], Z[i, 2])
            o0, o1, o2, o3, o4, o5 = out[i, 0], out[i, 1], out[i, 2], out[i, 3], out[i, 4], \
                out[i, 5]
            for k in range(p0.shape[0]):
                _, d, length, _, _, dx, dy, dz, h = geometry(
                    (p0[k], p1[k], p2[k]), ((R0[k], R1[k], R2[k]), (R3[k], R4[k], R5[k]),
                                            (R6[k], R7[k], R8[k])), s, Pi, Xi, Yi, Zi)
                o0[k], o1[k], o2[k], o3[k], o4[k], o5[k] = length, d[2], dx, dy, dz, h

    q = robot.home_pose() + 0.05 * np.sin(np.outer(np.arange(n) * 1e-3, np.arange(1, 10)))
    qT = q.T
    R = np.array([np.asarray(x) for row in F.attitude(qT)[0] for x in row])     # (9, n)
    p = np.ascontiguousarray(qT[:3])
    pN, RN = np.ascontiguousarray(p.T), np.ascontiguousarray(R.T)
    a, b = np.empty((n, 6, 6)), np.empty((6, 6, n))
    sec_a = best_of(lambda: per_sample(pN, RN, S, P, X, Y, Z, a))
    sec_b = best_of(lambda: arrays(p, R, S, P, X, Y, Z, b))
    ref = np.array([[x[2], x[1][2], x[5], x[6], x[7], x[8]] for x in (
        F.leg_geometry(tuple(p), tuple(map(tuple, R.reshape(3, 3, n))), S[i], P[i], X[i],
                       Y[i], Z[i]) for i in range(6))])                           # (6, 6, n)
    same = np.array_equal(a.transpose(1, 2, 0), b) and np.array_equal(ref, b)
    print(f"legs' geometry: per sample and structure of arrays bit for bit equal (and to "
          f"the NumPy backend): {same}; structure of arrays {sec_a / sec_b:.2f}x faster")
    if not same:
        raise SystemExit("the two layouts disagree: a bug in this benchmark")
    count, nbytes = _flops.legs_geometry(robot), (12 + 36) * 8
    return {"legs' geometry, per sample": (count, sec_a / n, nbytes),
            "legs' geometry, arrays": (count, sec_b / n, nbytes)}
    # bytes: the pose in (p 3, R 9 doubles), 6 numbers a leg out


def floor_us(robot, n: int) -> float:
    """Pinocchio's rneaInParallel (1 thread, tree states given) per sample [µs]."""
    from bench import floor_call, trajectory

    q, qd, qdd = trajectory(n)
    return best_of(floor_call(robot, q, qd, qdd)) / n * 1e6


def main(argv=None) -> int:
    import offshore_crane as oc
    from offshore_crane.dynamics import warm_up

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=100_000, help="samples per timing")
    add_save_option(p, "roofline")
    args = p.parse_args(argv)
    robot = oc.load_robot()
    warm_up(robot, methods=("kane", "kane-explicit"))
    peak, bw, width = peak_gflops(), bandwidth_gbs(), vector_width()
    scalar = peak / width
    print(f"machine: one core's peak {peak:.1f} GFLOP/s (BLAS dgemm), vector width {width} "
          f"doubles -> scalar roof {scalar:.1f} GFLOP/s; memory copy {bw:.1f} GB/s")
    floor = floor_us(robot, args.n)
    print(f"reference: Pinocchio rneaInParallel(1) {floor:.3f} µs a sample (N = {args.n})")
    head = (f"{'kernel':<27}{'flop/sample':>12}{'sin,cos':>8}{'µs/sample':>11}"
            f"{'GFLOP/s':>9}{'% peak':>8}{'% scalar':>9}{'flop/B':>8}  verdict")
    print(head)
    rows = []
    for name, (count, sec, nbytes) in kernels(robot, args.n).items():
        flop = count["flop"]
        rate = flop / sec / 1e9
        intensity = flop / nbytes
        memory_roof = intensity * bw
        if memory_roof < peak and rate >= 0.5 * memory_roof:
            verdict = "memory-bound"
        elif rate >= 0.5 * peak:
            verdict = "compute-bound"
        elif rate < scalar:
            verdict = "latency-bound (scalar chains; vector units idle)"
        else:
            verdict = "partly vectorised (above the scalar roof, under half the peak)"
        rows.append(dict(kernel=name, flop=flop, trig=count["sin"] + count["cos"]
                         + count["atan2"], us=sec * 1e6, gflops=rate,
                         peak_share=rate / peak, scalar_share=rate / scalar,
                         intensity=intensity, verdict=verdict))
        r = rows[-1]
        print(f"{name:<27}{flop:>12d}{r['trig']:>8d}{r['us']:>11.3f}{rate:>9.2f}"
              f"{100 * rate / peak:>8.1f}{100 * rate / scalar:>9.1f}{intensity:>8.1f}  "
              f"{verdict}")
    if args.save:
        save("roofline", dict(**stamp(), n=args.n, peak_gflops=peak, bandwidth_gbs=bw,
                              vector_width=width, floor_us=floor, kernels=rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
