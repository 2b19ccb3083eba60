"""The Gymnasium environment's speed (issue 38): the elastic compensated lift at 100 Hz
control against real time on one core (target >= 30 x), and a vectorised environment of
16 seeds on 2 worker processes against 1 (target >= 1.6 x the steps per second), in one
process.

    python benchmarks/gym.py [--repeats 3] [--save]

The actions are the built-in computed torque's commands at the control instants, taken
from its compiled run of the lift (as ``benchmarks/stepper.py`` takes them), replayed
through ``gymnasium.make("offshore_crane.gym:CraneLift-v0", ...)`` (with the default
reward and Gymnasium's wrappers): the same run (its largest |Δq| from the compiled one is
printed and saved). The agent's own time is not counted: what is timed is the
environment's ``reset`` and ``step``.

1. ``env``: one environment, 10 s of the lift (1000 steps): real-time factor, and its
   time over the bare stepper's replay of the same actions;
2. ``vector``: :class:`~offshore_crane.gym.CraneLiftVector` of 16 environments (2 s
   each, the same actions in every one), stepped with ``workers=1`` (all in this
   process) and ``workers=2`` (this process and one worker process, 8 each) after their
   start and a first episode not timed (the processes' first pass touches their memory),
   the two vectors timed in turn, an episode each a repeat: steps per second of each and
   their ratio.

``--save`` writes ``benchmarks/results/gym.json``, from which ``python
scripts/figures.py`` writes the figures of docs/control.md ("Speed").
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
from offshore_crane import scenes  # noqa: E402

PERIOD = 0.01               # [s]: 100 Hz control
SECONDS = 10.0              # simulated by the single environment
VECTOR_SECONDS = 2.0        # simulated by each of the vector's environments
ENVS = 16
TARGETS = {"rtf": 30.0, "scaling": 1.6}
SCENE = ROOT / "scenes" / "compensated_lift.toml"


def commands(seconds: float) -> np.ndarray:
    """``(periods, 9)`` [N·m, N]: the scene's computed torque sampled at 100 Hz, its
    commands at the control instants of its compiled run (and that run's q)."""
    from offshore_crane.simulation.elastic import simulate_elastic

    scene = scenes.load_scene(SCENE)
    lift = scenes.load_robot(scene)
    traj, options = scenes.cable_simulation(scene, lift, scenes.load_trajectory(scene, lift))
    law = dataclasses.replace(scenes.controller(scene, lift), rate=1.0 / PERIOD)
    q0, qd0, _ = (x[0] for x in traj.reference(traj.t[:1]))
    res = simulate_elastic(lift, seconds, traj.reference, q0=q0.copy(), qd0=qd0,
                           controller=law, gravity=scene.gravity,
                           step=scene.control.get("step", 1e-3), t0=float(traj.t[0]),
                           **options, **scenes.instruments(scene))
    every = int(round(PERIOD / res.step))
    return res.X_cmd[::every][:int(round(seconds / PERIOD))], res.q


def single(actions: np.ndarray, q_ref: np.ndarray, repeats: int) -> dict:
    """The environment's real-time factor, its time over the stepper's, |Δq|."""
    import gymnasium

    import offshore_crane.gym  # noqa: F401  (registers the id)

    env = gymnasium.make("offshore_crane.gym:CraneLift-v0", scene=SCENE,
                         control_period=PERIOD, duration=SECONDS)
    sim = scenes.stepper(SCENE, control_period=PERIOD, duration=SECONDS)
    env.reset(seed=0)
    env.step(actions[0])                    # warm-ups
    sim.reset()
    sim.step(actions[0])
    walls, bare = [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        env.reset(seed=0)
        for a in actions:
            env.step(a)
        walls.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        sim.reset()
        for a in actions:
            sim.step(a)
        bare.append(time.perf_counter() - t0)
    rec = env.unwrapped.sim.record()
    n = min(len(rec.q), len(q_ref))
    wall = statistics.median(walls)
    return {"env_s": wall, "stepper_s": statistics.median(bare), "rtf": SECONDS / wall,
            "over_stepper": wall / statistics.median(bare),
            "dq_max": float(np.abs(rec.q[:n] - q_ref[:n]).max()),
            "steps": len(actions)}


def vector(actions: np.ndarray, repeats: int) -> dict:
    """Steps per second of 16 environments on 1 and on 2 workers, both vectors open and
    timed in turn (each repeat one episode of each: the machine's moods fall on both)."""
    from offshore_crane.gym import CraneLiftVector

    vecs = {}
    try:
        for workers in (1, 2):
            vecs[workers] = CraneLiftVector(num_envs=ENVS, workers=workers, scene=SCENE,
                                            control_period=PERIOD,
                                            duration=VECTOR_SECONDS)
        walls = {w: [] for w in vecs}
        for k in range(repeats + 1):          # the first: a warm-up, not timed
            for workers, vec in vecs.items():
                vec.reset(seed=0)
                t0 = time.perf_counter()
                for a in actions:
                    vec.step(np.tile(a, (ENVS, 1)))
                if k:
                    walls[workers].append(time.perf_counter() - t0)
    finally:
        for vec in vecs.values():
            vec.close()
    out = {w: ENVS * len(actions) / statistics.median(x) for w, x in walls.items()}
    return {"steps_per_s_1": out[1], "steps_per_s_2": out[2],
            "scaling": out[2] / out[1], "envs": ENVS, "steps": len(actions)}


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "gym", repeats=3)
    args = parser.parse_args(argv)
    w0, m0, a0 = time.perf_counter(), time.process_time(), cpu_busy()
    actions, q = commands(SECONDS)
    env = single(actions, q, args.repeats)
    print(f"  env: {env['rtf']:.1f} x real time (target >= {TARGETS['rtf']:g}), "
          f"{env['over_stepper']:.2f} x the bare stepper, max |dq| {env['dq_max']:.1e}",
          flush=True)
    others = max(0.0, ((cpu_busy() - a0) - (time.process_time() - m0))
                 / (time.perf_counter() - w0))
    vec = vector(actions[:int(round(VECTOR_SECONDS / PERIOD))], args.repeats)
    print(f"  vector: {vec['steps_per_s_1']:.0f} steps/s on 1 worker, "
          f"{vec['steps_per_s_2']:.0f} on 2: {vec['scaling']:.2f} x (target >= "
          f"{TARGETS['scaling']:g})", flush=True)
    if args.save:
        save("gym", {**stamp(), "repeats": args.repeats, "period_s": PERIOD,
                     "seconds": SECONDS, "vector_seconds": VECTOR_SECONDS,
                     "targets": TARGETS, "env": env, "vector": vec,
                     "others_cores": others})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
