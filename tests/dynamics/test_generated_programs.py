"""The generated programs are checked (issue 36): a program of
:mod:`offshore_crane.dynamics.lanes` cut short, with a constant changed or a line deleted
was run as it was (a sweep's forces wrong, values near 1e228); now its checksum line
fails, it is generated again with one warning and the forces are those of the undamaged
program, bit for bit.

Every test damages a copy of the package's programs in its own folder (with their
compiled code, so that nothing compiles): never the files the other tests load.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import kernel_cache
from offshore_crane.conventions import LANES
from offshore_crane.dynamics import lanes, program_files, solve
from offshore_crane.dynamics.constants import cable_arrays, robot_arrays
from offshore_crane.kernel_cache import GeneratedProgramWarning
from offshore_crane.robot.kinematics.formulas import LEG_MODEL_CODES
from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.validation import as_gravity
from problems import random_states

FULL = LEG_MODEL_CODES["full"]


def _truncated(text: str) -> str:
    """Cut at the end of a line two thirds in: still a program (the block's last inputs
    ungathered, the epilogue gone), so that only the checksum tells."""
    return text[:text.index("\n", 2 * len(text) // 3) + 1]


def _constant(text: str) -> str:
    """An input gathered from another column, the length kept (same size)."""
    assert "ib[5 * L + k] = q[s + k, 5]" in text
    return text.replace("ib[5 * L + k] = q[s + k, 5]", "ib[5 * L + k] = q[s + k, 4]", 1)


def _deleted(text: str) -> str:
    """One input's line deleted: its row would stay whatever memory held."""
    lines = text.splitlines(keepends=True)
    k = next(i for i, line in enumerate(lines) if line.lstrip().startswith("ib[5 * L"))
    return "".join(lines[:k] + lines[k + 1:])


DAMAGES = {"truncated": (_truncated, "has no checksum line"),
           "a changed constant": (_constant, "does not match its checksum"),
           "a deleted line": (_deleted, "does not match its checksum")}


@pytest.fixture
def copied(tmp_path, monkeypatch):
    """``copy(arrays, cable)``: the package's program of that structure (loaded or written
    there first) copied into ``tmp_path/lanes``, which the kernels are then read from,
    and its compiled code where the copy's cache looks: the copy's path."""
    folder = tmp_path / "lanes"
    folder.mkdir()

    def copy(arrays, cable=False):
        original = lanes.kane_kernel(arrays, FULL, cable)
        name = real_name(arrays, cable)
        shutil.copy2(lanes.cache_folder() / name, folder / name)
        monkeypatch.setattr(lanes, "cache_folder", lambda: folder)
        _fresh(monkeypatch)
        _copy_compiled(original, lanes.kane_kernel(arrays, FULL, cable))
        return folder / name

    return copy


def _copy_compiled(original, kernel) -> None:
    """Put the compiled entries of ``original``'s program where ``kernel``'s cache looks
    (the same text: they load; nothing compiles)."""
    assert original is not None and kernel is not None
    source, target = original._cache._cache_file, kernel._cache._cache_file
    os.makedirs(target._cache_path, exist_ok=True)
    for f in kernel_cache.entry_files(source):
        shutil.copy2(f, os.path.join(target._cache_path, os.path.basename(f)))


def _fresh(monkeypatch):
    """Forget the kernels loaded: the next call reads its program again, as a new
    process does."""
    monkeypatch.setattr(lanes, "_KERNELS", {})
    monkeypatch.setattr(lanes, "_BY_ARRAYS", {})


def _caught(run):
    """``(run()'s result, the warnings it gave)``."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = run()
    return out, caught


def _check_damages(path: Path, monkeypatch, run, before, damages=DAMAGES):
    """Damage ``path`` each way in turn: each time ``run()`` gives ``before`` bit for bit
    with one warning naming the program and the damage, and the program is rewritten
    as it was, without compiling anything (its compiled code is the checked text's)."""
    written = path.read_bytes()
    compiled = kernel_cache.COMPILED[0]
    for what, (damage, problem) in damages.items():
        damaged = damage(written.decode())
        assert damaged.encode() != written
        compile(damaged, str(path), "exec")          # still Python: only the check tells
        path.write_text(damaged)
        _fresh(monkeypatch)
        after, caught = _caught(run)
        for a, b in zip(after, before):
            np.testing.assert_array_equal(a, b, err_msg=what)
        assert [w.category for w in caught] == [GeneratedProgramWarning], what
        message = str(caught[0].message)
        assert "\n" not in message and message.startswith(f"generated program {path} ")
        assert problem in message and "generated again from the formulas" in message
        assert path.read_bytes() == written, what
    assert kernel_cache.COMPILED[0] == compiled
    assert [p.name for p in path.parent.iterdir() if p.name != "__pycache__"] == [path.name]


def test_a_damaged_program_is_generated_again_with_the_same_forces(copied, monkeypatch):
    """The robot's block kernel, through ``solve`` (3 blocks and a partial one): the
    forces before any damage, then after each damage, bit for bit; and after another
    structure's program (massless legs, its checksum line intact) copied over it."""
    robot = oc.load_robot()
    arrays = robot_arrays(robot)
    q, qd, qdd = random_states(robot, 3 * LANES + 5, seed=36)
    massless = LEG_MODEL_CODES["massless"]
    assert lanes.kane_kernel(arrays, massless) is not None
    other = (lanes.cache_folder() / real_name(arrays, leg_model=massless)).read_text()
    path = copied(arrays)

    def run():
        return (solve(robot, q, qd, qdd).X,)

    before, caught = _caught(run)
    assert caught == [] and np.isfinite(before[0]).all()
    assert list(lanes._KERNELS.values())[0] is not None          # the block kernel ran
    _check_damages(path, monkeypatch, run, before)
    _check_damages(path, monkeypatch, run, before, {
        "another program": (lambda text: other, "does not match its checksum")})


def test_the_hanging_loads_program_is_checked_too(copied, monkeypatch):
    """The hanging load's block kernel (X and the cable's pull, tension and residual F),
    damaged the three ways, gives its undamaged numbers with one warning each time."""
    robot = oc.load_robot(overrides={"payload.cable_length": 1.2, "payload.mass": 3.0})
    arrays = cable_arrays(robot)
    rng = np.random.default_rng(37)
    states = random_states(robot, 2 * LANES + 3, seed=38)
    q, qd, qdd = (np.column_stack([x, rng.uniform(-s, s, (len(x), 2))])
                  for x, s in zip(states, (0.5, 1.0, 3.0)))
    g, damp = as_gravity((0.0, 0.0, -9.81)), np.array([0.05, 0.07])
    path = copied(arrays, cable=True)

    def run():
        n = len(q)
        X, F, kappa = np.empty((n, 9)), np.empty((n, 6)), np.empty((3, n))
        lanes.kane_kernel(arrays, FULL, cable=True)(
            arrays.flat, arrays.layout, arrays.prismatic, damp, q, qd, qdd, g, True, True,
            10.0, 50.0, 0, n, X, kappa, ws.new_health(), F)
        return X, F, kappa

    before, caught = _caught(run)
    assert caught == [] and all(np.isfinite(x).all() for x in before)
    _check_damages(path, monkeypatch, run, before)


def test_a_read_only_package_checks_the_programs_in_the_users_cache(tmp_path, monkeypatch):
    """A package folder that cannot be written puts the programs in the user's cache
    folder: one written there is checked the same way (the package's compiled code for
    it copied there, so that nothing compiles)."""
    robot = oc.load_robot()
    arrays = robot_arrays(robot)
    original, real = lanes.kane_kernel(arrays, FULL), lanes.cache_folder()
    access = os.access
    monkeypatch.setattr(program_files.os, "access", lambda p, mode: False if Path(p) == real
                        else access(p, mode))
    monkeypatch.setattr(lanes.Path, "home", classmethod(lambda cls: tmp_path))
    folder = lanes.cache_folder()
    assert folder == tmp_path / ".cache" / "offshore_crane" / "lanes"
    _fresh(monkeypatch)
    kernel, caught = _caught(lambda: lanes.kane_kernel(arrays, FULL))    # written there
    assert caught == [] and [p.name for p in folder.glob("*.py")] == [real_name(arrays)]
    _copy_compiled(original, kernel)
    q, qd, qdd = random_states(robot, LANES + 3, seed=39)

    def run():
        return (solve(robot, q, qd, qdd).X,)

    before, caught = _caught(run)
    assert caught == [] and np.isfinite(before[0]).all()
    _check_damages(folder / real_name(arrays), monkeypatch, run, before)


def real_name(arrays, cable=False, leg_model=FULL) -> str:
    """The file name of the program of ``arrays``' structure."""
    return (f"kane_lanes_{lanes._sources_hash()[:8]}_"
            f"{lanes._structure_key(arrays, leg_model, cable)}.py")


def _full_disk(replace, src, dst):
    raise OSError(28, "No space left on device")


def _short_write(replace, src, dst):
    """The rename done, the file then shorter than written (a filesystem losing data)."""
    replace(src, dst)
    Path(dst).write_bytes(Path(dst).read_bytes()[:1000])


@pytest.mark.parametrize("failure, problem, left", [
    (_full_disk, r"cannot be written \(No space left on device\)", 0),
    (_short_write, "does not read back as written", 1)], ids=["full disk", "short write"])
def test_a_program_that_cannot_be_written_leaves_the_per_sample_kernel(
        tmp_path, monkeypatch, failure, problem, left):
    """A full disk, or a program that does not read back as written: one line naming the
    program and the problem, no temporary file left, and the per-sample kernel's forces
    (the same numbers)."""
    robot = oc.load_robot()
    q, qd, qdd = random_states(robot, LANES + 1, seed=40)
    expected = solve(robot, q, qd, qdd).X
    monkeypatch.setattr(lanes, "cache_folder", lambda: tmp_path)
    _fresh(monkeypatch)
    replace = os.replace
    monkeypatch.setattr(program_files.os, "replace", lambda src, dst: failure(replace, src, dst)
                        if Path(dst).parent == tmp_path else replace(src, dst))
    X, caught = _caught(lambda: solve(robot, q, qd, qdd).X)
    np.testing.assert_array_equal(X, expected)
    assert [w.category for w in caught] == [GeneratedProgramWarning]
    assert re.fullmatch(rf"generated program {tmp_path}/kane_lanes_\w+\.py {problem}: the "
                        r"per-sample kernel runs instead \(the same numbers, slower\)",
                        str(caught[0].message))
    assert list(lanes._KERNELS.values()) == [None] and len(list(tmp_path.iterdir())) == left


def test_compiled_code_is_keyed_by_the_programs_checksum(tmp_path):
    """Numba keys a compiled entry by the function's byte code and its file's content,
    which a constant changed in the text run (not in the file) leaves as they were: its
    cache then gives the first text's code. The checksum in the key gives each text its
    own, and the code of a text seen before loads without compiling."""
    path = tmp_path / "prog.py"
    text = ("from offshore_crane.kernel_cache import njit\n\n\n"
            "@njit(cache=True)\ndef kernel(x):\n    return x * {}\n")
    path.write_text(text.format("2.0"))
    results, compiled = [], []
    for constant, digest in (("2.0", None), ("3.0", None), ("2.0", "a" * 64),
                             ("3.0", "b" * 64), ("2.0", "a" * 64)):
        space = {} if digest is None else {kernel_cache.PROGRAM_DIGEST: digest}
        exec(compile(text.format(constant), str(path), "exec"), space)
        count = kernel_cache.COMPILED[0]
        results.append(space["kernel"](1.5))
        compiled.append(kernel_cache.COMPILED[0] - count)
    assert results == [3.0, 3.0, 3.0, 4.5, 3.0]      # Numba's own key: 3.0 for "3.0"
    assert compiled == [1, 0, 1, 1, 0]


RACE = '''
import sys, time, warnings
warnings.simplefilter("always")
from pathlib import Path
import numpy as np
import offshore_crane as oc
from offshore_crane.dynamics import lanes, program_files, solve
sys.path.insert(0, sys.argv[3])
from problems import random_states
lanes.cache_folder = lambda: Path(sys.argv[1])
robot = oc.load_robot()
q, qd, qdd = random_states(robot, 20, seed=41)
while time.time() < float(sys.argv[2]):
    time.sleep(0.001)
np.save(sys.stdout.buffer, solve(robot, q, qd, qdd).X)
'''


def test_processes_finding_one_damaged_program_at_once(copied, tmp_path, monkeypatch):
    """Three processes load one damaged program at the same moment: each warns at most
    once and gives the undamaged forces bit for bit; the folder ends with the program
    as written and no temporary file."""
    import io
    import time

    robot = oc.load_robot()
    q, qd, qdd = random_states(robot, 20, seed=41)
    path = copied(robot_arrays(robot))
    written = path.read_bytes()
    expected = solve(robot, q, qd, qdd).X
    path.write_text(_truncated(written.decode()))
    tests = Path(__file__).resolve().parents[1]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(Path(oc.__file__).resolve().parents[1]), os.environ.get("PYTHONPATH", "")])}
    start = time.time() + 4.0                           # after the three have imported
    procs = [subprocess.Popen([sys.executable, "-c", RACE, str(path.parent), str(start),
                               str(tests)], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE) for _ in range(3)]
    outs = [p.communicate(timeout=300) for p in procs]
    warned = []
    for p, (out, err) in zip(procs, outs):
        assert p.returncode == 0, err.decode()
        np.testing.assert_array_equal(np.load(io.BytesIO(out)), expected)
        warned.append(err.decode().count("GeneratedProgramWarning"))
        assert "Traceback" not in err.decode() and "KernelCacheWarning" not in err.decode()
    assert max(warned) == 1, warned               # each at most once; the first did
    assert path.read_bytes() == written
    assert sorted(p.name for p in path.parent.iterdir()) == ["__pycache__", path.name]
