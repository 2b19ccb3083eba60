"""The FMU (:mod:`offshore_crane.fmu`, ``offshore-crane export --fmu``): FMPy finds no
problem in it; stepped by FMPy with a sampled law it gives the stepper's run of that law;
its parameters reach the scene; bad input is refused in one line, nothing written."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
from fmpy.validation import validate_fmu

from offshore_crane import scenes
from offshore_crane.conventions import QD_COLUMNS, Q_COLUMNS
from offshore_crane.errors import InputError
from offshore_crane.fmu import export_fmu
from problems import computed_torque_law

SCENES = Path(__file__).parents[2] / "scenes"
PERIOD = 0.01           # [s]: 100 Hz
SECONDS = 0.2


class Unit:
    """An FMU opened with FMPy's FMU2Slave (the value references by name)."""

    def __init__(self, path: Path, start: dict | None = None):
        md = read_model_description(str(path))
        self.refs = {v.name: v.valueReference for v in md.modelVariables}
        self.kinds = {v.name: v.type for v in md.modelVariables}
        self.md = md
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(path)),
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName="crane")
        self.fmu.instantiate(loggingOn=True)
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        for name, value in (start or {}).items():
            setter = (self.fmu.setInteger if self.kinds[name] == "Integer"
                      else self.fmu.setReal)
            setter([self.refs[name]], [value])
        self.fmu.exitInitializationMode()

    def get(self, names):
        return np.array(self.fmu.getReal([self.refs[n] for n in names]))

    def set(self, names, values):
        self.fmu.setReal([self.refs[n] for n in names], list(map(float, values)))

    def close(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


@pytest.fixture(scope="module")
def hanging_fmu(tmp_path_factory):
    path = tmp_path_factory.mktemp("fmu") / "hanging.fmu"
    export_fmu(SCENES / "hanging_load.toml", path, control_period=PERIOD,
               duration=SECONDS)
    return path


@pytest.mark.parametrize("scene", ["hanging_load.toml", "compensated_lift.toml"])
def test_the_fmu_stepped_by_fmpy_is_the_steppers_run(scene, tmp_path):
    """FMPy's validation finds nothing; a sampled computed torque on the observation
    alone (q, q̇ and the reference's q, q̇; no feed-forward acceleration), its forces
    set as inputs, one doStep a period: the observation at each period is the
    stepper's under the same law (the same run: ≤ 1e-9 relative asked, equal here)."""
    path = export_fmu(SCENES / scene, tmp_path / "crane.fmu", control_period=PERIOD,
                      duration=SECONDS)
    assert validate_fmu(str(path)) == []
    sim = scenes.stepper(SCENES / scene, control_period=PERIOD, duration=SECONDS)
    law = computed_torque_law(sim.plant.robot)
    names, acts = sim.observation_names, sim.action_names
    cols = [[names.index(c) for c in cs] for cs in (
        Q_COLUMNS, QD_COLUMNS, [c.replace("_", "_ref_", 1) for c in Q_COLUMNS],
        [c.replace("_", "_ref_", 1) for c in QD_COLUMNS])]

    def act(y):
        return law(None, *(y[c] for c in cols), np.zeros(9))
    want, y = [], sim.reset(seed=int(scenes.load_scene(SCENES / scene).sea["seed"]))
    while not sim.truncated:
        y = sim.step(act(y))
        want.append(y)
    unit = Unit(path)
    try:
        got, y = [], unit.get(names)
        for k in range(len(want)):
            unit.set(acts, act(y))
            unit.fmu.doStep(currentCommunicationPoint=k * PERIOD,
                            communicationStepSize=PERIOD)
            y = unit.get(names)
            got.append(y)
        scale = np.abs(np.array(want)).max(axis=0) + 1e-300
        assert np.max(np.abs(np.array(got) - np.array(want)) / scale) <= 1e-9
    finally:
        unit.close()


def test_parameters_reach_the_scene(hanging_fmu):
    """The defaults are the scene's own values; another ``hs`` or ``seed`` draws another
    sea (the platform's reference moves apart); a sea the platform cannot follow is
    refused at initialisation, its message logged."""
    md = read_model_description(str(hanging_fmu))
    start = {v.name: v.start for v in md.modelVariables if v.causality == "parameter"}
    assert float(start["hs"]) == 2.5 and float(start["payload_mass"]) == 2.0
    assert int(start["seed"]) == 1
    ref = [f"q{k}_ref_{u}" for k, u in ((1, "m"), (2, "m"), (3, "m"))]
    runs = {}
    for key, start in (("scene", {}), ("hs", {"hs": 2.0}), ("seed", {"seed": 7})):
        unit = Unit(hanging_fmu, start)
        try:
            rows = []
            for k in range(5):
                unit.fmu.doStep(currentCommunicationPoint=k * PERIOD,
                                communicationStepSize=PERIOD)
                rows.append(unit.get(ref))
            runs[key] = np.array(rows)
        finally:
            unit.close()
    assert not np.allclose(runs["hs"], runs["scene"])
    assert not np.allclose(runs["seed"], runs["scene"])
    with pytest.raises(FMICallException, match="fmi2ExitInitializationMode failed"):
        Unit(hanging_fmu, {"hs": 5.0})


def test_a_step_that_is_not_whole_periods_or_out_of_turn_is_refused(hanging_fmu):
    unit = Unit(hanging_fmu)
    try:
        with pytest.raises(FMICallException, match="fmi2DoStep failed"):
            unit.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=0.015)
    finally:
        unit.fmu.freeInstance()
    unit = Unit(hanging_fmu)
    try:
        unit.set(["T1"], [np.nan])
        with pytest.raises(FMICallException, match="fmi2DoStep failed"):
            unit.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=PERIOD)
    finally:
        unit.fmu.freeInstance()


def test_the_command_line_writes_it_and_refuses_bad_paths(tmp_path):
    """``export --fmu`` writes a valid FMU, which FMPy's command line runs in a process
    of its own over the default experiment and ends with exit status 0 (its exit's
    clean-up: ``test_fmu_exit.py``); onto the scene file itself, without a control
    period, with another suffix: one line, exit 2, nothing written."""
    scene = tmp_path / "scene.toml"
    scene.write_text((SCENES / "hanging_load.toml").read_text())
    before = scene.read_bytes()

    def cli(*args):
        return subprocess.run([sys.executable, "-m", "offshore_crane", "export", *args],
                              capture_output=True, text=True, cwd=tmp_path)
    ok = cli("--fmu", "crane.fmu", "--scene", "scene.toml", "--control-period", "0.01",
             "--duration", "0.1")
    assert ok.returncode == 0, ok.stderr
    assert "wrote crane.fmu" in ok.stdout
    assert validate_fmu(str(tmp_path / "crane.fmu")) == []
    run = subprocess.run([sys.executable, "-m", "fmpy", "simulate", "crane.fmu",
                          "--output-interval", "0.01", "--output-file", "out.csv"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr              # FMPy's command line, a fresh process
    rows = (tmp_path / "out.csv").read_text().splitlines()
    assert rows[0].startswith('"time","q1_m"') and len(rows) == 1 + 11        # 0 .. 0.1 s
    for args, words in (
            (("--fmu", "scene.toml", "--scene", "scene.toml", "--control-period", "0.01"),
             "file type '.toml' is not one of .fmu"),
            (("--fmu", "x.fmu", "--scene", "scene.toml"), "needs --control-period"),
            (("--fmu", "x.fmu", "--scene", "scene.toml", "--control-period", "0.0015"),
             "is not a whole number of integration steps")):
        bad = cli(*args)
        assert bad.returncode == 2 and words in bad.stderr, bad.stderr
        assert len(bad.stderr.strip().splitlines()) == 1 and "Traceback" not in bad.stderr
    assert scene.read_bytes() == before and not (tmp_path / "x.fmu").exists()
    with pytest.raises(InputError, match="give the scene file's path"):
        export_fmu(scenes.load_scene(scene), tmp_path / "y.fmu", control_period=0.01)


def test_a_reference_as_the_input_drives_the_scenes_law(tmp_path):
    """``action="reference"``: the inputs are ``q1_cmd_m ... qd9_cmd_m_s``, starting at
    the scene's reference; held there, the scene's law keeps the platform near it."""
    path = export_fmu(SCENES / "hanging_load.toml", tmp_path / "outer.fmu",
                      control_period=PERIOD, duration=0.05, action="reference")
    assert validate_fmu(str(path)) == []
    md = read_model_description(str(path))
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    assert inputs[0] == "q1_cmd_m" and inputs[-1] == "qd9_cmd_m_s" and len(inputs) == 18
    unit = Unit(path)
    try:
        start = unit.get(inputs)
        for k in range(5):
            unit.fmu.doStep(currentCommunicationPoint=k * PERIOD,
                            communicationStepSize=PERIOD)
        q = unit.get(list(Q_COLUMNS))
        assert np.abs(q - start[:9]).max() < 0.01       # [m, rad]: held near it
    finally:
        unit.close()


def test_a_simulation_process_that_cannot_start_is_said_at_initialisation(tmp_path,
                                                                          monkeypatch):
    """``$OFFSHORE_CRANE_PYTHON`` naming a Python without the package: initialisation
    fails and the log asks whether offshore-crane is installed for it."""
    path = export_fmu(SCENES / "hanging_load.toml", tmp_path / "c.fmu",
                      control_period=PERIOD, duration=0.05)
    monkeypatch.setenv("OFFSHORE_CRANE_PYTHON", "/usr/bin/env")   # runs, but no Python
    with pytest.raises(FMICallException, match="fmi2ExitInitializationMode failed"):
        Unit(path)
