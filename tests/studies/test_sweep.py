"""Sweeps (offshore_crane.studies.sweep and ``offshore-crane sweep``): grids and their errors,
rows bit-identical serially / on joblib workers / on a Dask LocalCluster, the resumable
store (a killed sweep rerun gives every case exactly once), failing cases recorded, the
results directory and scheduler refused before anything is written, verdicts and the
scatter-diagram operability against hand computations.

Cases are short model-scale sea records (5 s at 50 Hz: ~5 ms each) so that the file runs
in well under a minute on two cores; the kill test uses longer ones.
"""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import offshore_crane


from offshore_crane import scenes
from offshore_crane.studies import sweep
from offshore_crane.cli import main                           # noqa: E402
from offshore_crane.errors import GridError, InputError, ResultsDirectoryError  # noqa: E402

#: Where the package the tests import lives (the source tree, or the installed copy in
#: CI): subprocesses import the same one, whose compiled kernels are already cached.
SRC = Path(offshore_crane.__file__).resolve().parents[1]
SCENE = """
name = "sweep test"
[payload]
mass = 2.0
offset = [0.0, 0.0, -0.05]
[trajectory]
source = "sea"
duration = {duration}
rate = {rate}
[sea]
hs = 2.5
tp = 8.0
heading = 90.0
scale = 20.0
seed = 1
highpass = 0.2
[extremes]
record = "scene"    # the engine's tests: each case the scene's own short record
"""


#: Exposure records of 0.01 h full scale (36 s: 8 s at 1:20) instead of the scene's own:
#: what a verdict's Gumbel fit takes, kept cheap.
EXPOSURE_RECORDS = 'record = "exposure"\nexposure = 0.01'


def _scene(tmp_path, duration=5.0, rate=50.0, name="scene.toml", exposure=False, **extra):
    path = tmp_path / name
    text = SCENE.format(duration=duration, rate=rate)
    if exposure:
        text = text.replace('record = "scene"', EXPOSURE_RECORDS)
    for key, value in extra.items():
        text = text.replace(f"{key} = ", f"{key} = {value}  # was ", 1)
    path.write_text(text)
    return path


def _grid(tmp_path, text, name="grid.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _bits(df):
    """Every column as comparable bits: floats by their int64 view (NaN payloads too)."""
    out = {}
    for c in df.columns:
        a = df[c].to_numpy()
        out[c] = a.astype(np.float64).view(np.int64) if a.dtype.kind == "f" else a.astype(str)
    return out


# --------------------------------------------------------------------------- grids
@pytest.mark.parametrize("text, match", [
    ("hs = [1.0]\nbogus = [1]\n", "unknown grid key 'bogus'"),
    ("hs = []\n", r"hs = \[\]: the list is empty"),
    ("hs = [1.0, -1.0]\n", r"hs\[1\] = -1: \[sea\] hs = -1.0 m must be > 0"),
    ("tp = 8.0\n", "tp = 8: must be a list of values"),
    ("seed = [0, -2]\n", r"seed\[1\] = -2: must be an integer ≥ 0"),
    ("hs = [1.0, 1.0]\n", "names a value twice"),
    ('"payload.mass" = [1.0, -2.0]\n', r"payload.mass\[1\] = -2: .*negative"),
    ('payload_mass = [1.0]\n"payload.mass" = [2.0]\n', "name the same robot field"),
    ("heading = ['x']\n", r"heading\[0\] = \"x\": is text, not a number: give a finite number"),
    ("hs = [true]\n", r"hs\[0\] = true: is a boolean, not a number"),
    ('"payload.mass" = [true, 2.0]\n', r"payload.mass\[0\] = true: is a boolean, not a number"),
    ("heading = [90.0, 450.0]\n", r"names a value twice \(headings modulo 360°\)"),
    ("heading = [-90.0, 270.0]\n", r"names a value twice \(headings modulo 360°\)"),
])
def test_grid_errors(tmp_path, text, match):
    scene = scenes.load_scene(_scene(tmp_path))
    with pytest.raises(GridError, match=match):
        sweep.check_grid(scene, sweep.load_grid(_grid(tmp_path, text)), "grid.toml")


def test_grid_sea_key_needs_a_sea_scene(tmp_path):
    with pytest.raises(GridError, match="a sea key, but the scene .* is not a sea"):
        sweep.check_grid(scenes.Scene(duration=1.0), {"hs": [1.0]})


def test_grid_case_count_is_capped_before_anything_is_built(tmp_path, capsys):
    """10⁷ cases: one line at once, from the lists' lengths (memory grew by GBs while
    nothing was printed); --max-cases raises the limit."""
    import time

    scene = scenes.load_scene(_scene(tmp_path))
    big = {"hs": [1.0 + i for i in range(100)], "tp": [4.0 + i / 100 for i in range(1000)],
           "seed": list(range(100))}
    t0 = time.perf_counter()
    with pytest.raises(GridError, match=r"the grid makes 10,000,000 cases \(100 × 1000 × 100\)"
                       r", more than the limit 1,000,000: split it"):
        sweep.check_grid(scene, big)
    assert time.perf_counter() - t0 < 0.5
    with pytest.raises(GridError, match="makes 4 cases .* more than the limit 3"):
        sweep.check_grid(scene, {"hs": [1.0, 2.0], "seed": [0, 1]}, max_cases=3)
    small = sweep.check_grid(scene, {"hs": [1.0, 2.0], "seed": [0, 1]}, max_cases=4)
    assert small.count == len(list(small.cases())) == 4
    grid = _grid(tmp_path, "hs = [1.0, 2.0]\nseed = [0, 1, 2]\n")
    out = tmp_path / "res"
    assert main(["sweep", "--scene", str(_scene(tmp_path)), "--grid", str(grid), "--out",
                 str(out), "--max-cases", "5"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "makes 6 cases (2 × 3)" in err and not out.exists()


def test_grid_headings_are_directions(tmp_path):
    """A heading of 450° or -270° is the heading 90°: the same case (id included) as 90°,
    so that operability by heading never counts one direction twice (issue 21)."""
    scene = scenes.load_scene(_scene(tmp_path))
    ids = [sweep.case_id(scene, next(sweep.check_grid(scene, {"heading": [h]}).cases()))
           for h in (90.0, 450.0, -270.0, 810.0)]
    assert len(set(ids)) == 1
    assert list(sweep.check_grid(scene, {"heading": [-10.0]}).cases()) == [{"heading": 350.0}]


def test_grid_product_order_and_names(tmp_path):
    scene = scenes.load_scene(_scene(tmp_path))
    grid = sweep.check_grid(scene, sweep.load_grid(_grid(tmp_path, (
        "seed = [0, 1]\nhs = [1.0, 2.0]\npayload.mass = [0, 3]\n"))))
    assert grid.keys == ("payload.mass", "hs", "seed")          # robot slowest, seed fastest
    cases = list(grid.cases())
    assert len(cases) == 8 and cases[1] == {"payload.mass": 0.0, "hs": 1.0, "seed": 1}
    ids = sweep.CaseIds(scene)
    assert len({ids(c) for c in cases}) == 8


def test_a_grid_value_equal_to_the_scenes_own_is_the_scenes_case(tmp_path):
    """Case ids are of the resolved case: Hs 2.5 m on a scene of Hs 2.5 m, 2 kg of payload
    on a payload of 2 kg, the seed the scene has, a heading of 450° on a scene heading
    90°, a field by its alias: each is the scene's own case. Rerunning a grid that names
    them runs nothing again, the rows carry this grid's values, and read_results returns
    each case once with the scene's value where a row's grid did not vary a key."""
    scene = scenes.load_scene(_scene(tmp_path))
    ids = sweep.CaseIds(scene)
    own = ids({})
    for same in ({"hs": 2.5}, {"payload.mass": 2.0}, {"seed": 1}, {"heading": 450.0},
                 {"tp": 8.0, "scale": 20.0},
                 {"hs": 2.5, "payload.mass": 2.0, "seed": 1}):
        assert ids(same) == own, same
    for other in ({"hs": 2.4}, {"payload.mass": 2.5}, {"seed": 2}, {"heading": 91.0},
                  {"arm.link1.mass": 9.0}):
        assert ids(other) != own, other
    assert sweep.case_id(scene, {"payload.mass": 2.0}) == own
    out = tmp_path / "res"
    first = sweep.run(scene, {"seed": [1, 2]}, out=out)
    stats: dict = {}
    second = sweep.run(scene, {"hs": [2.5, 3.0], "seed": [1, 2]}, out=out, stats=stats)
    assert (stats["cases"], stats["skipped"], stats["ran"]) == (4, 2, 2)
    assert list(second["hs"]) == [2.5, 2.5, 3.0, 3.0]          # this grid's names
    assert list(second["seed"]) == [1, 2, 1, 2]
    assert set(first["case_id"]) == set(second["case_id"][:2])
    third = sweep.run(scene, {"payload.mass": [2.0, 3.0], "seed": [1]}, out=out,
                      stats=stats)
    assert (stats["skipped"], stats["ran"]) == (1, 1)
    assert list(third["payload.mass"]) == [2.0, 3.0]
    df = sweep.read_results(out).sort_values("case_id")
    assert len(df) == 5 and df["case_id"].is_unique
    assert not df[["hs", "seed", "payload.mass"]].isna().any().any()   # the scene's values
    row = df[df["case_id"] == own].iloc[0]
    assert (row["hs"], row["seed"], row["payload.mass"]) == (2.5, 1, 2.0)


# --------------------------------------------------------------------------- backends
@pytest.mark.slow
def test_rows_bit_identical_serial_forked_joblib_dask(tmp_path, monkeypatch):
    """The same rows, bit for bit, serially, on 2 forked workers (Linux), on 2 joblib
    (loky) workers (the path elsewhere, forced here) and on a Dask LocalCluster of 2
    workers; each run says where its cases ran."""
    from offshore_crane.studies.sweep import running

    scene = scenes.load_scene(_scene(tmp_path))
    grid = {"hs": [1.5, 3.0], "seed": [0, 1, 2, 3], "payload.mass": [1.0]}
    where = {}
    runs = {}
    for name, workers, scheduler in (("serial", 1, None), ("forked", 2, None),
                                     ("dask", 2, "local")):
        stats: dict = {}
        runs[name] = sweep.run(scene, grid, workers=workers, scheduler=scheduler,
                               stats=stats)
        where[name] = stats["backend"]
    monkeypatch.setattr(running, "can_fork", lambda: False)
    stats = {}
    runs["joblib"] = sweep.run(scene, grid, workers=2, stats=stats)
    where["joblib"] = stats["backend"]
    assert where == {"serial": "in this process", "forked": "on 2 forked workers",
                     "dask": "on the Dask cluster", "joblib": "on 2 joblib workers"}
    serial = runs["serial"]
    assert len(serial) == 8 and (serial["status"] == "ok").all()
    assert list(serial["case"]) == list(range(8))
    ref = _bits(serial)
    for other in (runs["forked"], runs["joblib"], runs["dask"]):
        assert list(other.columns) == list(serial.columns)
        got = _bits(other)
        for c in ref:
            np.testing.assert_array_equal(got[c], ref[c], err_msg=c)


@pytest.mark.slow
def test_remote_scheduler_address(tmp_path):
    """A scheduler given by its address (here a LocalCluster's tcp:// address, on
    loopback): the kernels are warmed up on its workers one at a time, and the rows are
    those of a serial run."""
    import distributed
    scene = scenes.load_scene(_scene(tmp_path))
    grid = {"hs": [1.0, 2.0]}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, host="127.0.0.1") as cluster:
        remote = sweep.run(scene, grid, scheduler=cluster.scheduler_address)
    ref, got = _bits(sweep.run(scene, grid)), _bits(remote)
    for c in ref:
        np.testing.assert_array_equal(got[c], ref[c], err_msg=c)


def test_failing_cases_are_recorded(tmp_path):
    """A record that leaves the workspace (scale too small) is a failed row with its error;
    the other cases run, those with a cable through the swing (sway and tension columns,
    equal to offshore_crane.dynamics.cable's own run; NaN without a cable)."""
    from offshore_crane.dynamics import cable

    scene = scenes.load_scene(_scene(tmp_path, offset="[0.0, 0.0, 0.0]"))
    df = sweep.run(scene, {"scale": [2.0, 20.0], "payload.cable_length": [0.0, 0.5]})
    status = dict(zip(zip(df["payload.cable_length"], df["scale"]), df["status"]))
    assert status == {(0.0, 2.0): "failed", (0.0, 20.0): "ok", (0.5, 2.0): "failed",
                      (0.5, 20.0): "ok"}
    row = df[(df["payload.cable_length"] == 0.0) & (df["scale"] == 2.0)].iloc[0]
    assert row["error_type"] == "SeaWorkspaceError" and "fits from scale" in row["error"]
    welded = df[(df["payload.cable_length"] == 0.0) & (df["scale"] == 20.0)].iloc[0]
    assert np.isnan(welded["sway_max"]) and np.isnan(welded["tension_min"])
    hanging = df[(df["payload.cable_length"] == 0.5) & (df["scale"] == 20.0)].iloc[0]
    case = sweep.case_scene(scene, {"payload.cable_length": 0.5})
    robot = scenes.load_robot(case)
    ref = cable.swing(robot, scenes.load_trajectory(case, robot))
    assert hanging["sway_max"] == ref.sway_angle.max() > 0
    assert (hanging["tension_min"], hanging["tension_max"]) == (ref.tension.min(),
                                                                ref.tension.max())
    assert hanging["Fl1_rms"] != welded["Fl1_rms"]          # the swing changes the forces
    v = sweep.verdicts(df, scene)
    assert (v["basis"] == "failed").sum() == 2 and np.isinf(v["worst_util"]).sum() == 2


def test_controlled_scene_simulates(tmp_path):
    """A scene with [control] runs the forward simulation; the envelope is of the applied
    forces, the condition numbers of the simulated motion."""
    path = tmp_path / "ctl.toml"
    path.write_text(SCENE.format(duration=0.5, rate=50.0)
                    + '[control]\nlaw = "computed-torque"\nkp = 400.0\nkd = 40.0\n')
    scene = scenes.load_scene(path)
    done = sweep.record(scene)
    assert done.kind == "simulation" and len(done.t) == 501     # every 1 ms step
    np.testing.assert_array_equal(done.X, done.simulation.X)
    assert done.envelope.peak_push[3] == max(done.simulation.X[:, 3].max(), 0.0)
    assert np.isfinite(done.envelope.kappa["leg"])


# --------------------------------------------------------------------------- the store
def test_resume_skips_finished_cases(tmp_path):
    scene = scenes.load_scene(_scene(tmp_path))
    out = tmp_path / "res"
    stats = {}
    first = sweep.run(scene, {"hs": [1.0, 2.0]}, out=out, stats=stats)
    assert stats["ran"] == 2
    before = {p.name: p.stat().st_mtime_ns for p in out.iterdir()}
    again = sweep.run(scene, {"hs": [1.0, 2.0, 3.0]}, out=out, stats=stats)
    assert (stats["skipped"], stats["ran"]) == (2, 1) and len(again) == 3
    for name, mtime in before.items():
        if name.startswith("rows-"):
            assert (out / name).stat().st_mtime_ns == mtime        # not rewritten
    assert len(list(out.glob("rows-*.parquet"))) == 2              # one file per run
    for c in first.columns:
        np.testing.assert_array_equal(_bits(again.iloc[:2])[c], _bits(first)[c])
    manifest = json.loads((out / "_manifest.json").read_text())
    assert manifest["grids"] == [{"hs": [1.0, 2.0]}, {"hs": [1.0, 2.0, 3.0]}]
    assert len(sweep.read_results(out)) == 3                       # a Parquet dataset


def test_a_batch_is_written_after_its_time_even_when_no_row_follows(tmp_path, monkeypatch):
    """A batch's first row waits at most OFFSHORE_CRANE_BATCH_SECONDS: the timer writes
    it without another row arriving; finish() compacts the run's batches into one file
    holding every row once."""
    from offshore_crane.studies.sweep import rowfiles

    scene = scenes.load_scene(_scene(tmp_path))
    rows = sweep.run(scene, {"hs": [1.0, 2.0, 3.0]}, out=tmp_path / "ref")
    schema = sweep.row_schema(sweep.check_grid(scene, {"hs": [1.0, 2.0, 3.0]}))
    records = rowfiles.read_rows(str(tmp_path / "ref")).to_pylist()
    monkeypatch.setenv("OFFSHORE_CRANE_BATCH_SECONDS", "0.05")
    out = tmp_path / "res"
    out.mkdir()
    writer = rowfiles.BatchWriter(str(out), schema)
    writer.add(records[0])
    assert not list(out.glob("part-*"))              # held: its time has not come
    deadline = time.monotonic() + 5.0                # the timer fires after 0.05 s
    while not list(out.glob("part-*")) and time.monotonic() < deadline:
        time.sleep(0.01)
    assert len(list(out.glob("part-*"))) == 1
    writer.add(records[1])
    writer.add(records[2])
    writer.finish()
    assert [p.name for p in out.iterdir()] == [f"rows-{writer.run}.parquet"]
    back = rowfiles.read_rows(str(out)).to_pandas()
    assert sorted(back["case_id"]) == sorted(rows["case_id"])


def test_a_case_in_two_files_is_read_once_and_recovery_removes_compacted_batches(tmp_path):
    """A run killed between writing its compacted file and removing its batches leaves
    each of those cases twice: read_results returns them once, and the next run's
    recovery removes the batches; batches of a killed run that never compacted are
    compacted by it."""
    scene_path = _scene(tmp_path)
    scene = scenes.load_scene(scene_path)
    out = tmp_path / "res"
    first = sweep.run(scene, {"hs": [1.0, 2.0]}, out=out)
    (whole,) = out.glob("rows-*.parquet")
    run = whole.name[len("rows-"):-len(".parquet")]
    part = out / f"part-{run}-000000.parquet"
    part.write_bytes(whole.read_bytes())            # as if killed before the unlink
    orphan = out / "part-19990101T000000-1-abcd-000000.parquet"
    orphan.write_bytes(whole.read_bytes())          # a dead run that never compacted
    df = sweep.read_results(out)
    assert len(df) == 2 and df["case_id"].is_unique
    assert sorted(df["case_id"]) == sorted(first["case_id"])
    stats: dict = {}
    sweep.run(scene, {"hs": [1.0, 2.0]}, out=out, stats=stats)        # recovers, skips
    assert stats["ran"] == 0
    names = sorted(p.name for p in out.iterdir() if p.name.endswith(".parquet"))
    assert names == sorted([whole.name, "rows-19990101T000000-1-abcd.parquet"])
    assert len(sweep.read_results(out)) == 2


@pytest.mark.parametrize("damage", [b"", b"PAR1 not really", None])
def test_a_damaged_row_file_is_named_in_one_line(tmp_path, capsys, damage):
    """A row file that is not Parquet (empty, garbage, truncated) is named, with what to
    do, by read_results, by a rerun of the library and by the command line (exit 2)."""
    scene_path = _scene(tmp_path)
    scene = scenes.load_scene(scene_path)
    out = tmp_path / "res"
    sweep.run(scene, {"hs": [1.0, 2.0]}, out=out)
    (whole,) = out.glob("rows-*.parquet")
    data = whole.read_bytes()
    whole.write_bytes(data[:len(data) // 2] if damage is None else damage)
    message = f"{whole.name} is damaged .*move it out of the directory"
    with pytest.raises(ResultsDirectoryError, match=message):
        sweep.read_results(out)
    with pytest.raises(ResultsDirectoryError, match=message):
        sweep.run(scene, {"hs": [1.0, 2.0]}, out=out)
    grid = _grid(tmp_path, "hs = [1.0, 2.0]\n")
    code = main(["sweep", "--scene", str(scene_path), "--grid", str(grid), "--out", str(out),
                 "--no-progress"])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and whole.name in err


def test_a_version_1_directory_of_one_file_per_case_is_read_and_resumed(tmp_path):
    """Directories written before batches (case-<id>.parquet, one row each) are read and
    resumed: their cases are not run again."""
    from offshore_crane.studies.sweep import rowfiles

    scene = scenes.load_scene(_scene(tmp_path))
    out = tmp_path / "res"
    first = sweep.run(scene, {"hs": [1.0, 2.0]}, out=out)
    (whole,) = out.glob("rows-*.parquet")
    table = rowfiles.read_rows(str(out))
    whole.unlink()
    for i in range(table.num_rows):
        one = table.slice(i, 1)
        (out / f"case-{one.column('case_id')[0].as_py()}.parquet").write_bytes(
            rowfiles.parquet_bytes(one))
    stats: dict = {}
    again = sweep.run(scene, {"hs": [1.0, 2.0, 3.0]}, out=out, stats=stats)
    assert (stats["skipped"], stats["ran"]) == (2, 1)
    assert set(first["case_id"]) < set(again["case_id"])
    assert len(sweep.read_results(out)) == 3


def test_a_version_1_directory_is_migrated_to_resolved_case_ids(tmp_path):
    """Rows stored under version 1's ids (a hash of the grid's values as given) are given
    their resolved cases' ids when a run takes the directory: nothing is run again, a
    grid naming the scene's own value finds its case, each case is read once."""
    import hashlib

    from offshore_crane.studies.sweep import rowfiles

    scene = scenes.load_scene(_scene(tmp_path))
    out = tmp_path / "res"
    first = sweep.run(scene, {"hs": [2.5, 3.0]}, out=out)
    table = rowfiles.read_rows(str(out))
    old = [hashlib.sha256(json.dumps({"hs": h}, sort_keys=True).encode()).hexdigest()[:16]
           for h in table.column("hs").to_pylist()]
    import pyarrow as pa
    table = table.set_column(0, "case_id", pa.array(old, pa.string()))
    for p in out.glob("rows-*"):
        p.unlink()
    (out / "rows-19990101T000000-1-abcd.parquet").write_bytes(rowfiles.parquet_bytes(table))
    manifest = json.loads((out / "_manifest.json").read_text())
    manifest["version"] = 1
    del manifest["scene"]["values"]
    (out / "_manifest.json").write_text(json.dumps(manifest))
    stats: dict = {}
    again = sweep.run(scene, {"seed": [1, 2]}, out=out, stats=stats)   # seed 1: Hs 2.5
    assert (stats["skipped"], stats["ran"]) == (1, 1)
    assert json.loads((out / "_manifest.json").read_text())["version"] == 2
    assert set(first["case_id"]) <= set(sweep.read_results(out)["case_id"])
    assert first["case_id"][0] == again["case_id"][0]
    assert len(sweep.read_results(out)) == 3


@pytest.mark.slow
def test_killed_sweeps_rerun_to_every_case_once_bit_identical(tmp_path):
    """SIGKILL a sweep at a random moment of its run, 10 times (seeded): after each rerun
    every case is in the directory exactly once and bit-identical to an uninterrupted
    run's row, the killed run's batches are compacted, no temporary file is left. Batches
    every 0.1 s so that kills land between, inside and after them."""
    import random

    scene = _scene(tmp_path, duration=150.0, rate=100.0)          # ~50 ms a case
    grid = _grid(tmp_path, "hs = [1.0, 1.5, 2.0, 2.5]\nseed = [0, 1, 2, 3, 4, 5]\n")
    reference = _bits(sweep.run(scenes.load_scene(scene), sweep.load_grid(grid))
                      .sort_values("case_id").drop(columns="case").reset_index(drop=True))
    env = {**os.environ, "PYTHONPATH": str(SRC), "OFFSHORE_CRANE_BATCH_SECONDS": "0.1"}

    def command(out):
        return [sys.executable, "-m", "offshore_crane", "sweep", "--scene", str(scene),
                "--grid", str(grid), "--out", str(out), "--no-progress"]

    def start(out):
        """The sweep's process, once its manifest is written (its cases start)."""
        proc = subprocess.Popen(command(out), env=env, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 60
        while not (out / "_manifest.json").exists() and proc.poll() is None \
                and time.monotonic() < deadline:
            time.sleep(0.005)
        return proc

    for name in ("warm", "whole"):                # the second's span: kernels cached
        proc = start(tmp_path / name)
        t0 = time.monotonic()
        assert proc.wait() == 0
        span = time.monotonic() - t0              # warm-up, cases, compaction
    rng = random.Random(20261125)
    kept_counts = []
    for k in range(10):                           # 20 took 64 s of CI; 10 land throughout
        out = tmp_path / f"run{k}"
        proc = start(out)
        try:
            time.sleep(rng.uniform(0.0, 1.1) * span)
            proc.send_signal(signal.SIGKILL)
        finally:
            proc.wait()
        kept_counts.append(len(sweep.ResultsStore.open(out, scenes.load_scene(scene)).done())
                           if (out / "_manifest.json").exists() else 0)
        os.environ["OFFSHORE_CRANE_BATCH_SECONDS"] = "0.1"
        try:
            sweep.run(scenes.load_scene(scene), sweep.load_grid(grid), out=out)
        finally:
            del os.environ["OFFSHORE_CRANE_BATCH_SECONDS"]
        df = sweep.read_results(out)
        assert len(df) == 24 and df["case_id"].is_unique
        got = _bits(df.sort_values("case_id").reset_index(drop=True)[
            [c for c in df.columns if c in reference]])
        assert got.keys() == reference.keys()
        for c in reference:
            assert np.array_equal(got[c], reference[c]), (k, c)
        names = os.listdir(out)
        assert not [n for n in names if n.startswith("part-") or n.endswith(".tmp")], names
        assert len([n for n in names if n.startswith("rows-")]) <= 2     # killed, rerun
    print("rows kept by the killed runs:", kept_counts)
    assert any(0 < n < 24 for n in kept_counts), f"no kill landed mid-run: {kept_counts}"


def _children(pid: int, marker: str) -> set:
    """Pids of the processes whose parent is ``pid`` and whose command line holds
    ``marker`` (read from /proc)."""
    found = set()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            status = (entry / "status").read_text()
            cmdline = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except OSError:
            continue
        ppid = int(next(l.split()[1] for l in status.splitlines() if l.startswith("PPid:")))
        if ppid == pid and marker in cmdline:
            found.add(int(entry.name))
    return found


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="reads /proc (Linux)")
def test_a_killed_sweeps_workers_exit(tmp_path):
    """SIGKILL leaves the sweep no time to stop its workers (forked from it): they notice
    they were orphaned and exit within a second or two (joblib's idled ~300 s with
    ~180 MB each)."""
    seeds = ", ".join(str(s) for s in range(400))
    grid = _grid(tmp_path, f"hs = [1.0, 2.0]\nseed = [{seeds}]\n")
    cmd = [sys.executable, "-m", "offshore_crane", "sweep", "--scene", str(_scene(tmp_path)),
           "--grid", str(grid), "--out", str(tmp_path / "res"), "--workers", "2",
           "--no-progress"]
    proc = subprocess.Popen(cmd, env={**os.environ, "PYTHONPATH": str(SRC)},
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    workers: set = set()
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and len(workers) < 2 and proc.poll() is None:
            workers = _children(proc.pid, "offshore_crane")
            time.sleep(0.05)
        time.sleep(0.5)                               # the workers are running cases
        assert proc.poll() is None and len(workers) == 2, "no workers seen: longer grid"
        proc.send_signal(signal.SIGKILL)
    finally:
        proc.wait()
    deadline = time.monotonic() + 5.0                 # ORPHAN_POLL 0.5 s, and a case
    while time.monotonic() < deadline and any(Path(f"/proc/{w}").exists() for w in workers):
        time.sleep(0.1)
    alive = [w for w in workers if Path(f"/proc/{w}").exists()
             and "offshore_crane" in Path(f"/proc/{w}/cmdline").read_bytes().decode(errors="replace")]
    assert not alive, f"workers {alive} outlived the sweep by 5 s"


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="reads /proc (Linux)")
def test_ctrl_c_stops_a_sweep_and_its_workers_in_one_line(tmp_path):
    """SIGINT to the process group (what a terminal's Ctrl-C sends): the sweep says so in
    one line and exits 130, its forked workers (which ignore it) are terminated, and the
    rows it finished stay readable."""
    seeds = ", ".join(str(s) for s in range(400))
    grid = _grid(tmp_path, f"hs = [1.0, 2.0]\nseed = [{seeds}]\n")
    out = tmp_path / "res"
    cmd = [sys.executable, "-m", "offshore_crane", "sweep", "--scene", str(_scene(tmp_path)),
           "--grid", str(grid), "--out", str(out), "--workers", "2", "--no-progress"]
    proc = subprocess.Popen(cmd, env={**os.environ, "PYTHONPATH": str(SRC)},
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    workers: set = set()
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and len(workers) < 2 and proc.poll() is None:
        workers = _children(proc.pid, "offshore_crane")
        time.sleep(0.05)
    time.sleep(0.5)
    assert proc.poll() is None and len(workers) == 2
    os.killpg(proc.pid, signal.SIGINT)
    err = proc.communicate(timeout=30)[1]
    assert proc.returncode == 130, err
    assert err.splitlines() == ["offshore-crane: interrupted (SIGINT); nothing half-written "
                                "was left"], err
    deadline = time.monotonic() + 5.0
    while time.monotonic() < deadline and any(Path(f"/proc/{w}").exists() for w in workers):
        time.sleep(0.1)
    assert not [w for w in workers if Path(f"/proc/{w}").exists()]
    assert 0 < len(sweep.read_results(out)) < 800


def test_out_of_another_scene_is_refused(tmp_path, capsys):
    grid = _grid(tmp_path, "hs = [1.0]\n")
    out = tmp_path / "res"
    assert main(["sweep", "--scene", str(_scene(tmp_path)), "--grid", str(grid),
                 "--out", str(out), "--no-progress"]) == 0
    capsys.readouterr()
    listing = sorted(os.listdir(out))
    other = _scene(tmp_path, name="other.toml", hs="3.0")
    assert main(["sweep", "--scene", str(other), "--grid", str(grid), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "holds the results of another scene" in err and err.count("\n") == 1
    assert sorted(os.listdir(out)) == listing
    scene = scenes.load_scene(_scene(tmp_path))
    junk = tmp_path / "junk"
    junk.mkdir()
    (junk / "notes.txt").write_text("x")
    with pytest.raises(ResultsDirectoryError, match="holds files but no sweep manifest"):
        sweep.run(scene, {"hs": [1.0]}, out=junk)
    with pytest.raises(ResultsDirectoryError, match="is not a directory"):
        sweep.run(scene, {"hs": [1.0]}, out=junk / "notes.txt")
    assert os.listdir(junk) == ["notes.txt"]


@pytest.mark.parametrize("argv, match", [
    (["--scheduler", "tcp://127.0.0.1:9"], "cannot reach the Dask scheduler"),
    (["--scheduler", "127.0.0.1:9"], "give 'local'"),
    (["--scheduler", "http://127.0.0.1:8786"], "the scheme must be tcp"),
    (["--scheduler", "tcp://127.0.0.1:99999"], "the port must be 1..65535"),
    (["--scheduler", "tcp://127.0.0.1"], "the port must be 1..65535"),
    (["--scheduler", "tcp://:8786"], "no host"),
    (["--workers", "0"], "--workers 0: must be ≥ 1"),
])
def test_cli_errors_write_nothing(tmp_path, capsys, argv, match):
    grid = _grid(tmp_path, "hs = [1.0, 2.0]\n")
    out = tmp_path / "res"
    status = main(["sweep", "--scene", str(_scene(tmp_path)), "--grid", str(grid),
                   "--out", str(out), *argv])
    err = capsys.readouterr().err
    assert status == 2 and match in err and err.count("\n") == 1
    assert not out.exists()


def test_a_listener_that_is_not_dask_ends_in_the_timeout(tmp_path, capsys):
    """--scheduler at a web server (it listens, accepts, and waits for a request): one
    line and exit 2 within CONNECT_TIMEOUT, nothing written (it hung for minutes)."""
    import http.server
    import threading
    import time

    server = http.server.HTTPServer(("127.0.0.1", 0), http.server.BaseHTTPRequestHandler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        out = tmp_path / "res"
        t0 = time.perf_counter()
        status = main(["sweep", "--scene", str(_scene(tmp_path)), "--grid",
                       str(_grid(tmp_path, "hs = [1.0]\n")), "--out", str(out),
                       "--scheduler", f"tcp://127.0.0.1:{server.server_address[1]}"])
        took = time.perf_counter() - t0
    finally:
        server.shutdown()
    err = capsys.readouterr().err
    assert status == 2 and err.count("\n") == 1, err
    assert "sent no Dask handshake within 3 s" in err
    assert took < sweep.CONNECT_TIMEOUT + 2.0 and not out.exists()


def test_cli_bad_grid_one_line(tmp_path, capsys):
    grid = _grid(tmp_path, "hs = [0.0]\n")
    out = tmp_path / "res"
    assert main(["sweep", "--scene", str(_scene(tmp_path)), "--grid", str(grid),
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "hs[0] = 0" in err and "must be > 0" in err and err.count("\n") == 1
    assert not out.exists()


# --------------------------------------------------------------------------- verdicts
def test_verdicts_gumbel_from_rows(tmp_path):
    """Five seeds of exposure records: the verdict's utilisation is the Gumbel MPM of the
    rows' utilisations (equal to the MPM of the peaks over the capacity, the fit being
    equivariant); the scene's own short records: the largest observed, not extrapolated."""
    from offshore_crane.studies import sizing

    scene = scenes.load_scene(_scene(tmp_path, exposure=True))
    df = sweep.run(scene, {"seed": [0, 1, 2, 3, 4]})
    v = sweep.verdicts(df, scene, 36.0)
    assert len(v) == 1 and v["basis"][0] == "gumbel" and v["seeds"][0] == 5
    record = float(v["record_s"][0])
    assert 36.0 - 0.02 * np.sqrt(20.0) <= record <= 36.0     # the exposure, to one sample
    util = sizing.most_probable_maximum(df["Fl6_util_speed"], record, 36.0)
    peak = sizing.most_probable_maximum(df["Fl6_peak_speed"], record, 36.0)
    assert util == pytest.approx(peak / 0.5, rel=1e-12)
    assert v["Fl6_util"][0] >= util
    own = scenes.load_scene(_scene(tmp_path, name="own.toml"))
    df = sweep.run(own, {"seed": [0, 1, 2, 3, 4]})
    v = sweep.verdicts(df, own)
    assert v["basis"][0] == "observed"
    assert v["Fl6_util"][0] == df[[f"Fl6_util_{c}" for c in sizing.CAPACITIES]].max().max()


def test_limiting_hs_and_operability(tmp_path):
    import pandas as pd
    assert sweep.limiting_hs([1, 2, 3], [0.4, 0.8, 1.2]) == pytest.approx(2.5)
    assert sweep.limiting_hs([1, 2, 3], [0.4, 0.8, 0.9]) == 3.0      # never exceeded
    assert sweep.limiting_hs([1, 2, 3], [1.1, 0.8, 0.9]) == 0.0      # first crossing
    assert sweep.limiting_hs([1, 2, 3], [0.5, np.inf, 0.9]) == 1.0   # failed case
    # utilisation = hs / 2.5 at tp 6, hs / 1.5 at tp 10: limits 2.5 m and 1.5 m
    rows = [{"hs": h, "tp": tp, "heading": hd, "worst_util": h / lim}
            for hd, scale in ((90.0, 1.0), (180.0, 2.0)) for tp, lim0 in ((6.0, 2.5),
                                                                           (10.0, 1.5))
            for lim in (lim0 * scale,) for h in (1.0, 2.0, 3.0)]
    table = pd.DataFrame(rows)
    path = tmp_path / "scatter.csv"
    path.write_text("# test\nhs_m/tp_s,6,8,10,12\n1.0,1,1,1,1\n2.0,1,1,1,1\n"
                    "2.8,1,1,1,1\n")
    scatter = sweep.load_scatter(path)
    assert scatter.p.sum() == pytest.approx(1.0)
    op = sweep.operability(table, scatter, scenes.Scene(duration=1.0))
    by = dict(zip(op["heading"].fillna(-1), op["operability_pct"]))
    # heading 90: limit at tp 6, 8, 10 = 2.5, 2.0, 1.5 m -> cells (1,6) (2,6) (1,8) (2,8)
    # (1,10): 5 of 12; tp 12 is outside the swept Tp (not operable)
    assert by[90.0] == pytest.approx(100 * 5 / 12)
    # heading 180: limits 5, 4, 3 m clipped to the swept 3 m -> all 9 covered cells
    assert by[180.0] == pytest.approx(100 * 9 / 12)
    assert by[-1] == pytest.approx(100 * 7 / 12)
    assert op["uncovered_pct"].iloc[0] == pytest.approx(100 * 3 / 12)


#: The sweep scene with its payload on a 1 m cable judged by the slack criterion (a
#: fraction 0.9 of the static tension: crossed by the larger sea state, so that the
#: "no slack" diagram has a limit inside the grid).
LIFT_SCENE = SCENE.replace("offset = [0.0, 0.0, -0.05]", """cable_length = 1.0
sway_damping = 0.25
[payload.limits]
tension_ratio_min = 0.9
sway_max_deg = 45.0""").replace('record = "scene"', EXPOSURE_RECORDS)


def test_lift_columns_and_the_no_slack_operability(tmp_path):
    """Rows carry the lift figures (tension ratios over m g, time slack, the load's
    utilisations); the verdict's slack utilisation is the limit over the most probable
    minimum of the tension ratio (the Gumbel fit of its negation, by hand here), the
    load's worst and the overall worst are the larger ones; the "no slack" operability
    reads slack_util (a limiting Hs between the swept ones)."""
    from offshore_crane.studies import sizing

    path = tmp_path / "lift.toml"
    path.write_text(LIFT_SCENE.format(duration=5.0, rate=50.0))
    scene = scenes.load_scene(path)
    df = sweep.run(scene, {"hs": [1.0, 3.0], "seed": [0, 1, 2, 3, 4]})
    assert (df["status"] == "ok").all()
    g = 2.0 * 9.81
    assert np.allclose(df["tension_ratio_min"], df["tension_min"] / g, rtol=1e-15)
    assert np.allclose(df["tension_ratio_max"], df["tension_max"] / g, rtol=1e-15)
    assert (df["time_slack_s"] == 0.0).all() and (df["tension_ratio_limit"] == 0.9).all()
    assert np.allclose(df["slack_util"], 0.9 / df["tension_ratio_min"], rtol=1e-15)
    assert np.allclose(df["sway_util"], df["sway_max"] / np.radians(45.0), rtol=1e-15)
    assert np.allclose(df["load_util"], np.maximum(df["slack_util"], df["sway_util"]))
    assert df["winch_util_pull"].isna().all()             # no winch
    v = sweep.verdicts(df, scene, 36.0).set_index("hs")
    for hs in (1.0, 3.0):
        assert v.loc[hs, "basis"] == "gumbel"
        record = v.loc[hs, "record_s"]
        ratio = df.loc[df["hs"] == hs, "tension_ratio_min"]
        mpm_min = -sizing.most_probable_maximum(-ratio, record, 36.0)
        assert v.loc[hs, "tension_ratio_min"] == pytest.approx(mpm_min, rel=1e-12)
        assert v.loc[hs, "slack_util"] == pytest.approx(0.9 / mpm_min, rel=1e-12)
        assert v.loc[hs, "load_util"] == max(v.loc[hs, "slack_util"], v.loc[hs, "sway_util"])
        assert v.loc[hs, "overall_util"] == max(v.loc[hs, "load_util"],
                                               v.loc[hs, "worst_util"])
    assert v.loc[1.0, "slack_util"] < 1.0 < v.loc[3.0, "slack_util"]
    scatter_path = tmp_path / "scatter.csv"
    scatter_path.write_text("hs_m/tp_s,8\n1.0,1\n3.0,1\n5.0,1\n")
    op = sweep.operability(v.reset_index(), sweep.load_scatter(scatter_path), scene,
                           "no slack")
    limit = sweep.limiting_hs([1.0, 3.0], v["slack_util"])
    assert 1.0 < limit < 3.0
    expected = 100.0 * np.mean([h <= limit for h in (1.0, 3.0, 5.0)])
    assert op["operability_pct"].iloc[-1] == pytest.approx(expected)
    with pytest.raises(InputError, match="criterion 'slack' is not one of"):
        sweep.operability(v.reset_index(), sweep.load_scatter(scatter_path), scene, "slack")


def test_a_failed_case_is_inoperable_by_every_criterion(tmp_path):
    path = tmp_path / "lift.toml"
    path.write_text(LIFT_SCENE.format(duration=5.0, rate=50.0))
    scene = scenes.load_scene(path)
    df = sweep.run(scene, {"hs": [1.0, 12.0]})
    assert list(df["status"]) == ["ok", "failed"]
    v = sweep.verdicts(df, scene).set_index("hs")
    for column in sweep.CRITERIA.values():
        assert np.isfinite(v.loc[1.0, column]) and np.isinf(v.loc[12.0, column])


@pytest.mark.parametrize("text, match", [
    ("hs_m/tp_s,6,8\n1.0,1,x\n", r"line 2, cell 3: 'x' is not a finite number"),
    ("hs_m/tp_s,6,8\n1.0,1\n", "2 cells, but the header has 3"),
    ("hs_m/tp_s,8,6\n1.0,1,1\n", "the Tp values of the header must increase"),
    ("hs_m/tp_s,6,8\n1.0,0,0\n", "every occurrence is 0"),
])
def test_scatter_errors(tmp_path, text, match):
    from offshore_crane.errors import InputError

    path = tmp_path / "s.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=match):
        sweep.load_scatter(path)


def test_cli_sweep_of_a_hanging_load_draws_the_no_slack_diagram(tmp_path, capsys):
    path = tmp_path / "lift.toml"
    path.write_text(LIFT_SCENE.format(duration=5.0, rate=50.0))
    grid = _grid(tmp_path, "hs = [1.0, 3.0]\ntp = [6.0, 9.0]\n")
    scatter = tmp_path / "s.csv"
    scatter.write_text("hs_m/tp_s,6,9\n1.0,3,1\n3.0,1,1\n")
    plots = tmp_path / "plots"
    assert main(["sweep", "--scene", str(path), "--grid", str(grid), "--plot", str(plots),
                 "--scatter", str(scatter), "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "load %" in out and "load: slack" in out
    assert " no slack (the slack criterion" in out and "actuators and hanging load" in out
    assert sorted(os.listdir(plots)) == [
        "operability-all.png", "operability-load.png", "operability-no-slack.png",
        "operability.png", "utilisation-worst-case.png"]


def test_cli_sweep_plots_csv_and_operability(tmp_path, capsys):
    grid = _grid(tmp_path, "hs = [1.0, 3.0]\ntp = [6.0, 9.0]\n")
    scatter = tmp_path / "s.csv"
    scatter.write_text("hs_m/tp_s,6,9\n1.0,3,1\n3.0,1,1\n")
    plots = tmp_path / "plots"
    assert main(["sweep", "--scene", str(_scene(tmp_path)), "--grid", str(grid),
                 "--plot", str(plots), "--csv", str(tmp_path / "rows.csv"),
                 "--scatter", str(scatter), "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "heading 90°:" in out and "overall:" in out
    assert sorted(os.listdir(plots)) == ["operability.png", "utilisation-worst-case.png"]
    rows = (tmp_path / "rows.csv").read_text().splitlines()
    assert len(rows) == 5 and rows[0].startswith("case,case_id,hs,tp,status")


def test_imports_stay_lazy():
    """Importing the package, the new modules and the CLI, and running ``id``, import
    none of the sweep's optional libraries (nor matplotlib)."""
    code = ("import sys; import offshore_crane, offshore_crane.studies.sizing, offshore_crane.studies.sweep, "
            "offshore_crane.cli.size, offshore_crane.cli.sweep; "
            "from offshore_crane.__main__ import main; "
            "assert main(['id', '--duration', '1']) == 0; "
            "assert main(['size', '--duration', '1']) == 0; "
            "heavy = ('joblib', 'dask', 'distributed', 'pandas', 'pyarrow', 'tqdm', "
            "'matplotlib', 'pinocchio', 'imageio', 'viser', 'mujoco'); "
            "bad = [m for m in heavy if m in sys.modules]; assert not bad, bad")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(SRC)})
    assert proc.returncode == 0, proc.stderr


def test_kane_sweep_imports_neither_pinocchio_nor_matplotlib(tmp_path):
    """A sweep of a Kane scene without --plot loads only what it runs (its warm-up too)."""
    scene = _scene(tmp_path)
    code = ("import sys; from offshore_crane.studies import sweep; "
            f"df = sweep.run({str(scene)!r}, {{'hs': [1.0]}}); "
            "assert (df['status'] == 'ok').all(); "
            "bad = [m for m in ('pinocchio', 'matplotlib') if m in sys.modules]; "
            "assert not bad, bad")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(SRC)})
    assert proc.returncode == 0, proc.stderr


# --------------------------------------------------------------------------- the lock
def test_a_results_directory_in_use_is_refused_at_once(tmp_path):
    """While a sweep holds its results directory, another is refused at once naming the
    holder; once released, the directory is free again (issue 21)."""
    import filelock

    from offshore_crane.errors import ResultsDirectoryError
    from offshore_crane.studies.sweep.store import LOCK, LOCK_INFO

    scene = scenes.load_scene(_scene(tmp_path))
    out = tmp_path / "res"
    out.mkdir()
    holder = filelock.FileLock(str(out / LOCK), timeout=0)
    holder.acquire()
    (out / LOCK_INFO).write_text('{"pid": 4242, "since": "2026-11-25 12:03:00"}')
    try:
        with pytest.raises(ResultsDirectoryError, match=r"res: in use by process 4242 since "
                           r"2026-11-25 12:03:00: wait for that sweep to end"):
            sweep.run(scene, {"payload.mass": [0.0]}, out=out)
        assert sorted(os.listdir(out)) == [LOCK, LOCK_INFO]        # nothing written
    finally:
        holder.release()
        (out / LOCK_INFO).unlink()
    df = sweep.run(scene, {"payload.mass": [0.0]}, out=out)
    assert len(df) == 1 and not (out / LOCK_INFO).exists()


@pytest.mark.slow
def test_two_sweeps_of_different_scenes_on_one_directory(tmp_path):
    """Started together on one new directory: one is refused (exit 2, one line), the
    other's manifest and rows are intact and its own (they both exited 0 and mixed)."""
    import json

    out = tmp_path / "res"
    runs = []
    for k, mass in enumerate(("0.5", "1.5")):
        scene = _scene(tmp_path, name=f"scene{k}.toml")
        scene.write_text(scene.read_text() + f'\n# scene {k}\n')
        grid = _grid(tmp_path, f"payload.mass = [{mass}, {mass}1, {mass}2]\n",
                     name=f"grid{k}.toml")
        runs.append(subprocess.Popen(
            [sys.executable, "-m", "offshore_crane", "sweep", "--scene", str(scene), "--grid",
             str(grid), "--out", str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
            text=True))
    results = [(p.wait(timeout=300), p.stderr.read()) for p in runs]
    codes = sorted(code for code, _ in results)
    assert codes == [0, 2], results
    loser = next(err for code, err in results if code == 2)
    assert loser.count("\n") == 1 and ("in use by process" in loser
                                       or "holds the results of another scene" in loser)
    manifest = json.loads((out / "_manifest.json").read_text())
    winner = next(k for k, (code, _) in enumerate(results) if code == 0)
    assert len(manifest["grids"]) == 1
    assert len(sweep.read_results(out)) == 3
    assert manifest["grids"][0]["payload.mass"][0] == (0.5, 1.5)[winner]


def test_a_directory_just_taken_by_another_run_is_not_called_foreign(tmp_path):
    """The race CI met: a run that has just taken a new directory holds its lock, its
    name and a whole-file write's temporary (.oc-*.tmp), no manifest yet; a second run
    opening the directory then must not call it "not a results directory" (it goes on
    to the lock, which names the holder)."""
    from offshore_crane.studies.sweep.store import LOCK, LOCK_INFO, ResultsStore

    out = tmp_path / "res"
    out.mkdir()
    for name in (LOCK, LOCK_INFO, ".oc-a1b2c3d4.tmp"):
        (out / name).write_text("")
    scene = scenes.load_scene(_scene(tmp_path))
    assert ResultsStore.open(out, scene).manifest is None
    (out / "notes.txt").write_text("mine")
    with pytest.raises(ResultsDirectoryError, match="holds files but no sweep manifest"):
        ResultsStore.open(out, scene)


def test_a_refused_run_waits_for_the_holder_to_say_who_it_is(tmp_path):
    """The holder writes its name just after taking the lock: a run refused in between
    waits for it (up to store.HOLDER_WAIT) and names the process, not 'another process'
    (a race two sweeps started together met in CI)."""
    import threading

    import filelock

    from offshore_crane.studies.sweep import store as st

    out = tmp_path / "res"
    out.mkdir()
    lock = filelock.FileLock(str(out / st.LOCK), timeout=0)
    lock.acquire()
    try:
        late = threading.Timer(0.2, lambda: (out / st.LOCK_INFO).write_text(
            json.dumps({"pid": 4321, "since": "2026-11-25 17:00:00"})))
        late.start()
        scene = scenes.load_scene(_scene(tmp_path))
        store = sweep.ResultsStore.open(out, scene)
        with pytest.raises(ResultsDirectoryError,
                           match=r"in use by process 4321 since 2026-11-25 17:00:00"):
            store.lock(scene)
        late.join()
    finally:
        lock.release()
