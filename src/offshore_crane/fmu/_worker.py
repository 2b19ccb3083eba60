"""The process an FMU's model runs its simulation in: ``python -m
offshore_crane.fmu._worker`` started by the FMU (:mod:`offshore_crane.fmu.model`), the
scene's stepper (:func:`offshore_crane.scenes.stepper`) driven by the calls it reads.

The FMU's own process then loads nothing compiled of ours (no Numba, LLVM or LAPACK
in a master that may carry its own), needs only the standard library and PythonFMU in
the Python it embeds (a master that is not Python preloads a system ``libpython``; the
simulation runs in a Python with the package), and outlives a simulation that crashes
or hangs (each answer has a time-out). The abort at the master's exit that first
motivated it was PythonFMU's own bug, which the model works around
(:func:`offshore_crane.fmu.model._release_at_exit`).

The protocol, on the standard input and a copy of the standard output (the output
itself goes to the standard error, so that nothing printed can corrupt a frame):
pickled ``(call, argument)`` frames, each answered with ``("ok", value)`` or
``("error", message)``:

- ``("open", {"scene", "settings", "values", "seed"})`` → ``(observation, time)``;
- ``("step", (action, periods))`` → ``(observation, time, terminated, truncated,
  message)``;
- ``("close", None)`` → ends the process.
"""

from __future__ import annotations

import os
import pickle
import sys

#: The FMU's parameters and the scene's keys they set (``[sea]`` keys, full scale; the
#: payload's mass, a robot field).
PARAMETERS = {"hs": "hs", "tp": "tp", "heading": "heading", "payload_mass": "payload.mass"}


class Run:
    """One FMU instance's run (a scene's stepper)."""

    def __init__(self):
        self.sim = None

    def open(self, arg: dict):
        """The scene with the FMU's parameters, reset with its seed: ``(observation,
        time [s])``."""
        from offshore_crane import scenes

        s, values = arg["settings"], dict(arg["values"])
        scene = scenes.load_scene(arg["scene"])
        changed = {PARAMETERS[k]: v for k, v in values.items()
                   if k in PARAMETERS and v != s["parameters"][k]}
        if "hs" in s["parameters"] and int(arg["seed"]) != int(s["seed"]):
            changed["seed"] = int(arg["seed"])
        self.sim = scenes.stepper(scenes.with_values(scene, changed),
                                  control_period=s["control_period"],
                                  duration=s["duration"], action=s["action"])
        y = self.sim.reset(seed=int(arg["seed"]))
        return y.tolist(), self.sim.time

    def step(self, arg):
        """``periods`` control periods under ``action`` (held): ``(observation, time,
        terminated, truncated, why it stopped or "")``."""
        import numpy as np

        sim = self.sim
        action, periods = np.asarray(arg[0], dtype=float), int(arg[1])
        for _ in range(periods):
            y = sim.step(action)
            if sim.terminated or sim.truncated:
                break
        why = ""
        if sim.terminated:
            why = sim.record().stop or (f"stopped at t = {sim.time:g} s: the cable's "
                                        "tension fell below its slack criterion")
        return y.tolist(), sim.time, sim.terminated, sim.truncated, why


def main() -> int:
    """Answer the FMU's calls until ``close`` or the end of the input."""
    from offshore_crane.errors import OffshoreCraneError

    answers = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)                        # anything printed goes to the standard error
    sys.stdout = sys.stderr
    calls, run = sys.stdin.buffer, Run()
    while True:
        try:
            what, arg = pickle.load(calls)
        except EOFError:
            return 0
        if what == "close":
            return 0
        try:
            answer = ("ok", getattr(run, what)(arg))
        except OffshoreCraneError as exc:
            answer = ("error", str(exc))
        except Exception as exc:  # noqa: BLE001 - the FMU logs it, the master decides
            answer = ("error", f"{type(exc).__name__}: {exc}")
        pickle.dump(answer, answers)
        answers.flush()


if __name__ == "__main__":
    raise SystemExit(main())
