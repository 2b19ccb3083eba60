"""How closely MuJoCo simulates the exported MJCF model (docs/mjcf.md, issue 16 part 3).

Prints, for the shipped descriptions and models written at the home pose and at a
rotated pose:

- the agreement of MuJoCo's forward dynamics with ours at our exact states under our
  inverse-dynamics X: per coordinate, max |q̈_MuJoCo - q̈_ours| over the largest
  acceleration the loop constraints produce (``MujocoForward.agreement``), its maximum
  over the coordinates, against ``offshore_crane.outputs.export.mjcf.AGREEMENT``;
- what a 1 % and a 3 % error in the upper leg links' mass gives in the same measure (the
  comparison's resolution);
- the drift of the platform over 1 s of MuJoCo simulation from the keyframe 'hold'
  (our static X as ctrl), and the time per ``mj_forward`` call.

Run: ``PYTHONPATH=src python benchmarks/mjcf_agreement.py`` (needs mujoco).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

import offshore_crane as oc
from offshore_crane.motion import trajectories
from offshore_crane.outputs.export import mjcf
from offshore_crane.robot.kinematics import legs

from _saved import benchmark_parser, save, stamp  # noqa: E402  (benchmarks/ is on the path)

HARIB = str(Path(__file__).resolve().parents[1] / "models" / "descriptions"
            / "harib_srinivasan_2003.toml")


def states(robot, n: int, seed: int):
    """Table 1 for the lab robot; seeded states near home for a robot whose workspace
    Table 1 leaves (every leg in its stroke)."""
    if robot.spec.name == "lab":
        t = np.linspace(0.0, 10 * np.pi, n)
        return "Table 1", trajectories.table1(t)
    rng = np.random.default_rng(seed)
    scale = np.array([0.01, 0.01, 0.01, 0.05, 0.05, 0.05, 0, 0, 0])
    q = rng.uniform(-1, 1, (4 * n, 9)) * scale
    q[:, 2] += robot.home_height
    length = legs(robot, q).length
    stroke = robot.hybrid.stroke
    q = q[np.all((length > stroke[:, 0]) & (length < stroke[:, 1]), axis=1)][:n]
    arm = np.arange(9) < 6
    return "random near home", (q, rng.uniform(-0.3, 0.3, q.shape) * arm,
                                rng.uniform(-2, 2, q.shape) * arm)


def agreement(robot, model, q, qd, qdd):
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    ours = oc.forward_dynamics(robot, q, qd, X)
    res = mjcf.forward(model, robot, q, qd, X)
    return res.agreement(ours), res.loop.max()


def main() -> None:
    import mujoco

    parser = benchmark_parser(__doc__, "mjcf_agreement")
    args = parser.parse_args()
    saved = {**stamp(), "mujoco": mujoco.__version__, "agreement": mjcf.AGREEMENT}

    print(f"mujoco {mujoco.__version__}; AGREEMENT = {mjcf.AGREEMENT:g}; solimp "
          f"{mjcf.SOLIMP}, solref {mjcf.SOLREF}, timestep {mjcf.TIMESTEP} s")
    worst = 0.0
    for desc in (None, HARIB):
        robot = oc.load_robot(desc)
        name, (q, qd, qdd) = states(robot, 200, seed=1)
        poses = {"home": None,
                 "rotated": np.array([0.005, -0.005, robot.home_height + 0.005, 0.04,
                                      -0.03, 0.05, 1.0, -0.5, 0.05]),
                 "sample 0": q[0]}
        for label, pose in poses.items():
            model = mjcf.export(robot, pose)
            ratio, loop = agreement(robot, model, q, qd, qdd)
            worst = max(worst, ratio.max())
            saved.setdefault("ratios", {})[f"{robot.spec.name}, {label}"] = ratio.max()
            print(f"{robot.spec.name:<26} written at {label:<8} {name:<17} N = {len(q)}: "
                  f"max ratio {ratio.max():.3g} (per q: "
                  f"{' '.join(f'{r:.2g}' for r in ratio[:9])}); loops {loop:.1e} m")
    print(f"worst ratio {worst:.3g}: AGREEMENT is {mjcf.AGREEMENT / worst:.1f} x above it")
    saved["worst"] = worst

    robot = oc.load_robot()
    name, (q, qd, qdd) = states(robot, 50, seed=1)
    for factor in (1.01, 1.03):
        wrong = oc.load_robot(overrides={"legs.upper.mass":
                                         factor * robot.hybrid.upper_mass[0]})
        ratio, _ = agreement(robot, mjcf.export(wrong), q, qd, qdd)
        print(f"upper leg links {100 * (factor - 1):.0f} % heavier in the MuJoCo model: "
              f"ratio {ratio.max():.3g} ({ratio.max() / mjcf.AGREEMENT:.1f} x AGREEMENT)")

    for desc in (None, HARIB):
        robot = oc.load_robot(desc)
        model = mjcf.export(robot)
        m, d = mjcf.load(model)
        mujoco.mj_resetDataKeyframe(m, d, 0)
        start = d.qpos[:6].copy()
        for _ in range(round(1.0 / m.opt.timestep)):
            mujoco.mj_step(m, d)
        drift = np.abs(d.qpos[:6] - start)
        print(f"{robot.spec.name:<26} hold 1 s: platform drift {drift[:3].max():.2g} m, "
              f"{drift[3:].max():.2g} rad")
        n = 2000
        t0 = time.perf_counter()
        for _ in range(n):
            mujoco.mj_forward(m, d)
        print(f"{robot.spec.name:<26} mj_forward {1e6 * (time.perf_counter() - t0) / n:.1f} "
              "us a call")
    if args.save:
        save("mjcf_agreement", saved)


if __name__ == "__main__":
    main()
