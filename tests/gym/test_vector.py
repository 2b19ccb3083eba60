"""Many episodes at once (:class:`~offshore_crane.gym.CraneLiftVector`): in this process
and in worker processes, each environment's run is the single environment's, bit for bit;
an episode that ended starts again on the next step."""

from __future__ import annotations

from pathlib import Path

import gymnasium
import numpy as np
import pytest

import offshore_crane as oc
import offshore_crane.gym  # noqa: F401  (registers CraneLift-v0)
from offshore_crane.errors import InputError
from offshore_crane.gym import CraneLift, CraneLiftVector

SCENE = Path(__file__).parents[2] / "scenes" / "hanging_load.toml"
N = 3


def _noisy(tmp_path) -> Path:
    path = tmp_path / "noisy.toml"
    path.write_text(SCENE.read_text() + "\n[sensors]\nnoise_q = 1e-4\nseed = 1\n")
    return path


def _actions(env, rng, n):
    """``n`` rows of forces near those holding the robot still (the first state's)."""
    env.reset()
    y = env.sim.state
    hold = oc.inverse_dynamics(env.sim.plant.robot.without_hanging_payload(), y[:9],
                               np.zeros(9), np.zeros(9))
    return hold + rng.normal(0.0, 2.0, (n, 9))


def test_workers_give_each_environment_its_own_run_and_autoreset_on_the_next_step(
        tmp_path):
    """Three seeds on 1, 2 and 3 workers against three single environments: the same
    observations and rewards; after the duration (3 periods) the next step returns the
    first observation of a new episode, reward 0, neither flag."""
    path = _noisy(tmp_path)
    kw = dict(scene=path, control_period=0.01, duration=0.03)
    singles = [CraneLift(**kw) for _ in range(N)]
    acts = _actions(singles[0], np.random.default_rng(2), 4)
    want = []
    for j, env in enumerate(singles):
        rows = [env.reset(seed=10 + j)[0]]
        for a in acts[:3]:
            o, r, term, trunc, _ = env.step(a)
            rows.append(np.r_[o, r, term, trunc])
        want.append(rows)
    for workers in (1, 2, 3):
        vec = CraneLiftVector(num_envs=N, workers=workers, **kw)
        try:
            obs, info = vec.reset(seed=10)
            np.testing.assert_array_equal(obs, np.array([w[0] for w in want]))
            for k, a in enumerate(acts[:3]):
                o, r, term, trunc, info = vec.step(np.tile(a, (N, 1)))
                np.testing.assert_array_equal(np.c_[o, r, term, trunc],
                                              np.array([w[k + 1] for w in want]))
            assert trunc.all()
            o, r, term, trunc, info = vec.step(np.tile(acts[3], (N, 1)))
            assert not (term.any() or trunc.any()) and (r == 0).all()
            assert (info["time"] == 0).all()
            with pytest.raises(InputError, match=r"actions of shape \(9,\): give \(3, 9\)"):
                vec.step(acts[0])
        finally:
            vec.close()


def test_make_vec_builds_it_and_a_worker_passes_an_environments_refusal_on():
    """``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")`` makes a
    :class:`CraneLiftVector`; an environment's InputError comes back naming it."""
    vec = gymnasium.make_vec("offshore_crane.gym:CraneLift-v0", num_envs=2,
                             vectorization_mode="vector_entry_point", workers=2,
                             scene=SCENE, control_period=0.01, duration=0.02)
    try:
        assert isinstance(vec, CraneLiftVector) and vec.observation_space.shape[0] == 2
        vec.reset(seed=0)
        bad = np.zeros((2, 9))
        bad[1, 3] = np.nan
        with pytest.raises(InputError, match="environment 1: action Fl1 = nan at t = 0 s"):
            vec.step(bad)
    finally:
        vec.close()
    with pytest.raises(InputError, match="num_envs = 0: give 1 or more"):
        CraneLiftVector(num_envs=0, scene=SCENE)
    with pytest.raises(InputError, match=r"workers = 0: give 1 \(this process\) or more"):
        CraneLiftVector(num_envs=2, workers=0, scene=SCENE)
