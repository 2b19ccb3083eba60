"""Many episodes of one scene at once (:class:`CraneLiftVector`): the environments split
over workers (this process and worker processes), each stepping its share in turn, the
actions and observations passed as one batch a step."""

from __future__ import annotations

import multiprocessing as mp

import gymnasium
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from offshore_crane.errors import InputError, OffshoreCraneError

#: [s] how long a process waits for the other side's answer by polling before it sleeps:
#: a share's step takes milliseconds, and waking a sleeping process took about 0.1 ms on
#: the 2-core machine of ``benchmarks/gym.py`` (twice a step: a tenth of it); past this
#: the wait sleeps (an agent thinking between steps leaves its workers asleep).
SPIN = 2e-3
#: [s] the longest a worker may take to answer one call (a step of its share of the
#: environments takes milliseconds; its start, the compiled kernels loaded from the
#: disk cache, seconds; a cold compile, a minute): past it the worker is taken for hung.
ANSWER_TIMEOUT = 600.0


class CraneLiftVector(VectorEnv):
    """``num_envs`` :class:`~offshore_crane.gym.CraneLift` environments of one scene.

    Args:
        num_envs: Environments (episodes stepped at once).
        workers: Processes stepping them, this one included (each its share of the
            environments, in turn; 1: all in this process; default: ``min(num_envs,
            os.cpu_count())``). This process steps its share while the others step
            theirs.
        **kwargs: :class:`~offshore_crane.gym.CraneLift`'s (``scene``,
            ``control_period``, ...), the same for every environment.

    An environment whose episode ended is reset by the next :meth:`step`, which returns
    its first observation, reward 0 and neither ``terminated`` nor ``truncated``
    (``autoreset_mode``: next step). ``reset(seed=s)`` seeds environment ``j`` with
    ``s + j`` (or a list of seeds, one each).

    Raises:
        InputError: ``num_envs < 1``, ``workers < 1``; what an environment refuses (the
            first environment's message, with its index).
    """

    metadata = {"render_modes": [], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs: int = 1, workers: int | None = None, **kwargs):
        import os

        if int(num_envs) < 1:
            raise InputError(f"num_envs = {num_envs!r}: give 1 or more", name="num_envs")
        self.num_envs = int(num_envs)
        workers = min(self.num_envs, os.cpu_count() or 1) if workers is None else int(workers)
        if workers < 1:
            raise InputError(f"workers = {workers}: give 1 (this process) or more",
                             name="workers")
        shares = np.array_split(np.arange(self.num_envs), workers)
        self._shares = [s for s in shares if len(s)]
        self._conns, self._procs = [], []
        ctx = mp.get_context("spawn")
        for share in self._shares[1:]:        # started first: they build while we do
            ours, theirs = ctx.Pipe()
            proc = ctx.Process(target=_work, args=(theirs, len(share), kwargs),
                               daemon=True)
            proc.start()
            theirs.close()
            self._conns.append(ours)
            self._procs.append(proc)
        try:
            self._local = _Share(len(self._shares[0]), kwargs)
            first = self._call("spaces", [None] * len(self._shares))[0]
        except BaseException:
            self.close_extras()
            raise
        self.single_observation_space = first.observation_space
        self.single_action_space = first.action_space
        self.observation_names = first.observation_names
        self.action_names = first.action_names
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)

    # ----------------------------------------------------------------- the API
    def reset(self, *, seed=None, options=None):
        """All episodes from the scene's initial state. Returns ``(observations
        (num_envs, n), infos)``."""
        if seed is None:
            seeds = [None] * self.num_envs
        elif np.ndim(seed) == 0:
            seeds = [int(seed) + j for j in range(self.num_envs)]
        else:
            seeds = [None if s is None else int(s) for s in seed]
            if len(seeds) != self.num_envs:
                raise InputError(f"{len(seeds)} seeds for {self.num_envs} environments: "
                                 "give one each, or one integer", name="seed")
        out = self._call("reset", [seeds[s[0]:s[-1] + 1] for s in self._shares])
        obs = np.concatenate([o for o, _ in out])
        return obs, {"time": np.concatenate([t for _, t in out])}

    def step(self, actions):
        """One control period of every environment under ``actions`` ``(num_envs,
        nx)``. Returns ``(observations, rewards, terminated, truncated, infos)``,
        arrays of ``num_envs`` rows."""
        a = np.asarray(actions, dtype=float)
        if a.shape != self.action_space.shape:
            raise InputError(f"actions of shape {a.shape}: give {self.action_space.shape} "
                             f"(one row of {', '.join(self.action_names)} an environment)",
                             name="actions")
        out = self._call("step", [a[s[0]:s[-1] + 1] for s in self._shares])
        obs, rew, term, trunc, t = (np.concatenate(x) for x in zip(*out))
        return obs, rew, term, trunc, {"time": t}

    def close_extras(self, **kwargs):
        for conn in self._conns:
            try:
                conn.send(("close", None))
            except (BrokenPipeError, OSError):
                pass
        for proc in self._procs:
            proc.join(timeout=5.0)
            if proc.is_alive():
                proc.terminate()
        self._conns, self._procs = [], []

    # ----------------------------------------------------------------- inside
    def _call(self, what: str, parts: list) -> list:
        """``what`` on every share (``parts[k]`` its argument): the worker processes' sent
        first, this process's done meanwhile; every answer received before an
        environment's refusal is raised (the pipes stay in step)."""
        for conn, part in zip(self._conns, parts[1:]):
            conn.send((what, part))
        out, failed = [None] * len(self._shares), None
        try:
            out[0] = getattr(self._local, what)(parts[0])
        except _Failed as exc:
            failed = (0, exc.j, exc.message)
        for k, (conn, proc) in enumerate(zip(self._conns, self._procs), start=1):
            if not (_spin(conn) or conn.poll(ANSWER_TIMEOUT)):
                raise OffshoreCraneError(f"worker {k} did not answer {what} within "
                                         f"{ANSWER_TIMEOUT:g} s (alive: {proc.is_alive()})"
                                         ": close the environment and start again")
            try:
                status, value = conn.recv()
            except (EOFError, ConnectionError):
                proc.join(timeout=5.0)
                raise OffshoreCraneError(
                    f"worker {k} ended during {what} (exit code {proc.exitcode}): workers "
                    "are spawned, so a script that makes a vector must do it under `if "
                    "__name__ == '__main__':` (else each worker runs the script again); "
                    "close the environment and start again") from None
            if status == "error":
                failed = failed or (k, *value)
            else:
                out[k] = value
        if failed is not None:
            k, j, message = failed
            raise InputError(f"environment {int(self._shares[k][0]) + j}: {message}",
                             name="actions")
        return out


class _Share:
    """A worker's environments, stepped in turn with the next-step autoreset."""

    def __init__(self, n: int, kwargs: dict):
        from offshore_crane.gym._env import CraneLift

        self.envs = [CraneLift(**kwargs) for _ in range(n)]
        self.done = np.zeros(n, dtype=bool)

    def spaces(self, _):
        env = self.envs[0]
        return _Spaces(env.observation_space, env.action_space, env.observation_names,
                       env.action_names)

    def reset(self, seeds):
        out = [env.reset(seed=s) for env, s in zip(self.envs, seeds)]
        self.done[:] = False
        return np.stack([o for o, _ in out]), np.array([i["time"] for _, i in out])

    def step(self, actions):
        n = len(self.envs)
        obs, rew = [], np.zeros(n)
        term, trunc, t = np.zeros(n, bool), np.zeros(n, bool), np.zeros(n)
        for j, env in enumerate(self.envs):
            try:
                if self.done[j]:
                    o, info = env.reset()
                    self.done[j] = False
                else:
                    o, rew[j], term[j], trunc[j], info = env.step(actions[j])
                    self.done[j] = term[j] or trunc[j]
            except OffshoreCraneError as exc:
                raise _Failed(j, str(exc)) from exc
            obs.append(o)
            t[j] = info["time"]
        return np.stack(obs), rew, term, trunc, t


class _Spaces:
    """What the parent needs of a worker's environments to build its spaces."""

    def __init__(self, observation_space, action_space, observation_names, action_names):
        self.observation_space: gymnasium.spaces.Box = observation_space
        self.action_space: gymnasium.spaces.Box = action_space
        self.observation_names, self.action_names = observation_names, action_names


class _Failed(Exception):
    def __init__(self, j: int, message: str):
        super().__init__(j, message)
        self.j, self.message = j, message


def _work(conn, n: int, kwargs: dict) -> None:
    """A worker: builds its ``n`` environments, then answers calls until ``close``."""
    try:
        share = _Share(n, kwargs)
    except OffshoreCraneError as exc:
        conn.send(("error", (0, str(exc))))
        return
    while True:
        _spin(conn)
        what, part = conn.recv()
        if what == "close":
            return
        try:
            conn.send(("ok", getattr(share, what)(part)))
        except _Failed as exc:
            conn.send(("error", (exc.j, exc.message)))


def _spin(conn) -> bool:
    """Whether ``conn`` has something to read within :data:`SPIN` seconds, polled
    without sleeping."""
    import time

    end = time.perf_counter() + SPIN
    while time.perf_counter() < end:
        if conn.poll():
            return True
    return False
