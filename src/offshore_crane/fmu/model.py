"""The FMU's model: a scene's crane as an FMI 2.0 co-simulation slave (PythonFMU's
``Fmi2Slave``) whose simulation runs in a process of its own
(:mod:`offshore_crane.fmu._worker`).

This file is the FMU's script: :func:`offshore_crane.fmu.export_fmu` copies its text
into the FMU, followed by the class the FMU names. It imports the standard library and
PythonFMU only (not this package, not NumPy): the master's process loads nothing
compiled of ours. The FMU's resources hold the folder :data:`FOLDER` with the scene,
the files it reads and ``settings.json`` (the control period, the duration, the
action's kind, the channels' names). The machine that runs it needs Python with
``offshore-crane`` installed (docs/control.md).
"""

from __future__ import annotations

import atexit
import ctypes
import json
import os
import pickle
import select
import shutil
import subprocess
import sys
from pathlib import Path

from pythonfmu import Boolean, Fmi2Causality, Fmi2Initial, Fmi2Slave, Fmi2Variability
from pythonfmu import Integer, Real
from pythonfmu.enums import Fmi2Status

#: The FMU's resources folder holding the scene and ``settings.json``.
FOLDER = "offshore_crane_fmu"
#: [s] the longest the simulation's process may take to answer a call (a step takes
#: milliseconds; its start, the compiled kernels loaded from the disk cache, seconds; a
#: cold compile, a minute or two): past it the process is taken for hung.
ANSWER_TIMEOUT = 900.0


class CraneSlave(Fmi2Slave):
    """Inputs: the action's channels (the actuators' forces [N·m, N], starting at those
    that hold the robot still at the run's start; or a reference, starting at the
    scene's). Outputs: the observation's (the CSV's names with their units) and
    ``terminated``. Parameters: ``seed`` (the sea's random phases and the sensors'
    noise) and, where the scene has them, ``hs`` [m], ``tp`` [s], ``heading`` [deg]
    (full scale) and ``payload_mass`` [kg]. A communication step is a whole number of
    control periods, the inputs held over it; the run's end or a stop ends it
    (``doStep`` discards, the log says why). The master's time starts where it likes
    (``setupExperiment``'s start is the run's start). The simulation runs in a process
    started at ``exitInitializationMode`` with the Python that loads the FMU (in a
    master that is not Python: ``$OFFSHORE_CRANE_PYTHON``, else ``python3`` on the
    ``PATH``), ended at ``terminate``."""

    author = "offshore-crane"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        _release_at_exit(Path(self.resources))
        folder = Path(self.resources) / FOLDER
        self._settings = s = json.loads((folder / "settings.json").read_text())
        self._scene_path = str(folder / s["scene"])
        self._proc, self._start, self._t0, self._time = None, None, 0.0, 0.0
        self._ended = False
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

    # ------------------------------------------------------------------ FMI
    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        """The master's start time [s]: the run's start (the scene's reference may start
        elsewhere: a step at the master's ``t`` is the run's at ``t0 + t − start``)."""
        self._start = float(start_time)

    def exit_initialization_mode(self):
        s = self._settings
        values = {k: getattr(self, k) for k in s["parameters"]}
        self._proc = _start_worker()
        ok, answer = self._call("open", {"scene": self._scene_path, "settings": s,
                                         "values": values, "seed": int(self.seed)})
        if not ok:                     # the message, before PythonFMU's repr of it
            self.log(answer, Fmi2Status.error)
            raise RuntimeError(answer)
        y, self._t0 = answer
        self._time = self._t0
        self._write(y)

    def do_step(self, current_time, step_size):
        period = self._settings["control_period"]
        periods = step_size / period
        if not (round(periods) >= 1 and abs(periods - round(periods)) <= 1e-9 * periods):
            return self._refuse(f"communication step {step_size:g} s is not a whole "
                                f"number of control periods of {period:g} s")
        start = self._start if self._start is not None else self._t0
        if abs((current_time - start) - (self._time - self._t0)) > 1e-9 * max(
                1.0, abs(current_time)):
            return self._refuse(f"doStep at t = {current_time:g} s, the run is at "
                                f"{start + self._time - self._t0:g} s: steps go forward "
                                "from where it is")
        if self._ended:
            return self._refuse(f"the run ended at t = {self._time:g} s")
        action = [float(getattr(self, n)) for n in self._settings["action_names"]]
        ok, answer = self._call("step", (action, round(periods)))
        if not ok:
            return self._refuse(answer)
        y, self._time, terminated, truncated, why = answer
        self._write(y)
        self._ended = terminated or truncated
        if terminated:
            self.terminated = True
            self.log(why, Fmi2Status.warning)
        return True

    def terminate(self):
        proc, self._proc = self._proc, None
        if proc is not None:
            try:
                pickle.dump(("close", None), proc.stdin)
                proc.stdin.close()
                proc.wait(timeout=10.0)
            except (OSError, subprocess.TimeoutExpired):
                proc.kill()

    def __del__(self):
        if getattr(self, "_proc", None) is not None:
            self._proc.kill()

    # ------------------------------------------------------------------ inside
    def _call(self, what: str, arg) -> tuple[bool, object]:
        """``(True, value)`` or ``(False, message)`` of the simulation's process."""
        proc = self._proc
        try:
            pickle.dump((what, arg), proc.stdin)
            proc.stdin.flush()
            ready = os.name == "nt" or select.select([proc.stdout], [], [],
                                                     ANSWER_TIMEOUT)[0]   # (pipes: POSIX)
            if not ready:
                proc.kill()
                return False, (f"the simulation's process did not answer {what} within "
                               f"{ANSWER_TIMEOUT:g} s: it was stopped")
            status, value = pickle.load(proc.stdout)
        except (OSError, EOFError, pickle.UnpicklingError):
            code = proc.poll()
            return False, (f"the simulation's process ended during {what} (exit code "
                           f"{code}): its standard error says why; is offshore-crane "
                           f"installed for {proc.args[0]}?")
        return status == "ok", value

    def _write(self, y) -> None:
        for name, value in zip(self._settings["observation_names"], y):
            setattr(self, name, float(value))

    def _refuse(self, message: str) -> bool:
        self.log(message, Fmi2Status.error)
        return False


#: The FMU binaries of this process whose state :func:`_release_at_exit` releases.
_RELEASED: set[str] = set()


def _release_at_exit(resources: Path) -> bool:
    """Work around a use after free at the exit of the process in PythonFMU's binary
    (0.6.4 and later; the abort in PythonFMU's issue #228 looks like it): it can abort
    the master as it ends.

    The binary keeps its interpreter's state in a global ``std::shared_ptr``. On Linux
    the library is never unloaded (its C++ ``STB_GNU_UNIQUE`` symbols make it
    ``NODELETE``), so at the process's exit the C++ static destructors free that state,
    and then the library's ``__attribute__((destructor))`` function
    ``finalizePythonInterpreter`` resets the same, already destroyed pointer again: it
    decrements a count inside the freed 128-byte block. Where glibc keeps that block in
    its unsorted bin, the count overlaps the bin's back link, and the exit aborts with
    "corrupted double-linked list". Valgrind shows the invalid access in every run;
    the abort comes in some.

    Here the binary's own ``finalizePythonInterpreter`` is called from Python's
    ``atexit``, which runs before the block is freed, so both clean-ups after it find
    the pointer empty:

    * in a master that is a Python program, ``atexit`` runs as the interpreter ends,
      before C's exit handlers: the state is released there (it holds nothing: its
      thread ended on finding the interpreter already running);
    * in a master that is not Python, the state's thread ends the interpreter from the
      static destructor, and ``atexit`` runs inside it: the call empties the pointer,
      and its decrement lands in the block still alive (its count is already 0; it
      destroys nothing).

    Args:
        resources: The FMU's ``resources`` folder (its binary is in ``../binaries``).

    Returns:
        Whether a release is registered for this FMU's binary: False off Linux or when
        no binary of this FMU is loaded in this process.
    """
    if not sys.platform.startswith("linux"):
        return False
    for binary in sorted((resources.parent / "binaries").glob("*/*.so")):
        try:                          # only the copy this process has loaded
            lib = ctypes.CDLL(str(binary), mode=os.RTLD_NOLOAD | os.RTLD_LAZY)
            release = lib.finalizePythonInterpreter
        except (OSError, AttributeError):
            continue
        if str(binary) not in _RELEASED:
            _RELEASED.add(str(binary))
            release.restype, release.argtypes = None, []
            atexit.register(release)
        return True
    return False


def _python() -> str:
    """The Python the simulation's process runs: ``$OFFSHORE_CRANE_PYTHON``, else this
    process's when it is a Python, else ``python3`` on the ``PATH``."""
    given = os.environ.get("OFFSHORE_CRANE_PYTHON")
    if given:
        return given
    if sys.executable and Path(sys.executable).name.startswith("python"):
        return sys.executable
    return shutil.which("python3") or "python3"


def _start_worker() -> subprocess.Popen:
    """The simulation's process (:mod:`offshore_crane.fmu._worker`)."""
    return subprocess.Popen([_python(), "-m", "offshore_crane.fmu._worker"],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE)
