"""Outputs that are not regular files (issue 36): a FIFO no process reads is refused
before anything is computed (``--out`` onto one blocked forever after computing); one
that is read is opened at the check and held, so the write never waits; a reader that
left is an OutputError; every command's outputs are checked so. Sockets and devices as
outputs are in the catalogue (tests/cli/cases_io.py).

Each test bounds its own time (``io.PIPE_TIMEOUT`` shortened, a SIGALRM deadline), so
that a regression fails instead of hanging.
"""

from __future__ import annotations

import gc
import os
import stat
import threading
import time
from pathlib import Path

import pytest

from offshore_crane import io, scenes
from offshore_crane.cli import main
from offshore_crane.errors import OutputError

from conftest import deadline

SCENES = Path(__file__).resolve().parents[1] / "scenes"


def _fifo(tmp_path: Path, name: str) -> Path:
    path = tmp_path / name
    os.mkfifo(path)
    return path


def test_a_fifo_nobody_reads_is_refused_before_computing(tmp_path, monkeypatch, capsys):
    """Library and command line: one line within io.PIPE_TIMEOUT, and ``id`` never
    reaches its computation (it blocked forever after computing)."""
    monkeypatch.setattr(io, "PIPE_TIMEOUT", 0.3)
    fifo = _fifo(tmp_path, "forces.csv")
    with deadline(10):
        with pytest.raises(OutputError, match=r"--out: cannot write .*forces\.csv: is a FIFO "
                           r"\(named pipe\) that no process read within 0\.3 s: start its "
                           r"reader first, or write to a regular file"):
            io.plan_outputs({"--out": fifo})

        def computed(*args, **kwargs):
            raise AssertionError("computed before the outputs were checked")

        monkeypatch.setattr(scenes, "load_robot", computed)
        t0 = time.perf_counter()
        assert main(["id", "--duration", "0.5", "--out", str(fifo)]) == 2
        assert time.perf_counter() - t0 < 3.0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "is a FIFO (named pipe) that no process read" in err
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


@pytest.mark.parametrize("argv", [
    ["id", "--duration", "0.5", "--out", "{}.csv"],
    ["id", "--duration", "0.5", "--plot", "{}.png"],
    ["size", "--duration", "0.5", "--out", "{}.csv"],
    ["simulate", "--duration", "0.1", "--out", "{}.csv"],
    ["simulate", "--duration", "0.1", "--plot", "{}.png"],
    ["motion", "--hs", "2", "--tp", "8", "--heading", "30", "--scale", "20", "--duration",
     "5", "--out", "{}.csv"],
    ["describe", "--out", "{}.yaml"],
    ["export", "--mjcf", "{}.xml"],
    ["show", "--out", "{}.png"],
    ["animate", "--duration", "1", "--out", "{}.gif"],
    ["excite", "--duration", "1", "--out", "{}.csv"],
    ["identify", "--log", "{}-absent.csv", "--out", "{}.toml"],
    ["compensate", "--scene", str(SCENES / "compensated_lift.toml"), "--plot", "{}.png"],
    ["sweep", "--scene", str(SCENES / "sweep_crane.toml"), "--grid", "{grid}", "--csv",
     "{}.csv"],
], ids=lambda argv: f"{argv[0]}{argv[-2]}")
def test_every_command_checks_its_outputs_for_a_reader(tmp_path, monkeypatch, capsys, argv):
    monkeypatch.setattr(io, "PIPE_TIMEOUT", 0.2)
    grid = tmp_path / "grid.toml"
    grid.write_text("hs = [1.0]\n")
    fifo = _fifo(tmp_path, "x" + Path(argv[-1]).suffix)
    argv = [a.format(str(tmp_path / "x"), grid=grid) for a in argv[:-1]] + [str(fifo)]
    with deadline(30):
        assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert f"{argv[-2]}: cannot write {fifo}: is a FIFO (named pipe) that no process " \
           "read within 0.2 s" in err, err


def test_a_fifo_whose_reader_comes_gets_the_output(tmp_path):
    """A reader that opens the FIFO a moment after the command started (``cat fifo &``):
    the check waits for it, holds the write end while computing, and the reader gets
    the whole CSV."""
    fifo = _fifo(tmp_path, "forces.csv")
    got: list = []

    def read():
        time.sleep(0.3)
        with open(fifo, "rb") as fh:
            got.append(fh.read())

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    with deadline(60):
        assert main(["id", "--duration", "0.5", "--out", str(fifo)]) == 0
    reader.join(10.0)
    lines = got[0].decode().splitlines()
    assert lines[0].startswith("t_s,") and len(lines) == 52       # 0.5 s at 100 Hz


def test_a_reader_that_left_is_an_output_error(tmp_path):
    """The reader was there at the check, gone at the write: an OutputError naming the
    FIFO (Python ignores SIGPIPE: the write fails with EPIPE), never a hang."""
    fifo = _fifo(tmp_path, "forces.csv")
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
    target = io.plan_outputs({"--out": fifo})["--out"]
    os.close(reader)
    with deadline(10), pytest.raises(OutputError, match=r"cannot write .*forces\.csv: "
                                                        r"Broken pipe"):
        io.write_text(target, "x" * 100_000)


def test_a_held_fifo_is_released_when_its_output_is_dropped(tmp_path):
    """Planned, then never written (the run failed): the held write end is closed when
    the plan is dropped, and the reader sees the end of the data instead of waiting."""
    fifo = _fifo(tmp_path, "forces.csv")
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
    try:
        planned = io.plan_outputs({"--out": fifo})
        with pytest.raises(BlockingIOError):
            os.read(reader, 10)                          # a writer holds it: no end yet
        del planned
        gc.collect()
        assert os.read(reader, 10) == b""                # no writer left: the end
    finally:
        os.close(reader)
