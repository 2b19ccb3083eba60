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
from offshore_crane.studies.sweep.scheduler import MAX_HANDSHAKE, handshake, scheduler_address

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


# --------------------------------------------------------------------------- the store
def _refuse_lock_writes(monkeypatch) -> None:
    """Opening the results directory's lock file for writing fails as in a read-only
    directory owned by someone else (root, running the tests, is refused nothing)."""
    real = os.open

    def opener(path, flags, *args, **kwargs):
        if os.path.basename(os.fspath(path)) == "_lock" and flags & (os.O_WRONLY | os.O_RDWR):
            raise PermissionError(errno.EACCES, "Permission denied", os.fspath(path))
        return real(path, flags, *args, **kwargs)

    monkeypatch.setattr(os, "open", opener)


def test_a_read_only_results_directory_is_one_line(tmp_path, monkeypatch, capsys):
    """A results directory its lock cannot be written in (a PermissionError traceback
    from filelock): one line naming the directory and what to do, exit 2, the directory
    unchanged."""
    scene, grid = _scene(tmp_path), _grid(tmp_path, "hs = [1.0, 2.0]\n")
    out = tmp_path / "res"
    assert main(["sweep", "--scene", str(scene), "--grid", str(grid), "--out", str(out),
                 "--no-progress"]) == 0
    capsys.readouterr()
    listing = {p.name: p.stat().st_mtime_ns for p in out.iterdir()}
    _refuse_lock_writes(monkeypatch)
    assert main(["sweep", "--scene", str(scene), "--grid", str(grid), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert f"--out {out}: is not writable" in err and "give another --out" in err
    assert "(Permission denied)" in err
    assert {p.name: p.stat().st_mtime_ns for p in out.iterdir()} == listing
    with pytest.raises(ResultsDirectoryError, match="is not writable"):
        sweep.run(scenes.load_scene(scene), {"hs": [1.0]}, out=tmp_path / "new")
    assert not (tmp_path / "new").exists()             # the directory it made, removed


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes in a read-only directory")
def test_a_read_only_results_directory_for_real(tmp_path, capsys):
    scene, grid = _scene(tmp_path), _grid(tmp_path, "hs = [1.0]\n")
    out = tmp_path / "res"
    assert main(["sweep", "--scene", str(scene), "--grid", str(grid), "--out", str(out),
                 "--no-progress"]) == 0
    capsys.readouterr()
    out.chmod(0o555)
    try:
        assert main(["sweep", "--scene", str(scene), "--grid", str(grid), "--out",
                     str(out)]) == 2
    finally:
        out.chmod(0o755)
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "is not writable" in err, err


# --------------------------------------------------------------------------- the scheduler
@contextlib.contextmanager
def peer(*chunks: bytes, pause: float = 0.0):
    """A local TCP server that sends ``chunks`` (``pause`` s apart) to each connection
    and then keeps it open; yields its address."""
    server = socket.create_server(("127.0.0.1", 0))
    server.settimeout(0.1)
    stop = threading.Event()

    def serve():
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except OSError:
                continue
            with conn:
                try:
                    for chunk in chunks:
                        conn.sendall(chunk)
                        stop.wait(pause)
                except OSError:
                    pass
                stop.wait(10.0)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{server.getsockname()[1]}"
    finally:
        stop.set()
        thread.join(5.0)
        server.close()


def _dask_like(info: dict) -> bytes:
    """``info`` framed as Dask writes a message: total length, frame count, frame
    lengths, then the msgpack frame."""
    import msgpack

    frame = msgpack.packb(info)
    body = struct.pack("QQ", 1, len(frame)) + frame
    return struct.pack("Q", len(body)) + body


HANDSHAKE = {"compression": None, "python": (3, 11, 7), "pickle-protocol": 5}


@pytest.mark.parametrize("chunks, match", [
    ((b"\xff" * 8,), r"announces 18446744073709551615 bytes; a Dask handshake has at most"),
    ((b"SSH-2.0-OpenSSH_9.6\r\n",), r"announces \d{19} bytes"),
    ((struct.pack("Q", MAX_HANDSHAKE + 1),), rf"announces {MAX_HANDSHAKE + 1} bytes"),
    ((struct.pack("QQ", 16, 0) + bytes(8),), "announces 0 frames"),
    ((struct.pack("QQQ", 24, 1, 10 ** 12) + bytes(8),), "frames do not add up"),
    ((struct.pack("QQQ", 19, 1, 3) + b"abc",), "is not a Dask handshake"),
    ((_dask_like({"op": "hello"}),), "is not a Dask handshake"),
    ((b"\x00" * 3,), r"connection closed|an incomplete message"),
])
def test_a_peer_that_is_not_dask_is_refused_on_what_it_sends(chunks, match):
    """Whatever the peer sends at once, every length is checked before anything is read
    into memory: one SchedulerError, at once."""
    with peer(*chunks) as address, deadline(10):
        t0 = time.perf_counter()
        with pytest.raises(SchedulerError, match=match) as info:
            handshake(address, timeout=1.0)
        took = time.perf_counter() - t0
    assert "\n" not in str(info.value) and "is it a Dask scheduler?" in str(info.value)
    assert took < 1.5


def test_a_trickling_peer_is_bounded_by_one_deadline():
    """A peer announcing a plausible length and sending a byte every 0.1 s: the whole
    handshake, not each read, has the timeout."""
    with peer(struct.pack("Q", 200), *[b"x"] * 100, pause=0.1) as address, deadline(10):
        t0 = time.perf_counter()
        with pytest.raises(SchedulerError, match=r"within 0\.5 s \(an incomplete message\)"):
            handshake(address, timeout=0.5)
        assert time.perf_counter() - t0 < 1.0


def test_a_dask_handshake_passes():
    with peer(_dask_like(HANDSHAKE)) as address, deadline(10):
        handshake(address, timeout=1.0)


def test_a_real_scheduler_passes_the_handshake():
    """The check reads a real Dask scheduler's handshake (this distributed's)."""
    distributed = pytest.importorskip("distributed")
    import asyncio

    async def run():
        async with distributed.Scheduler(host="127.0.0.1", port=0,
                                         dashboard_address=None) as scheduler:
            await asyncio.get_running_loop().run_in_executor(None, handshake,
                                                             scheduler.address, 3.0)

    with deadline(30):
        asyncio.run(run())


def test_the_sweep_never_hands_such_a_peer_to_dask(tmp_path, monkeypatch, capsys):
    """``sweep --scheduler`` at a peer that sends a huge length at once (Dask's client
    then tried to allocate it): one line, exit 2, nothing written, Dask's client never
    made."""
    import distributed

    def client(*args, **kwargs):
        raise AssertionError("Dask's client was given a peer that is not Dask")

    monkeypatch.setattr(distributed, "Client", client)
    out = tmp_path / "res"
    with peer(b"\xfe" * 64) as address, deadline(20):
        t0 = time.perf_counter()
        status = main(["sweep", "--scene", str(_scene(tmp_path)), "--grid",
                       str(_grid(tmp_path, "hs = [1.0]\n")), "--out", str(out),
                       "--scheduler", address])
        took = time.perf_counter() - t0
    err = capsys.readouterr().err
    assert status == 2 and err.count("\n") == 1, err
    assert "announces 18374403900871474942 bytes" in err and not out.exists()
    assert took < 5.0


# --------------------------------------------------------------------------- addresses
@pytest.mark.parametrize("address, match", [
    ("tcp://[::1", r"'\[' opens an IPv6 address that no '\]' closes"),
    ("tcp://[2001:db8::7:8786", r"'\[' opens an IPv6 address that no '\]' closes"),
    ("tcp://2001:db8::7]:8786", r"'\]' without '\['"),
    ("tcp://2001:db8::7:8786", r"an IPv6 address goes in brackets"),
    ("tcp://[localhost]:8786", r"\[localhost\] is not an IPv6 address"),
    ("tcp://[10.0.0.1]:8786", r"\[10\.0\.0\.1\] is not an IPv6 address"),
    ("tcp://[::1]8786", r"the port must follow '\]' as :PORT"),
    ("tcp://[::1]", r"the port must be 1\.\.65535 \(none given\)"),
    ("tcp://node7:", r"the port must be 1\.\.65535 \(none given\)"),
    ("tcp://node7:0x22", r"the port must be 1\.\.65535"),
    ("tcp://node7:8786:1", r"one ':' only"),
    ("tcp://node7:65536", r"the port must be 1\.\.65535"),
    ("tcp://node7:१२३", r"'१' \(character 13\) has no place in an address \(an "),
    ("tcp://node 7:8786", r"' ' \(character 11\) has no place in an address"),
    ("tcp://node7\t:8786", r"'\\t' \(character 12\)"),
    ("tcp://admin@node7:8786", "no user name"),
    ("tcp://node7:8786/status", "nothing may follow the port"),
    ("tcp://node7:8786#x", "nothing may follow the port"),
    ("tcp://node..lan:8786", r"'node\.\.lan' is not a host name"),
    ("tcp://-node:8786", r"'-node' is not a host name"),
    ("tcp://" + "n" * 64 + ":8786", r"is not a host name"),
    ("tls://node7:8786", "the scheme must be tcp"),
    ("node7:8786", r"--scheduler 'node7:8786': give 'local'"),
])
def test_every_malformed_address_is_one_line(address, match):
    with pytest.raises(InputError, match=match) as info:
        scheduler_address(address)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("address, expected", [
    ("tcp://[::1]:8786", ("::1", 8786)),
    ("tcp://[fe80::1%eth0]:1", ("fe80::1%eth0", 1)),
    ("tcp://node-7.lab.example.:65535", ("node-7.lab.example.", 65535)),
    ("tcp://10.0.0.1:08786", ("10.0.0.1", 8786)),
])
def test_well_formed_addresses(address, expected):
    assert scheduler_address(address) == expected


def test_random_addresses_are_an_address_or_one_line():
    """3000 seeded random strings of the characters that make addresses odd: each is
    ``(host, port)`` or an InputError of one line, never another exception."""
    rng = random.Random(36)
    alphabet = "[]:@/?#%.-_0123456789abcdefnode \t\n\x00é١"
    for _ in range(3000):
        text = "tcp://" + "".join(rng.choice(alphabet) for _ in range(rng.randint(0, 14)))
        try:
            host, port = scheduler_address(text)
        except InputError as exc:
            assert "\n" not in str(exc), text
        else:
            assert host and 0 < port < 65536, text
