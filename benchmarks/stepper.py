"""The stepper's overhead (issue 38: at most 1.5 x the compiled run of the same law and
plant at 100 Hz control): a run stepped from Python one control period at a time against
the same run inside ``simulate``, in one process.

    python benchmarks/stepper.py [--repeats 3] [--save]

For each plant: the built-in computed torque sampled at 100 Hz (held between control
instants, RK4 at the plant's 1 ms step) run by ``simulate`` (the compiled driver, its
workspace check on the record as the run goes); then its commands at the control
instants replayed through a :class:`~offshore_crane.simulation.stepper.Stepper` (one
``step`` a period, its workspace check after each), which gives the same run (the
largest |Δq| is printed and saved). Timed after a warm-up; medians of ``--repeats``.

1. ``rigid``: the rigid robot along Table 1, 10 s;
2. ``elastic``: ``scenes/compensated_lift.toml`` (the elastic cable, its winch and the
   compensated reference, as ``simulate --scene`` sets it up), 10 s.

``--save`` writes ``benchmarks/results/stepper.json``, from which ``python
scripts/figures.py`` writes the figure of docs/simulation.md ("A simulation you step").
"""

from __future__ import annotations

import dataclasses
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from _saved import benchmark_parser, cpu_busy, save, stamp  # noqa: E402  (benchmarks/ is on the path)
import offshore_crane as oc  # noqa: E402
from offshore_crane import scenes  # noqa: E402
from offshore_crane.motion.trajectories import table1  # noqa: E402
from offshore_crane.simulation.stepper import Stepper  # noqa: E402

PERIOD = 0.01           # [s]: 100 Hz control
SECONDS = 10.0          # simulated a run
TARGET = 1.5            # the stepper's time over the compiled run's


def _cases():
    """``{name: (compiled run(seconds) -> SimulationResult, stepper(seconds) ->
    Stepper)}``: the same plant, reference and law for both."""
    robot = oc.load_robot()
    sampled = oc.Controller(rate=1.0 / PERIOD)
    path = ROOT / "scenes" / "compensated_lift.toml"
    scene = scenes.load_scene(path)
    lift = scenes.load_robot(scene)
    traj, options = scenes.cable_simulation(scene, lift, scenes.load_trajectory(scene, lift))
    law = dataclasses.replace(scenes.controller(scene, lift), rate=1.0 / PERIOD)
    extras = scenes.instruments(scene)
    q0, qd0, _ = (x[0] for x in traj.reference(traj.t[:1]))
    from offshore_crane.simulation.elastic import simulate_elastic

    def elastic(seconds):
        return simulate_elastic(lift, seconds, traj.reference, q0=q0.copy(), qd0=qd0,
                                controller=law, gravity=scene.gravity,
                                step=scene.control.get("step", 1e-3), t0=float(traj.t[0]),
                                **options, **extras)

    return {
        "rigid": (lambda s: oc.simulate(robot, s, table1, step=1e-3, controller=sampled),
                  lambda s: Stepper(robot, s, table1, control_period=PERIOD)),
        "elastic": (elastic, lambda s: scenes.stepper(path, control_period=PERIOD,
                                                      duration=s)),
    }


def _replay(sim, actions) -> float:
    """Wall seconds of ``sim.reset()`` and one ``step`` per action row."""
    t0 = time.perf_counter()
    sim.reset()
    for a in actions:
        sim.step(a)
    return time.perf_counter() - t0


def measure(repeats: int) -> dict:
    """Per plant: the compiled run's and the stepper's wall seconds (medians), their
    ratio, the largest |Δq| between the two records, the others' load [cores]."""
    out = {}
    for name, (compiled, stepper) in _cases().items():
        compiled(2 * PERIOD)                            # warm-ups (compiles, caches)
        _replay(stepper(2 * PERIOD), np.zeros((2, 9)))
        w0, m0, a0 = time.perf_counter(), time.process_time(), cpu_busy()
        walls, steps = [], []
        for _ in range(repeats):
            t0 = time.perf_counter()
            res = compiled(SECONDS)
            walls.append(time.perf_counter() - t0)
            every = int(round(PERIOD / res.step))
            actions = res.X_cmd[::every][:int(round(SECONDS / PERIOD))]
            sim = stepper(SECONDS)
            if len(sim.action_names) != actions.shape[1]:
                raise SystemExit(f"{name}: the stepper takes {len(sim.action_names)} "
                                 f"forces, the run recorded {actions.shape[1]}")
            steps.append(_replay(sim, actions))
        wall = time.perf_counter() - w0
        others = max(0.0, ((cpu_busy() - a0) - (time.process_time() - m0)) / wall)
        rec = sim.record()
        n = min(len(rec.q), len(res.q))
        out[name] = {"compiled_s": statistics.median(walls),
                     "stepper_s": statistics.median(steps),
                     "ratio": statistics.median(steps) / statistics.median(walls),
                     "dq_max": float(np.abs(rec.q[:n] - res.q[:n]).max()),
                     "periods": int(round(SECONDS / PERIOD)), "others_cores": others}
        r = out[name]
        print(f"  {name}: compiled {r['compiled_s'] * 1e3:.1f} ms, stepper "
              f"{r['stepper_s'] * 1e3:.1f} ms ({r['ratio']:.2f} x; target <= {TARGET:g}); "
              f"max |dq| {r['dq_max']:.1e}", flush=True)
    return out


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "stepper", repeats=3)
    args = parser.parse_args(argv)
    rows = measure(args.repeats)
    if args.save:
        save("stepper", {**stamp(), "repeats": args.repeats, "period_s": PERIOD,
                         "seconds": SECONDS, "target": TARGET, "rows": rows})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
