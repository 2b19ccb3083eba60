"""The fused Kane pass on blocks of samples (offshore_crane.dynamics.lanes): the traced
text vectorised across samples gives the per-sample kernel's numbers bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.conventions import LANES
from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics import lanes, program_files, solve
from offshore_crane.dynamics.constants import robot_arrays
from offshore_crane.dynamics.tracing import Symbol, TraceError
from offshore_crane.errors import WorkspaceError
from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.robot.kinematics.formulas import LEG_MODEL_CODES
from offshore_crane.validation import as_gravity
from problems import random_states


def _both(robot, q, qd, qdd, leg_model, want_cond=True, want_limits=True):
    """(X, κ, health) of the block kernel and of the per-sample kernel, same inputs (κ
    starts NaN: a sample with a non-finite input is skipped, its κ not written)."""
    arrays = robot_arrays(robot)
    g = as_gravity((0.0, 0.0, -9.81))
    out = []
    for block in (True, False):
        n = len(q)
        X, kappa, health = np.empty((n, 9)), np.full((3, n), np.nan), ws.new_health()
        if block:
            kernel = lanes.kane_kernel(arrays, LEG_MODEL_CODES[leg_model])
            kernel(arrays.flat, arrays.layout, arrays.prismatic, q, qd, qdd, g, want_cond,
                   want_limits, 10.0, 50.0, 0, n, X, kappa, health)
        else:
            c.kane(arrays.flat, arrays.layout, arrays.prismatic, q, qd, qdd, g, False,
                   LEG_MODEL_CODES[leg_model], True, want_cond, want_limits, 10.0, 50.0, 0,
                   n, X, kappa, health)
        out.append((X, kappa, health))
    return out


@pytest.mark.parametrize("leg_model", ["full", "thin-rod", "massless"])
def test_block_kernel_is_the_per_sample_kernel_bit_for_bit(leg_model):
    """Seeded random states, a count that leaves a partial last block (1000 + 7), a sample
    with a NaN input, one outside the workspace and one at the attitude singularity's
    edge: X, the condition numbers and the health record (first violations, worst κ with
    their samples) are equal bit for bit - the traced program does the per-sample
    formulas' operations in their order, and the epilogue is the same code."""
    robot = oc.load_robot()
    q, qd, qdd = random_states(robot, 1007, seed=25)
    q[13, 4] = 1.5                                    # |cos q5| small: κ_attitude large
    q[500, 2] = 0.9                                   # legs beyond their stroke
    qd[777, 3] = np.nan                               # a non-finite input
    (Xb, kb, hb), (Xs, ks, hs) = _both(robot, q, qd, qdd, leg_model)
    np.testing.assert_array_equal(Xb, Xs)
    np.testing.assert_array_equal(kb, ks)
    np.testing.assert_array_equal(hb, hs)
    assert np.isnan(Xb[777]).all() and not ws.is_clean(hb)
    assert np.isfinite(Xb[:777]).all()


def test_solve_takes_the_blocks_from_lanes_samples_with_the_same_result():
    """The public path: LANES samples and more go through the block kernel, fewer one at a
    time; the same forces either way (each sample alone through ``solve``), in one thread
    or two, and the same error naming the same sample."""
    robot = oc.load_robot()
    q, qd, qdd = random_states(robot, 3 * LANES + 5, seed=3)
    X = solve(robot, q, qd, qdd).X
    one = np.array([solve(robot, q[k], qd[k], qdd[k]).X[0] for k in range(len(q))])
    np.testing.assert_array_equal(X, one)
    np.testing.assert_array_equal(X, solve(robot, q, qd, qdd, threads=2).X)
    q[40, 2] = 0.9
    messages = []
    for rows in (slice(None), slice(40, 41)):
        with pytest.raises(WorkspaceError, match="sample") as info:
            solve(robot, q[rows], qd[rows], qdd[rows])
        messages.append(str(info.value).replace("sample 0", "sample 40"))
    assert "sample 40" in messages[0] and messages[0] == messages[1]


def test_a_branch_on_a_value_stops_the_trace():
    """The straight-line program cannot branch on a value: a comparison of traced
    numbers raises TraceError (the caller keeps the per-sample kernel)."""
    x = Symbol("q0")
    with pytest.raises(TraceError, match="a branch on a value cannot be traced"):
        bool(x > 0.0)
    with pytest.raises(TraceError, match="cannot trace an operation with str"):
        x + "a"


def test_the_generated_module_reads_constants_from_the_description():
    """The program copies no value of the robot: its constants are the description's
    array read by index, so a heavier payload (another URDF, same structure) reuses the
    same module and gives its own forces."""
    heavy = oc.load_robot(overrides={"payload.mass": 7.5})
    light = oc.load_robot()
    a, b = robot_arrays(heavy), robot_arrays(light)
    assert lanes._structure_key(a, 0) == lanes._structure_key(b, 0)
    text = lanes.source(b, 0) + lanes.program(b, 0, "")[1]
    assert "7.5" not in text and "%c_0.p = getelementptr double, ptr %flat, i64 0" in text
    q, qd, qdd = random_states(light, LANES, seed=9)
    assert not np.array_equal(solve(heavy, q, qd, qdd).X, solve(light, q, qd, qdd).X)
    (Xb, _, _), (Xs, _, _) = _both(heavy, q, qd, qdd, "full")
    np.testing.assert_array_equal(Xb, Xs)


def test_the_hanging_loads_block_kernel_is_its_per_sample_kernel_bit_for_bit():
    """The swing's Kane pass (the arm continued by the two sway joints, the cable's pull,
    tension and residual into F) on blocks: X, F, κ and the health record equal the
    per-sample kernel's bit for bit, on seeded random states with swinging sway angles,
    a NaN input and a partial last block."""
    from offshore_crane.dynamics.cable import kernels as ck
    from offshore_crane.dynamics.constants import cable_arrays

    robot = oc.load_robot(overrides={"payload.cable_length": 1.2, "payload.mass": 3.0})
    arrays = cable_arrays(robot)
    rng = np.random.default_rng(11)
    q9, qd9, qdd9 = random_states(robot, 3 * LANES + 3, seed=12)
    q, qd, qdd = (np.column_stack([x, rng.uniform(-s, s, (len(x), 2))])
                  for x, s in ((q9, 0.6), (qd9, 1.0), (qdd9, 3.0)))
    qdd[7, 2] = np.nan
    g = as_gravity((0.0, 0.0, -9.81))
    damp = np.array([0.05, 0.07])
    out = []
    for kernel in (lanes.kane_kernel(arrays, LEG_MODEL_CODES["full"], cable=True), ck.kane):
        n = len(q)
        X, F = np.empty((n, 9)), np.full((n, 6), np.nan)       # F: not written at a NaN
        kappa, health = np.full((3, n), np.nan), ws.new_health()
        kernel(arrays.flat, arrays.layout, arrays.prismatic, damp, q, qd, qdd, g, True,
               True, 10.0, 50.0, 0, n, X, kappa, health, F)
        out.append((X, F, kappa, health))
    for a, b in zip(*out):
        np.testing.assert_array_equal(a, b)
    assert np.isnan(out[0][0][7]).all() and np.isfinite(out[0][1][8:]).all()


def test_an_untraceable_text_keeps_the_per_sample_kernel(tmp_path, monkeypatch):
    """When the formulas cannot be traced (a branch on a value: TraceError), no module is
    written and the callers keep the per-sample kernel: the same forces, through solve
    and through the swing's Kane pass."""
    from offshore_crane.dynamics import tracing

    def refuse(*args, **kwargs):
        raise tracing.TraceError("a branch on a value cannot be traced")

    monkeypatch.setattr(tracing, "trace_kane", refuse)
    monkeypatch.setattr(lanes, "cache_folder", lambda: tmp_path)
    monkeypatch.setattr(lanes, "_KERNELS", {})
    monkeypatch.setattr(lanes, "_BY_ARRAYS", {})
    monkeypatch.setattr(lanes, "_SOURCES", ["another text"])     # another key: no file
    robot = oc.load_robot()
    assert lanes.kane_kernel(robot_arrays(robot), LEG_MODEL_CODES["full"]) is None
    assert list(tmp_path.iterdir()) == []
    q, qd, qdd = random_states(robot, LANES + 1, seed=4)
    X = solve(robot, q, qd, qdd).X
    one = np.array([solve(robot, q[k], qd[k], qdd[k]).X[0] for k in range(len(q))])
    np.testing.assert_array_equal(X, one)


def test_a_read_only_package_keeps_the_programs_in_the_users_cache(tmp_path, monkeypatch):
    """The generated modules go beside the package's own Numba cache when it can be
    written, else into the user's cache folder (an installation owned by another user)."""
    monkeypatch.setattr(program_files.os, "access", lambda path, mode: False)
    monkeypatch.setattr(lanes.Path, "home", classmethod(lambda cls: tmp_path))
    assert lanes.cache_folder() == tmp_path / ".cache" / "offshore_crane" / "lanes"


def test_literals_are_written_as_python_reads_them():
    """A literal of the text is written so that the program reads the same double back
    (repr), non-finite ones as NumPy's names."""
    from offshore_crane.dynamics.tracing import _operand

    values = (1.5, -0.0, 1e-300, 0.1, float("inf"), -float("inf"))
    written = [_operand(v) for v in values]
    assert written[4:] == ["np.inf", "-np.inf"] and _operand(float("nan")) == "np.nan"
    assert [float(eval(w, {"np": np})) for w in written] == list(values)
    assert str(float(eval(written[1]))) == "-0.0"


def test_a_robot_without_arm_takes_its_own_block_kernel_bit_for_bit():
    """The structure decides the program: the platform alone (no arm joint: its rows,
    the arm pass and the arm's outputs vanish from the trace) gets a kernel of its own,
    equal to the per-sample kernel bit for bit."""
    robot = oc.load_robot(with_arm=0)
    q, qd, qdd = random_states(robot, 2 * LANES + 3, seed=31)
    (Xb, kb, hb), (Xs, ks, hs) = _both(robot, q, qd, qdd, "full")
    for a, b in ((Xb, Xs), (kb, ks), (hb, hs)):
        np.testing.assert_array_equal(a, b)
    assert np.isnan(Xb[:, :3]).all() and np.isfinite(Xb[:, 3:]).all()


def test_a_new_version_of_the_text_removes_the_programs_of_the_old(tmp_path, monkeypatch):
    """Writing a program removes the programs of other versions of the text (their
    compiled code, and a killed writer's temporary file) but keeps the other structures
    of its own version."""
    monkeypatch.setattr(lanes, "cache_folder", lambda: tmp_path)
    monkeypatch.setattr(lanes, "_KERNELS", {})
    monkeypatch.setattr(lanes, "_BY_ARRAYS", {})
    version = lanes._sources_hash()[:8]
    (tmp_path / "__pycache__").mkdir()
    old = tmp_path / "kane_lanes_00000000_abc.py"
    kept = tmp_path / f"kane_lanes_{version}_other.py"
    compiled = tmp_path / "__pycache__" / "kane_lanes_00000000_abc.kane-13.py311.nbi"
    left = tmp_path / ".kane_lanes_00000000_abc.123.0a1b2c3d.tmp"   # a killed writer's
    for p in (old, kept, compiled, left):
        p.write_text("# a program\\n")
    robot = oc.load_robot()
    assert lanes.kane_kernel(robot_arrays(robot), LEG_MODEL_CODES["massless"]) is not None
    names = sorted(p.name for p in tmp_path.glob("*.py"))
    assert not old.exists() and not compiled.exists() and kept.exists()
    assert not left.exists()
    assert len(names) == 2 and all(n.startswith(f"kane_lanes_{version}_") for n in names)


def test_a_block_slot_held_by_another_structure_keeps_the_per_sample_kernel(monkeypatch):
    """Two structures whose keys fall on one block slot in a process (1 in 1024): the
    second gets no block kernel (its driver would call the first's program) and its
    callers keep the per-sample kernel, the same forces."""
    from offshore_crane.dynamics import native

    robot = oc.load_robot()
    arrays = robot_arrays(robot)
    key = lanes._structure_key(arrays, LEG_MODEL_CODES["thin-rod"])
    index = native.block_index(key)
    monkeypatch.setattr(lanes, "_KERNELS", {})
    monkeypatch.setattr(lanes, "_BY_ARRAYS", {})
    monkeypatch.setattr(native, "_BLOCK_KEYS", {**native._BLOCK_KEYS, index: "another"})
    assert lanes.kane_kernel(arrays, LEG_MODEL_CODES["thin-rod"]) is None
    q, qd, qdd = random_states(robot, LANES + 1, seed=5)
    X = solve(robot, q, qd, qdd, leg_model="thin-rod").X
    one = np.array([solve(robot, q[k], qd[k], qdd[k], leg_model="thin-rod").X[0]
                    for k in range(len(q))])
    np.testing.assert_array_equal(X, one)
