"""One right-hand side of the simulation on an elastic cable: the compiled kernel against
the Python plant it replaces, in one run.

    python benchmarks/elastic_plant.py [--calls 2000] [--repeats 5]

The plant of ``simulate_elastic`` (2 kg on 1 m of EA 2e4 N with 3 N·s/m of axial damping,
the sway damped at 20 % of critical and 0.5 m² of drag area: every branch of the
right-hand side taken) at one taut state near home under a winch rate: the time of one
``ẏ`` by :class:`offshore_crane.simulation.elastic.PythonPlant` (``derivative``: NumPy and
one-sample compiled calls) and by :class:`offshore_crane.dynamics.cable.elastic_plant.
ElasticPlant` (one kernel call), each the median over ``--repeats`` of the mean of
``--calls`` calls (a tenth of them for the Python plant), after a warm-up; and the same
for the computed-torque law (the load cell and the Kane pass with its pull). Prints the
times and their ratios; writes nothing.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np


def _timed(call, calls: int, repeats: int) -> float:
    """Median over ``repeats`` of the mean time of ``calls`` calls [s]."""
    call()
    runs = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(calls):
            call()
        runs.append((time.perf_counter() - t0) / calls)
    return statistics.median(runs)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--calls", type=int, default=2000)
    p.add_argument("--repeats", type=int, default=5)
    args = p.parse_args(argv)

    import offshore_crane as oc
    from offshore_crane.conventions import GRAVITY
    from offshore_crane.dynamics.cable.elastic_plant import ElasticPlant
    from offshore_crane.dynamics.cable.tip import tip_positions
    from offshore_crane.simulation.elastic import PythonPlant

    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0,
                                     "payload.sway_damping": 0.2 * 2.0 * np.sqrt(9.81),
                                     "payload.drag_area": 0.5})
    empty = robot.without_hanging_payload()
    g = np.asarray(GRAVITY, dtype=float)
    ref = PythonPlant(robot, empty, 2e4, 3.0, g)
    plant = ElasticPlant(robot, 2e4, 3.0, g, empty=empty)
    rng = np.random.default_rng(37)
    q = robot.home_pose() + rng.uniform(-0.02, 0.02, 9)
    qd = rng.uniform(-0.3, 0.3, 9)
    p_tip, v_tip = (x[0] for x in tip_positions(robot, q[None], qd[None]))
    y = np.concatenate([q, p_tip + [0.05, -0.03, -1.0005], qd, v_tip + [0.1, 0.0, -0.05]])
    L, Ld = 1.0, 0.1
    cmd = rng.uniform(-2.0, 2.0, 9)
    plant.measure(y, L, Ld)
    X = plant.computed_torque(y, cmd, np.empty(9)).copy()
    out, Xc = np.empty(24), np.empty(9)
    assert ref.derivative(y, X, L, Ld)[1] > 0.0, "the benchmark's cable should be taut"

    def ct_python():
        pull, at = ref.cable(y, L, Ld)[:2]
        return ref.pulled(y[:9], y[12:21], cmd, pull, at)

    def ct_compiled():
        plant.measure(y, L, Ld)
        return plant.computed_torque(y, cmd, Xc)

    n, r = args.calls, args.repeats
    rows = [("derivative", _timed(lambda: ref.derivative(y, X, L, Ld), max(n // 10, 1), r),
             _timed(lambda: plant.derivative(y, X, L, Ld, out), n, r)),
            ("computed torque", _timed(ct_python, max(n // 10, 1), r),
             _timed(ct_compiled, n, r))]
    for name, python, compiled in rows:
        print(f"{name}: Python {python * 1e6:.1f} µs, compiled {compiled * 1e6:.2f} µs a "
              f"call: {python / compiled:.1f}x")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
