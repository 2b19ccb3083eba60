"""Hostile sweeps (issue 36): a case that fails is a failed row, never the sweep's end
(a library error as its message, any other exception as an internal error to report),
serially and on forked workers, while the process's own failures (out of memory, Ctrl-C)
still end it; a results directory that cannot be written is one line; whatever a peer on
the scheduler's port sends is read within bounds on size and time (it once made the sweep
allocate exabytes); every malformed address is one line.

Every test is cheap (short model-scale records, local servers) and runs under a deadline,
so that a regression fails instead of hanging.
"""

from __future__ import annotations

import contextlib
import errno
import os
import random
import socket
import struct
import threading
import time

import numpy as np
import pytest

from offshore_crane import scenes
from offshore_crane.cli import main
from offshore_crane.errors import (InputError, OutputError, ResultsDirectoryError,
                                   SchedulerError, SeaWorkspaceError)
from offshore_crane.studies import sweep
from offshore_crane.studies.sweep.cases import fatal

from conftest import deadline
from test_sweep import _bits, _grid, _scene


# --------------------------------------------------------------------------- failed cases
def _breaks_at(monkeypatch, hs: float, error) -> None:
    """``scenes.load_trajectory`` (which every case calls) failing for the case of
    Hs = ``hs`` once it has built the record: ``IndexError`` as a library bug would (an
    index one past the record's end, raised by NumPy), any other exception class raised
    as it is."""
    real = scenes.load_trajectory

    def load(scene, robot, *args, **kwargs):
        traj = real(scene, robot, *args, **kwargs)
        if scene.sea.get("hs") == hs:
            if error is IndexError:
                traj.t[len(traj.t)]
            raise error
        return traj

    monkeypatch.setattr(scenes, "load_trajectory", load)


@pytest.mark.parametrize("workers", [1, 2])
def test_a_failing_case_is_a_failed_row_and_the_others_finish(tmp_path, monkeypatch, workers):
    """Scale 2 leaves the workspace (a library error: its message); the case of Hs 2 m
    meets an IndexError (an internal error: one line saying so and to report it, with
    where it was raised). Both are rows; the other cases' rows are those of a run without
    the failing ones, bit for bit, serially and on forked workers (which inherit the
    injected error); the store holds all six (it once ended the whole sweep)."""
    scene = scenes.load_scene(_scene(tmp_path, offset="[0.0, 0.0, 0.0]"))
    clean = sweep.run(scene, {"scale": [20.0], "hs": [1.0, 3.0]})
    _breaks_at(monkeypatch, 2.0, IndexError)
    out = tmp_path / "res"
    stats: dict = {}
    with deadline(60):
        df = sweep.run(scene, {"scale": [2.0, 20.0], "hs": [1.0, 2.0, 3.0]},
                       workers=workers, out=out, stats=stats)
    assert stats["backend"] == ("in this process" if workers == 1 else
                                "on 2 forked workers")
    assert (stats["ran"], stats["failed"]) == (6, 4)
    by = {(r.scale, r.hs): r for r in df.itertuples()}
    for hs in (1.0, 2.0, 3.0):
        assert by[2.0, hs].status == "failed"
        assert by[2.0, hs].error_type == SeaWorkspaceError.__name__
        assert "fits from scale" in by[2.0, hs].error
    bug = by[20.0, 2.0]
    assert (bug.status, bug.error_type) == ("failed", "IndexError")
    assert bug.error.startswith("internal error, a bug: please report it")
    assert "IndexError: index " in bug.error and "out of bounds" in bug.error
    assert "(at offshore_crane/studies/sweep/cases.py:" in bug.error and "\n" not in bug.error
    assert np.isnan(bug.worst_util)
    ok = df[df["status"] == "ok"].reset_index(drop=True)
    assert list(zip(ok["scale"], ok["hs"])) == [(20.0, 1.0), (20.0, 3.0)]
    expected = _bits(clean.drop(columns="case"))
    got = _bits(ok.drop(columns="case")[clean.drop(columns="case").columns])
    for column in expected:
        if column != "case_id":
            np.testing.assert_array_equal(got[column], expected[column], err_msg=column)
    stored = sweep.read_results(out)
    assert len(stored) == 6 and (stored["status"] == "failed").sum() == 4


@pytest.mark.parametrize("error", [MemoryError, KeyboardInterrupt])
def test_the_process_own_failures_still_end_the_sweep(tmp_path, monkeypatch, error):
    """Out of memory and Ctrl-C are the process's, not a case's: they propagate (no
    row), the directory is released with the rows finished before, and a rerun
    completes the rest."""
    scene = scenes.load_scene(_scene(tmp_path))
    out = tmp_path / "res"
    _breaks_at(monkeypatch, 2.0, error)
    with deadline(60), pytest.raises(error):
        sweep.run(scene, {"hs": [1.0, 2.0, 3.0]}, out=out)
    monkeypatch.undo()
    stats: dict = {}
    with deadline(60):
        df = sweep.run(scene, {"hs": [1.0, 2.0, 3.0]}, out=out, stats=stats)
    assert stats["skipped"] == 1 and (df["status"] == "ok").all()


def test_which_errors_are_the_process_own():
    assert fatal(MemoryError()) and fatal(KeyboardInterrupt()) and fatal(SystemExit(1))
    assert fatal(OSError(errno.EMFILE, "Too many open files"))
    assert not fatal(IndexError("index 3 is out of bounds"))
    assert not fatal(ZeroDivisionError()) and not fatal(OSError(errno.ENOENT, "gone"))
    assert not fatal(OutputError("cannot write x", path="x"))


def test_the_cli_reports_an_internal_error_in_its_table(tmp_path, monkeypatch, capsys):
    """The command line: exit 0, the failure counted and its row in the verdict table
    saying it is an internal error (one line per case)."""
    _breaks_at(monkeypatch, 2.0, IndexError)
    with deadline(60):
        status = main(["sweep", "--scene", str(_scene(tmp_path)), "--grid",
                       str(_grid(tmp_path, "hs = [1.0, 2.0]\n")), "--no-progress"])
    out = capsys.readouterr().out
    assert status == 0 and ", 1 failed)" in out
    line = next(row for row in out.splitlines() if "IndexError" in row)
    assert "IndexError: internal error, a bug: please report it" in line
