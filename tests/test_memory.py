"""Bounded memory (issue 21, item 4): a record's size is checked against a limit before it
is allocated, in one helper (``validation.check_memory``) that every path building a
sample record calls; beyond it, one line naming the flag that made it big."""

from __future__ import annotations

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.cli import main
from offshore_crane.errors import InputError
from offshore_crane.motion import sea, trajectories
from offshore_crane.outputs.visual.motion import Motion, frame_times
from offshore_crane.validation import MEMORY_SHARE, check_memory, memory_limit

LIMIT = 2e6           # bytes: far below every case here, far above the ordinary runs


@pytest.fixture
def small(monkeypatch):
    monkeypatch.setenv("OFFSHORE_CRANE_MEMORY_LIMIT", str(LIMIT))


def test_the_default_limit_is_a_share_of_the_available_memory(monkeypatch):
    monkeypatch.delenv("OFFSHORE_CRANE_MEMORY_LIMIT", raising=False)
    limit, how = memory_limit()
    with open("/proc/meminfo", encoding="ascii") as fh:
        total = next(float(l.split()[1]) * 1024 for l in fh if l.startswith("MemTotal:"))
    assert 0 < limit <= MEMORY_SHARE * total and how.endswith(" free")
    check_memory(1e6, "a small record", "nothing")                 # far below: passes


@pytest.mark.parametrize("value", ["lots", "nan", "-nan", "0", "0e5", "-1", "-2e9", "inf",
                                   "-inf", "1e400", " "])
def test_a_bad_limit_is_named(monkeypatch, value):
    """Not a finite number of bytes > 0: refused by name (``nan`` turned the guard off,
    every comparison with it being false; ``0`` and negatives refused every record)."""
    monkeypatch.setenv("OFFSHORE_CRANE_MEMORY_LIMIT", value)
    with pytest.raises(InputError, match=rf"OFFSHORE_CRANE_MEMORY_LIMIT = '{value}': give a "
                       r"number of bytes, finite and > 0 \(e\.g\. 8e9\), or unset it"):
        check_memory(1.0, "x", "y")


def test_a_bad_limit_is_one_line_on_the_command_line(monkeypatch, capsys, tmp_path):
    monkeypatch.setenv("OFFSHORE_CRANE_MEMORY_LIMIT", "nan")
    out = tmp_path / "x.csv"
    assert main(["id", "--duration", "5000", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "OFFSHORE_CRANE_MEMORY_LIMIT = 'nan'" in err
    assert not out.exists()


def test_a_small_positive_limit_is_a_limit(monkeypatch):
    monkeypatch.setenv("OFFSHORE_CRANE_MEMORY_LIMIT", "1e3")
    assert memory_limit() == (1e3, "OFFSHORE_CRANE_MEMORY_LIMIT")
    check_memory(1e3, "a record at the limit", "nothing")
    with pytest.raises(InputError, match=r"needs 1\.02 kB of memory, over the limit 1 kB"):
        check_memory(1024.0, "a record", "make it smaller")


@pytest.mark.parametrize("call, match", [
    (lambda: trajectories.time_grid(1000.0, 100.0),
     r"1000 s at 100 Hz \(100001 samples of t, q, qd, qdd\) needs 22\.4 MB of memory, over "
     r"the limit 2 MB \(OFFSHORE_CRANE_MEMORY_LIMIT\): shorten the duration"),
    (lambda: sea.sea_state(2.0, 8.0, 30.0, 3000.0, 10.0),
     r"a ship's motion of 3000 s at 10 Hz \(30001 samples\) needs .* shorten the duration"),
    (lambda: oc.simulate(oc.load_robot(), 10.0, trajectories.table1, step=1e-4),
     r"a simulation of 10 s at a step of 0\.0001 s \(100000 steps\) needs .* lengthen the "
     r"step \(--step\)"),
    (lambda: oc.dynamics.cable.inverse_dynamics(
        oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5}),
        *trajectories.table1(trajectories.time_grid(5.0, 100.0)),
        t=trajectories.time_grid(5.0, 100.0), substeps=200),
     r"the swing's stage grid \(501 samples × 200 substeps\) needs .* lower "
     r"substeps \(--substeps\)"),
    (lambda: frame_times(Motion("table1", np.linspace(0.0, 10.0, 11), np.zeros((11, 9))),
                         30.0, 1e-3),
     r"300001 frames of 10 s at --fps 30 and --speed 0\.001 needs .* raise --speed"),
])
def test_every_record_is_checked_before_it_is_built(small, call, match):
    with pytest.raises(InputError, match=match):
        call()


@pytest.mark.parametrize("argv, flag", [
    (["id", "--duration", "2000"], "shorten the duration or lower the rate"),
    (["simulate", "--duration", "5", "--step", "1e-5"], "(--step)"),
    (["motion", "--hs", "2", "--tp", "8", "--heading", "30", "--scale", "20", "--duration",
      "3000"], "shorten the duration"),
    (["id", "--duration", "5", "--set", "payload.mass=2", "--set", "payload.cable_length=0.5",
      "--substeps", "300"], "(--substeps)"),
    (["animate", "--speed", "1e-9"], "raise --speed"),                   # once 6.9 TiB
])
def test_the_cli_says_which_flag_in_one_line(small, capsys, tmp_path, argv, flag):
    out = tmp_path / ("x.gif" if argv[0] == "animate" else "x.csv")
    assert main([*argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "of memory, over the limit" in err and flag in err
    assert not out.exists()
