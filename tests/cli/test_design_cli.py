"""``offshore-crane design`` (issue 39): a run killed at a random moment and rerun gives the
uninterrupted run's front; every front design, picked as a description file, is
reproduced by ``size --robot`` to 1e-12; bad input is one line, exit 2, nothing written;
no feasible design is exit 1 naming the least-violating candidate.

The problem is tests/design_cases.py's."""

from __future__ import annotations

import contextlib
import io
import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import design_cases as dc
import offshore_crane
from offshore_crane.cli import main
from offshore_crane.robot.description import resolve
from offshore_crane.robot.expressions import evaluate
from offshore_crane.studies import design

SRC = Path(offshore_crane.__file__).resolve().parents[1]
BUDGET, SEED, POPULATION = 30, 5, 10


def _cli(argv) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main([str(a) for a in argv])
    return status, out.getvalue(), err.getvalue()


def _design(folder: Path, out: Path, *extra) -> list:
    return ["design", "--scene", folder / "scene.toml", "--space", folder / "space.toml",
            "--budget", BUDGET, "--seed", SEED, "--population", POPULATION, "--out", out,
            "--no-progress", *extra]


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """An uninterrupted run: its folder and its --out directory."""
    folder = tmp_path_factory.mktemp("design-cli")
    dc.write(folder)
    status, printed, _ = _cli(_design(folder, folder / "out"))
    assert status == 0, printed
    return folder, folder / "out"


def test_a_killed_run_resumes_to_the_uninterrupted_front(finished, tmp_path):
    """SIGKILL at a seeded random count of stored cases (batches every 0.05 s), then the
    same command again: the same pareto.csv, and the cases stored before the kill are
    read back, not run again."""
    from offshore_crane.studies.sweep.rowfiles import case_ids

    folder, reference = finished
    out = tmp_path / "out"
    total = BUDGET * 2                                  # candidates x seeds
    k = random.Random(39).randrange(5, total - 10)
    env = {**os.environ, "PYTHONPATH": str(SRC), "OFFSHORE_CRANE_BATCH_SECONDS": "0.05"}
    proc = subprocess.Popen([sys.executable, "-m", "offshore_crane",
                             *map(str, _design(folder, out))], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while len(case_ids(str(out / "candidates"))) < k and proc.poll() is None:
        assert time.monotonic() < deadline, "the design stored too few cases in 120 s"
        time.sleep(0.02)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    stored = len(case_ids(str(out / "candidates")))
    assert stored >= k and not (out / "pareto.csv").exists()
    status, printed, _ = _cli(_design(folder, out))
    assert status == 0
    assert (out / "pareto.csv").read_text() == (reference / "pareto.csv").read_text()
    assert f"{total - stored} cases run, {stored} read from" in printed


def test_every_front_design_is_reproduced_by_size_with_its_description(finished,
                                                                      tmp_path):
    folder, out = finished
    rows = design.read_front(out / design.PARETO)
    assert len(rows) >= 3
    for row in rows:
        robot = tmp_path / f"design-{row['design']}.toml"
        status, printed, _ = _cli(["design", "--scene", folder / "scene.toml", "--out", out,
                                   "--pick", row["design"], "--out-robot", robot])
        assert status == 0 and f"wrote {robot}: design {row['design']}" in printed
        status, printed, _ = _cli(["size", "--scene", folder / "scene.toml", "--robot",
                                   robot, "--json"])
        verdict = json.loads(printed)["verdict"]
        assert abs(verdict["utilisation"]["T1"]["push"] - row["T1_util_push"]) <= 1e-12
        assert abs(verdict["worst"]["utilisation"] - row["worst_util"]) <= 1e-12
        values = resolve(robot).values
        assert abs(evaluate(dc.REACH, values.__getitem__) - row[dc.REACH]) <= 1e-12
        assert values[dc.L1] == row[dc.L1] and values[dc.L2] == row[dc.L2]


def test_plot_draws_the_front(finished, tmp_path):
    folder, out = finished
    status, printed, _ = _cli(_design(folder, out, "--plot", tmp_path / "plots"))
    assert status == 0 and "0 cases run" in printed
    assert (tmp_path / "plots" / "front.png").stat().st_size > 10_000


BAD = [
    ('[variables]\n"arm.link1.bogus" = [0.3, 0.7]\n[objectives]\nminimise = ["worst_util"]\n',
     (), r"arm\.link1\.bogus = \[0\.3, 0\.7\]: not a field of the robot description"),
    (dc.SPACE.replace("[0.3, 0.7]", "[0.7, 0.3]"), (), r"the bounds are reversed"),
    (dc.SPACE.replace("[0.3, 0.7]", "[-0.3, 0.7]"), (),
     r"the lower bound -0\.3 is refused by the description: .*must not be negative"),
    (dc.SPACE.replace('"T1_util_push"', '"T1_util_shove"'), (),
     r"'T1_util_shove' names no verdict column"),
    ("", (), r"the space is empty"),
    (dc.SPACE, ("--budget", "0"), r"--budget 0: must be ≥ 1"),
]


@pytest.mark.parametrize("space, extra, match", BAD)
def test_bad_input_is_one_line_exit_2_and_nothing_written(tmp_path, space, extra, match):
    import re

    dc.write(tmp_path, space=space)
    status, printed, err = _cli(_design(tmp_path, tmp_path / "out", "--plot",
                                        tmp_path / "plots", *extra))
    assert status == 2 and printed == ""
    assert len(err.strip().splitlines()) == 1 and re.search(match, err), err
    assert sorted(os.listdir(tmp_path)) == ["scene.toml", "space.toml"]


def test_no_feasible_design_is_exit_1_with_the_least_violating_candidate(tmp_path):
    space = dc.SPACE + '[constraints]\n"T1_util_push" = { "<=" = 1e-4 }\n'
    dc.write(tmp_path, space=space)
    status, printed, err = _cli(_design(tmp_path, tmp_path / "out"))
    assert status == 1
    assert err.startswith("offshore-crane: no feasible design among the 30 candidates "
                          "evaluated: the least violating, arm.link1.shape.size.x = 0.3, "
                          "arm.link2.shape.size.x = 0.2, has T1_util_push = ")
    assert not (tmp_path / "out" / "pareto.csv").exists()
