"""The FMU's model: a scene's crane as an FMI 2.0 co-simulation slave (PythonFMU's
``Fmi2Slave``), on the simulation you step (:func:`offshore_crane.scenes.stepper`).

An exported FMU holds a script (its module named by the export's digest, so that two
FMUs in one process never share a module) whose class derives from :class:`CraneSlave`,
and the folder :data:`FOLDER` with the scene, the files it reads and ``settings.json``
(the control period, the duration, the action's kind and the channels' names). The
machine that runs it needs Python with ``offshore-crane`` installed (docs/control.md).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from pythonfmu import Boolean, Fmi2Causality, Fmi2Initial, Fmi2Slave, Fmi2Variability
from pythonfmu import Integer, Real
from pythonfmu.enums import Fmi2Status

#: The FMU's resources folder holding the scene and ``settings.json``.
FOLDER = "offshore_crane_fmu"
#: The scene's main values an FMU takes as parameters: ``{parameter: the scene's key}``
#: (``[sea]`` keys, full scale; the payload's mass, a robot field).
PARAMETERS = {"hs": "hs", "tp": "tp", "heading": "heading", "payload_mass": "payload.mass"}


class CraneSlave(Fmi2Slave):
    """Inputs: the action's channels (the actuators' forces [N·m, N], starting at those
    that hold the robot still at the run's start; or a reference, starting at the
    scene's).
    Outputs: the observation's (the CSV's names with their units) and ``terminated``.
    Parameters: ``seed`` (the sea's random phases and the sensors' noise) and, where the
    scene has them, ``hs`` [m], ``tp`` [s], ``heading`` [deg] (full scale) and
    ``payload_mass`` [kg]. A communication step is a whole number of control periods,
    the inputs held over it; the run's end or a stop ends it (``doStep`` discards, the
    log says why). The master's time starts where it likes (``setupExperiment``'s start
    is the run's start)."""

    author = "offshore-crane"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        folder = Path(self.resources) / FOLDER
        self._settings = s = json.loads((folder / "settings.json").read_text())
        self._scene_path = folder / s["scene"]
        self._sim, self._start = None, None
        fixed = dict(causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                     initial=Fmi2Initial.exact)
        self.seed = int(s["seed"])
        self.register_variable(Integer("seed", description="the sea's random phases and "
                                       "the sensors' noise", **fixed))
        for name, value in s["parameters"].items():
            setattr(self, name, float(value))
            self.register_variable(Real(name, **fixed))
        for name, value in zip(s["action_names"], s["action_start"]):
            setattr(self, name, float(value))
            self.register_variable(Real(name, causality=Fmi2Causality.input,
                                        variability=Fmi2Variability.continuous))
        for name in s["observation_names"]:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output,
                                        variability=Fmi2Variability.continuous,
                                        initial=Fmi2Initial.exact))
        self.terminated = False
        self.register_variable(Boolean("terminated", causality=Fmi2Causality.output,
                                       variability=Fmi2Variability.discrete,
                                       initial=Fmi2Initial.exact))

    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        """The master's start time [s]: the run's start (the scene's reference may start
        elsewhere: a step at the master's ``t`` is the run's at ``t0 + t − start``)."""
        self._start = float(start_time)

    def exit_initialization_mode(self):
        from offshore_crane.errors import OffshoreCraneError

        try:
            self._open()
        except OffshoreCraneError as exc:     # the message, before PythonFMU's repr
            self.log(str(exc), Fmi2Status.error)
            raise

    def _open(self) -> None:
        """The run of the scene with the parameters given, reset to its start."""
        from offshore_crane import scenes

        s = self._settings
        scene = scenes.load_scene(self._scene_path)
        values = {PARAMETERS[k]: getattr(self, k) for k, v in s["parameters"].items()
                  if getattr(self, k) != v}
        if "hs" in s["parameters"] and self.seed != int(s["seed"]):
            values["seed"] = int(self.seed)
        scene = scenes.with_values(scene, values)
        self._sim = scenes.stepper(scene, control_period=s["control_period"],
                                   duration=s["duration"], action=s["action"])
        self._write(self._sim.reset(seed=int(self.seed)))
        self._t0 = self._sim.time

    def do_step(self, current_time, step_size):
        sim, period = self._sim, self._settings["control_period"]
        periods = step_size / period
        if not (round(periods) >= 1 and abs(periods - round(periods)) <= 1e-9 * periods):
            return self._refuse(f"communication step {step_size:g} s is not a whole "
                                f"number of control periods of {period:g} s")
        start = self._start if self._start is not None else self._t0
        if abs((current_time - start) - (sim.time - self._t0)) > 1e-9 * max(
                1.0, abs(current_time)):
            return self._refuse(f"doStep at t = {current_time:g} s, the run is at "
                                f"{start + sim.time - self._t0:g} s: steps go forward "
                                "from where it is")
        if self.terminated or sim.truncated:
            return self._refuse(f"the run ended at t = {sim.time:g} s")
        from offshore_crane.errors import OffshoreCraneError

        action = np.array([getattr(self, n) for n in self._settings["action_names"]])
        try:
            for _ in range(round(periods)):
                y = sim.step(action)
                if sim.terminated or sim.truncated:
                    break
        except OffshoreCraneError as exc:
            return self._refuse(str(exc))
        self._write(y)
        if sim.terminated:
            self.terminated = True
            self.log(sim.record().stop or f"stopped at t = {sim.time:g} s: the cable's "
                     "tension fell below its slack criterion", Fmi2Status.warning)
        return True

    def _write(self, y: np.ndarray) -> None:
        for name, value in zip(self._settings["observation_names"], y):
            setattr(self, name, float(value))

    def _refuse(self, message: str) -> bool:
        self.log(message, Fmi2Status.error)
        return False
