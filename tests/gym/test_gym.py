"""The Gymnasium environment (:mod:`offshore_crane.gym`): ``check_env`` on the rigid
robot, the hanging load and the elastic lift with a commanded winch; the same law through
``simulate``, the stepper and the environment gives one run; the default reward is its
formula on the record; bad input is refused in one line."""

from __future__ import annotations

import warnings
from pathlib import Path

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import offshore_crane as oc
import offshore_crane.gym  # noqa: F401  (registers CraneLift-v0)
from offshore_crane import scenes
from offshore_crane.conventions import QD_COLUMNS, Q_COLUMNS
from offshore_crane.errors import InputError
from offshore_crane.gym import CraneLift, LiftReward
from problems import computed_torque_law, simulated_on_scene

SCENES = Path(__file__).parents[2] / "scenes"
PERIOD = 0.01           # [s]: 100 Hz


def commanded_winch_lift(tmp_path) -> Path:
    """The compensated lift whose winch is an actuator the agent commands (its reflected
    mass given: the line pull ``Fw`` is the tenth force)."""
    text = (SCENES / "compensated_lift.toml").read_text()
    path = tmp_path / "commanded_lift.toml"
    path.write_text(text.replace("[actuators.winch]",
                                 "[actuators.winch]\nreflected_mass = 2.0", 1))
    return path


@pytest.mark.parametrize("scene", ["sea_state_crane.toml", "hanging_load.toml", "winch"])
def test_check_env_passes(scene, tmp_path):
    """Gymnasium's own checker on the three plants (warnings about unbounded
    observations and unnormalised forces are advice, SI units are the contract)."""
    path = commanded_winch_lift(tmp_path) if scene == "winch" else SCENES / scene
    env = gymnasium.make("offshore_crane.gym:CraneLift-v0", scene=path,
                         control_period=PERIOD, duration=0.05)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        check_env(env.unwrapped, skip_render_check=True)
    u = env.unwrapped
    assert env.action_space.shape == (len(u.action_names),)
    assert env.observation_space.shape == (len(u.observation_names),)
    if scene == "winch":
        assert u.action_names[-1] == "Fw" and "tension_N" in u.observation_names
        assert env.action_space.high[-1] == u.sim.plant.robot.winch.pull_max


@pytest.mark.parametrize("scene", ["hanging_load.toml", "compensated_lift.toml"])
def test_one_law_through_simulate_the_stepper_and_the_environment_is_one_run(scene):
    """The law sampled at 100 Hz: ``simulate`` (a Python law at that rate on the
    scene's inputs), the stepper and the environment (the law on its observations):
    q, q̇ and the forces bit for bit (the same loop; ≤ 1e-12 asked)."""
    path = SCENES / scene
    law = computed_torque_law(scenes.load_robot(scenes.load_scene(path)))
    want = simulated_on_scene(path, law, 0.2, PERIOD)[0]
    env = gymnasium.make("offshore_crane.gym:CraneLift-v0", scene=path,
                         control_period=PERIOD, duration=0.2)
    names = env.unwrapped.observation_names
    iq, iqd = ([names.index(c) for c in cols] for cols in (Q_COLUMNS, QD_COLUMNS))
    ir = [names.index(c.replace("_", "_ref_", 1)) for c in Q_COLUMNS]
    ird = [names.index(c.replace("_", "_ref_", 1)) for c in QD_COLUMNS]
    y, _ = env.reset(seed=0)
    done = False
    while not done:
        t, _, _, qddr = env.unwrapped.sim.reference_now
        y, r, term, trunc, info = env.step(law(t, y[iq], y[iqd], y[ir], y[ird], qddr))
        assert info["time"] == pytest.approx(t + PERIOD) and np.isfinite(r)
        done = term or trunc
    assert trunc and not term
    got = env.unwrapped.sim.record()
    for name in ("t", "q", "qd", "q_ref"):
        np.testing.assert_array_equal(getattr(got, name), getattr(want, name), err_msg=name)
    np.testing.assert_array_equal(got.X[:-1], want.X[:-1])


def test_the_default_reward_is_its_formula_on_the_record():
    """``LiftReward`` at each step against its formula on the run's record: the payload
    recorded (the elastic cable's state), the aim from the tip under the reference
    (``tip_positions``) hanging by the winch's length stretched by m|g|/EA, the forces
    applied over the period (the record's). 1e-12 relative: the environment's sums are
    ordered apart (its mean over the period, its squared norms)."""
    from offshore_crane.dynamics.cable.tip import tip_positions

    env = CraneLift(SCENES / "compensated_lift.toml", control_period=PERIOD, duration=0.1)
    reward = LiftReward(position_scale=0.02, effort_weight=0.5)
    law = computed_torque_law(env.sim.plant.robot)
    names = env.observation_names
    iq, iqd = ([names.index(c) for c in cols] for cols in (Q_COLUMNS, QD_COLUMNS))
    y, _ = env.reset()
    rewards, done = [], False
    while not done:
        t, qr, qdr, qddr = env.sim.reference_now
        y, _, term, trunc, _ = env.step(law(t, y[iq], y[iqd], qr, qdr, qddr))
        rewards.append(reward(env, y, None))
        done = term or trunc
    res = env.sim.record()
    plant, every = env.sim.plant, env.sim.control_steps
    k = np.arange(1, len(rewards) + 1) * every
    k[-1] = len(res) - 1
    p = res.info["payload"][k]
    g = plant.g
    L = plant.Lg[2 * k, 0] * (1 + plant.m * np.linalg.norm(g) / plant.ea)
    aim = tip_positions(plant.robot, res.q_ref[k])[0] + np.outer(L, g / np.linalg.norm(g))
    lo, hi = env.capacities
    X = np.array([res.X[j - every:j].mean(axis=0) for j in k])
    share = X / np.where(X < 0, -lo, hi)
    want = -PERIOD * (((p - aim) ** 2).sum(axis=1) / 0.02 ** 2
                      + 0.5 * (share ** 2).mean(axis=1))
    np.testing.assert_allclose(rewards, want, rtol=1e-12)
    assert np.abs(p - aim).max() < 0.01                # the lift holds its aim to 1 cm


def test_a_reward_of_ones_own_is_called_and_a_noise_seed_repeats_an_episode(tmp_path):
    """``reward=`` replaces the default; with sensors' noise, ``reset(seed)`` gives the
    same episode again and another seed another."""
    text = (SCENES / "hanging_load.toml").read_text() + (
        "\n[sensors]\nnoise_q = 1e-4\nseed = 1\n")
    path = tmp_path / "noisy.toml"
    path.write_text(text)
    calls = []
    env = gymnasium.make("offshore_crane.gym:CraneLift-v0", scene=path,
                         control_period=PERIOD, duration=0.05,
                         reward=lambda env, obs, action: calls.append(1) or 7.0)
    env.reset()
    y = env.unwrapped.sim.state
    hold = oc.inverse_dynamics(env.unwrapped.sim.plant.robot.without_hanging_payload(),
                               y[:9], np.zeros(9), np.zeros(9))

    def episode(seed):
        obs = [env.reset(seed=seed)[0]]
        for _ in range(3):
            o, r, *_ = env.step(hold)
            obs.append(o)
            assert r == 7.0
        return np.array(obs)
    a, b, c = episode(3), episode(3), episode(4)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c) and len(calls) == 9


def test_bad_input_is_refused_in_one_line():
    env = CraneLift(SCENES / "sea_state_crane.toml", control_period=PERIOD, duration=0.02)
    with pytest.raises(InputError, match=r"step\(\) before reset\(\)"):
        env.step(np.zeros(9))
    env.reset(seed=1)
    with pytest.raises(InputError, match=r"action of shape \(10,\): give 9 forces"):
        env.step(np.zeros(10))
    with pytest.raises(InputError, match=r"action T2 = inf at t = 0 s: give finite"):
        env.step(np.r_[0.0, np.inf, [0.0] * 7])
    with pytest.raises(InputError, match="render_mode = 'human': the environment draws"):
        CraneLift(SCENES / "sea_state_crane.toml", render_mode="human")
    with pytest.raises(InputError, match="reward = 3: give a callable"):
        CraneLift(SCENES / "sea_state_crane.toml", reward=3)
    with pytest.raises(InputError, match="control_period = 0.0015 s is not a whole"):
        CraneLift(SCENES / "sea_state_crane.toml", control_period=0.0015)
    with pytest.raises(InputError, match="position_scale = 0 m: give a positive"):
        LiftReward(position_scale=0)
    while True:
        *_, term, trunc, _ = env.step(np.zeros(9))
        if term or trunc:
            break
    with pytest.raises(InputError, match=r"step\(\) after the run .* call reset\(\)"):
        env.step(np.zeros(9))


def test_forces_beyond_capacity_are_clipped_or_refused_as_the_scene_says(tmp_path):
    """``[control] saturation = false``: a force beyond its capacity is refused; by
    default the scene's actuators saturate and the record flags it."""
    over = np.r_[1e6, [0.0] * 8]
    env = CraneLift(SCENES / "sea_state_crane.toml", duration=0.02)
    env.reset()
    env.step(over)
    assert env.sim.record().saturated[:, 0].any()
    text = (SCENES / "sea_state_crane.toml").read_text()
    path = tmp_path / "strict.toml"
    path.write_text(text.replace("[trajectory]", "[control]\nsaturation = false\n\n"
                                 "[trajectory]", 1) if "[control]" not in text else
                    text.replace("[control]", "[control]\nsaturation = false", 1))
    env = CraneLift(path, duration=0.02)
    env.reset()
    with pytest.raises(InputError, match=r"action T1 = 1e\+06 at t = 0 s is beyond its "
                                         r"capacity"):
        env.step(over)
