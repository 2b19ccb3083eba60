"""Forward dynamics and simulation speed: ours against Pinocchio's closed-loop forward
dynamics on the robot's tree, side by side in one run (issue 13's speed targets).

    python benchmarks/pinocchio_fd.py [--samples N] [--repeats R]

On Table 1's states (every ``3142 // N``-th sample) with X from the Kane inverse
dynamics, one Pinocchio call per sample from Python (Pinocchio has no batched form):

- ``constraintDynamics``: the six CONTACT_3D loop constraints of
  :mod:`offshore_crane.reference.constrained`, tree states precomputed (the reference
  against which the other rows' ratios are given);
- ``lcaba``: the same constraints after ``computeJointMinimalOrdering``, on its own
  ``Data`` and ``RigidConstraintData`` (in pin 4.1 lcaba leaves a nonzero
  ``contact_acceleration_desired`` in the constraint data, which a later
  ``constraintDynamics`` on the same data takes as the target relative acceleration,
  even after ``initConstraintDynamics``: errors of tens of percent), for a few proximal
  ``mu`` (lcaba needs mu > 0; its round-off grows like eps/mu, its passes with mu);
- the loop-closure solve alone (:func:`tree_states`), and the whole reference
  (:func:`constrained_dynamics`: tree solve + constraintDynamics + residual checks);
- ours: :func:`offshore_crane.forward_dynamics` batched at N = 10⁴ (Table 1 states) and
  one sample per call from Python, and ``simulate`` of 60 s at 1 kHz (RK4, built-in
  computed torque, compiled) as a real-time factor, and the same law as a Python
  callable (a user's controller: RK4 driven from Python, 10 s).

The targets (ours batched ≤ 0.5 × constraintDynamics' call, ours single ≤ 1 ×, real-time
factor ≥ 10) are printed with the measured ratios.

Each Pinocchio call is timed alone (``perf_counter_ns``); the Python-level functions are
timed per batch and divided by N. Medians and minima over ``R`` repeats are printed, with
each row's error against the Kane accelerations (max over samples of |Δq̈| / max |q̈ with
X = 0|, the scale of the forces in the equation).
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

try:
    import offshore_crane as oc
except ImportError:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
    import offshore_crane as oc
from offshore_crane.reference import constrained as C

from _saved import benchmark_parser, save, stamp  # noqa: E402  (benchmarks/ is on the path)

#: lcaba's proximal regularisations to try: Pinocchio's docstring suggests 1e-6.
LCABA_MU = (1e-8, 1e-6, 1e-4, 1e-2)


def per_call(fn, n: int, repeats: int) -> np.ndarray:
    """Durations [s] of ``fn(k)`` for k < n, ``repeats`` times: ``(repeats, n)``."""
    out = np.empty((repeats, n))
    clock = time.perf_counter_ns
    for r in range(repeats):
        for k in range(n):
            t0 = clock()
            fn(k)
            out[r, k] = clock() - t0
    return out * 1e-9


def per_batch(fn, n: int, repeats: int) -> np.ndarray:
    """Per-sample durations [s] of ``fn()`` on n samples, ``repeats`` times: ``(repeats,)``."""
    out = np.empty(repeats)
    for r in range(repeats):
        t0 = time.perf_counter()
        fn()
        out[r] = (time.perf_counter() - t0) / n
    return out


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "pinocchio_fd")
    parser.add_argument("--samples", type=int, default=300, help="states timed (default 300)")
    parser.add_argument("--repeats", type=int, default=5, help="repeats (default 5)")
    args = parser.parse_args(argv)
    import pinocchio as pin

    # One core for every timing, ours and Pinocchio's: on this 2-core VM an unpinned
    # process sometimes runs ~1.5x slower for its whole life (benchmarks/simulation.py's
    # forward_dynamics_rows says how it was measured).
    os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})

    robot = oc.load_robot()
    t = oc.motion.trajectories.time_grid()
    q, qd, qdd = oc.motion.trajectories.table1(t)
    step = max(1, len(t) // args.samples)
    q, qd, qdd = q[::step][:args.samples], qd[::step][:args.samples], qdd[::step][:args.samples]
    n = len(q)
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    free = C.forward_dynamics(robot, q, qd, np.zeros_like(X))
    scale = np.abs(free).max()

    tree = C.loop_tree(robot)                   # the reference's Pinocchio objects
    model = tree.model
    model.gravity = pin.Motion(np.array([0.0, 0.0, -9.81]), np.zeros(3))
    states = C.tree_states(robot, q, qd)
    tau = np.zeros((n, model.nv))
    tau[:, tree.act] = X[:, tree.act_columns]
    rows = []

    def error(a) -> float:
        return float(np.abs(a[:, tree.indep] - qdd).max() / scale)

    prox = pin.ProximalSettings(C.ACCURACY, C.ACCURACY, C.PROXIMAL_MU, C.PROXIMAL_MAX_ITER)
    cd = np.empty((n, model.nv))

    def constraint_dynamics(k):
        cd[k] = pin.constraintDynamics(model, tree.data, states.q[k], states.v[k], tau[k],
                                       tree.cmodels, tree.cdatas, prox)

    per_call(constraint_dynamics, n, 1)           # warm-up (the first pass of a process)
    ref = per_call(constraint_dynamics, n, args.repeats)
    rows.append(("constraintDynamics (mu = 0)", ref.sum(axis=1) / n, ref, error(cd)))

    data = model.createData()                   # lcaba's own Data and constraint data
    cmodels = pin.StdVec_RigidConstraintModel()
    cdatas = pin.StdVec_RigidConstraintData()
    for cm in tree.cmodels:
        cmodels.append(pin.RigidConstraintModel(cm))
        cdatas.append(cm.createData())
    pin.computeJointMinimalOrdering(model, data, cmodels)
    for mu in LCABA_MU:
        lprox = pin.ProximalSettings(C.ACCURACY, C.ACCURACY, mu, C.PROXIMAL_MAX_ITER)
        la = np.empty((n, model.nv))
        passes = []

        def lcaba(k, lprox=lprox, la=la, passes=passes):
            la[k] = pin.lcaba(model, data, states.q[k], states.v[k], tau[k], cmodels, cdatas,
                              lprox)
            passes.append(lprox.iter)

        d = per_call(lcaba, n, args.repeats)
        rows.append((f"lcaba (mu = {mu:.0e}, {max(passes)} passes max)", d.sum(axis=1) / n, d,
                     error(la)))
    before = cd.copy()
    per_call(constraint_dynamics, n, 1)           # unaffected by lcaba on its own Data?
    assert np.array_equal(cd, before), "constraintDynamics changed after lcaba"

    d = per_batch(lambda: C.tree_states(robot, q, qd), n, args.repeats)
    rows.append(("tree_states (Newton loop closure)", d, None, float("nan")))
    result = [None]

    def whole():
        result[0] = C.constrained_dynamics(robot, q, qd, X)

    d = per_batch(whole, n, args.repeats)
    rows.append(("constrained_dynamics (tree + FD + checks)", d, None, error(result[0].a)))
    d = per_batch(lambda: oc.inverse_dynamics(robot, q, qd, qdd), n, args.repeats)
    rows.append((f"Kane inverse_dynamics, batched N = {n}", d, None, float("nan")))

    fd = oc.forward_dynamics
    d = per_call(lambda k: fd(robot, q[k], qd[k], X[k]), n, args.repeats)
    ours_single = np.median(d)
    rows.append(("Kane forward_dynamics, one sample per call", d.sum(axis=1) / n, d,
                 error_of(fd(robot, q, qd, X), qdd, scale)))
    tb = oc.motion.trajectories.time_grid(100.0, 100.0)[:10_000]           # N = 10^4
    qb, qdb, qddb = oc.motion.trajectories.table1(tb)
    Xb = oc.inverse_dynamics(robot, qb, qdb, qddb)
    d = per_batch(lambda: fd(robot, qb, qdb, Xb), len(tb), args.repeats)
    ours_batch = np.median(d)
    rows.append((f"Kane forward_dynamics, batched N = {len(tb)}", d, None,
                 error_of(fd(robot, qb, qdb, Xb), qddb, np.abs(fd(robot, qb, qdb,
                                                                 0 * Xb)).max())))

    from offshore_crane.simulation.rigid import simulate

    simulate(robot, 0.01, oc.motion.trajectories.table1)                   # load the loop
    walls = []
    for _ in range(max(1, args.repeats // 2)):
        t0 = time.perf_counter()
        simulate(robot, 60.0, oc.motion.trajectories.table1, step=1e-3)
        walls.append(time.perf_counter() - t0)
    rtf = 60.0 / min(walls)
    kp, kd = 400.0, 40.0                    # the built-in computed torque's default gains

    def python_law(t, q, qd, q_ref, qd_ref, qdd_ref):
        return oc.inverse_dynamics(robot, q, qd, qdd_ref + kd * (qd_ref - qd)
                                   + kp * (q_ref - q))

    t0 = time.perf_counter()
    simulate(robot, 10.0, oc.motion.trajectories.table1, step=1e-3, controller=python_law)
    rtf_python = 10.0 / (time.perf_counter() - t0)

    base = np.median(ref)
    print(f"pin {pin.__version__}, {n} Table 1 states, {args.repeats} repeats; "
          "times per sample [µs]")
    print(f"{'path':<46}{'median':>9}{'min':>9}{'call med':>10}{'call min':>10}"
          f"{'ratio':>8}{'error':>10}")
    for name, batch, calls, err in rows:
        cm = f"{np.median(calls) * 1e6:10.1f}{calls.min() * 1e6:10.1f}" if calls is not None \
            else " " * 20
        ratio = (np.median(calls) if calls is not None else np.median(batch)) / base
        print(f"{name:<46}{np.median(batch) * 1e6:9.1f}{batch.min() * 1e6:9.1f}{cm}"
              f"{ratio:8.2f}{err:10.1e}")
    print("median/min: per-sample time of a whole pass (median, minimum over repeats);"
          " call med/min: single calls; ratio: median against constraintDynamics' call; "
          "error: max |Δq̈| / max |q̈ with X = 0| against the Kane accelerations")
    print(f"\nsimulate 60 s at 1 kHz (RK4, computed torque, compiled): "
          f"{min(walls):.2f} s (best of {len(walls)}), real-time factor {rtf:.1f}")
    print(f"the same law written in Python (a user's controller, RK4 driven from Python, "
          f"10 s at 1 kHz): real-time factor {rtf_python:.2f}")
    print("\n| target | measured | met |\n| --- | --- | --- |")
    for label, value, limit in (
            ("forward dynamics batched (N = 10⁴) ≤ 0.5 × constraintDynamics call",
             ours_batch / base, 0.5),
            ("forward dynamics, one sample ≤ 1 × constraintDynamics call",
             ours_single / base, 1.0)):
        print(f"| {label} | {value:.2f} × | {value <= limit} |")
    print(f"| simulate 60 s at 1 kHz, real-time factor ≥ 10 | {rtf:.1f} | {rtf >= 10} |")
    if args.save:
        save("pinocchio_fd", {**stamp(), "pin": pin.__version__, "samples": n,
                              "repeats": args.repeats, "constraint_call_s": base,
                              "batch_s": ours_batch, "single_s": ours_single,
                              "simulate_60s_s": min(walls), "rtf": rtf,
                              "rtf_python": rtf_python})
    return 0


def error_of(a, b, scale) -> float:
    """max |a − b| / scale."""
    return float(np.abs(a - b).max() / scale)


if __name__ == "__main__":
    sys.exit(main())
