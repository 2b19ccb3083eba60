"""The Kane passes compiled by LLVM from their trace (:mod:`offshore_crane.dynamics.native`).

Reference: the same formulas run on Python floats with :mod:`math`
(``backends.PYTHON``): the same IEEE operations in the same order and the same libm
calls, so the program must agree bit for bit (no tolerance: any reassociation, fused
multiply-add or other library function would show). The golden simulation runs check
the programs inside every compiled loop.
"""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.dynamics import backends, native
from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics.constants import cable_arrays, pack, robot_arrays
from offshore_crane.dynamics.tracing import VARIANTS
from offshore_crane.kernel_cache import GeneratedProgramWarning

G = (0.0, 0.0, -9.81)


def _states(n, count, seed):
    """Random but reachable states: the platform near its home pose, the arm anywhere."""
    rng = np.random.default_rng(seed)
    q = np.zeros((count, n))
    q[:, :3] = rng.normal(0.0, 0.05, (count, 3)) + np.array([0.0, 0.0, 1.3])
    q[:, 3:6] = rng.normal(0.0, 0.1, (count, 3))
    q[:, 6:] = rng.uniform(-1.0, 1.0, (count, n - 6))
    return q, rng.normal(0.0, 0.5, (count, n)), rng.normal(0.0, 2.0, (count, n))


def _run(f, C, q, qd, qdd, want_mass):
    n = len(q)
    out = (np.zeros(n), np.zeros((6, 6)), np.zeros((n, n)), np.zeros((max(C.n_arm, 1), 27)),
           np.zeros((7, 6)), np.zeros((1, 3)))
    B, J, Mm, store, diag, mc = out
    f(C, q, qd, qdd, G, want_mass, B, J, Mm, store, np.zeros((n, 3)), np.zeros((n, 3)),
      np.zeros((n, 3)), diag, mc)
    return out


def _structures():
    arrays = robot_arrays(oc.load_robot())
    flipped = arrays.kane._replace(arm_prism=~arrays.kane.arm_prism)   # other joint types
    hanging = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.5})
    return {"robot": arrays.kane, "no arm": robot_arrays(oc.load_robot(with_arm=0)).kane,
            "joint types flipped": pack(flipped, arrays.limits).kane,
            "hanging load": cable_arrays(hanging).kane}       # 5 joints, 11 speeds


@pytest.mark.parametrize("name", ["robot", "no arm", "joint types flipped", "hanging load"])
@pytest.mark.parametrize("want_mass", [False, True])
def test_the_program_is_the_formulas_bit_for_bit(name, want_mass):
    C = _structures()[name]
    n = 6 + C.n_arm
    q, qd, qdd = _states(n, 12, seed=7)
    for k in range(len(q)):
        got = _run(c.explicit_sample, C, q[k], qd[k], qdd[k], want_mass)
        ref = _run(backends.PYTHON.explicit_sample, C, list(q[k]), list(qd[k]), list(qdd[k]),
                   want_mass)
        for a, b in zip(got, ref):
            np.testing.assert_array_equal(a, b)


def _fused(f, C, q, qd, qdd, *flags, pull=None):
    na = C.n_arm
    out = (np.full(max(na, 1), 7.0), np.full((6, 6), 7.0), np.full(6, 7.0),
           np.full((7, 6), 7.0), np.full((max(na, 1), 27), 7.0))  # 7: what it leaves
    if pull is None:
        f(C, q, qd, qdd, G, *flags, *out)
    else:
        f(C, q, qd, qdd, G, *pull, *out)
    return out


@pytest.mark.parametrize("name", ["robot", "no arm", "hanging load"])
@pytest.mark.parametrize("static", [False, True])
@pytest.mark.parametrize("leg_model", [0, 1, 2])
@pytest.mark.parametrize("want_legs", [False, True])
def test_the_fused_pass_is_the_formulas_bit_for_bit(name, static, leg_model, want_legs):
    """Every variant of the fused pass, and the arrays it does not write are left as
    they were (the 7s)."""
    C = _structures()[name]
    n = 6 + C.n_arm
    q, qd, qdd = _states(n, 4, seed=9)
    if static:
        qd[:, :6] = qdd[:, :6] = 0.0
    flags = (static, leg_model, want_legs)
    for k in range(len(q)):
        got = _fused(c.kane_pass, C, q[k], qd[k], qdd[k], *flags)
        ref = _fused(backends.PYTHON.kane_sample, C, list(q[k]), list(qd[k]), list(qdd[k]),
                     *flags)
        for a, b in zip(got, ref):
            np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("name", ["robot", "hanging load"])
def test_the_pass_with_a_pull_is_the_formulas_bit_for_bit(name):
    C = _structures()[name]
    n = 6 + C.n_arm
    q, qd, qdd = _states(n, 6, seed=10)
    rng = np.random.default_rng(11)
    for k in range(len(q)):
        pull = (tuple(rng.normal(0.0, 50.0, 3)), tuple(rng.normal(0.0, 1.0, 3)))
        got = _fused(c.kane_pull_pass, C, q[k], qd[k], qdd[k], pull=pull)
        ref = _fused(backends.PYTHON.kane_sample_pull, C, list(q[k]), list(qd[k]),
                     list(qdd[k]), pull=pull)
        for a, b in zip(got, ref):
            np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("name", ["robot", "hanging load"])
def test_the_two_passes_with_a_pull_are_each_its_own_call_bit_for_bit(name):
    """``kane_pull2``: the pass at (q̈, pull) and (q̈, 0 × pull) in one program; each
    row of its outputs is the formulas' own call, and A, the diagnostics and the store
    the last call's."""
    C = _structures()[name]
    n, r = 6 + C.n_arm, max(C.n_arm, 1)
    q, qd, qdd = _states(n, 6, seed=12)
    rng = np.random.default_rng(13)
    for k in range(len(q)):
        pull, at = tuple(rng.normal(0.0, 50.0, 3)), tuple(rng.normal(0.0, 1.0, 3))
        pz = tuple(0.0 * x for x in pull)
        rows, rhs = np.full((2, r), 7.0), np.full((2, 6), 7.0)
        A, diag, store = np.full((6, 6), 7.0), np.full((7, 6), 7.0), np.full((r, 27), 7.0)
        c.kane_pull2_pass(C, q[k], qd[k], qdd[k], G, pull, pz, at, rows, A, rhs, diag,
                          store)
        for j, force in enumerate((pull, pz)):
            ref = _fused(backends.PYTHON.kane_sample_pull, C, list(q[k]), list(qd[k]),
                         list(qdd[k]), pull=(force, at))
            np.testing.assert_array_equal(rows[j], ref[0])
            np.testing.assert_array_equal(rhs[j], ref[2])
        for a, b in zip((A, diag, store), (ref[1], ref[3], ref[4])):
            np.testing.assert_array_equal(a, b)


def test_the_slot_index_is_one_to_one():
    seen = set()
    for n_arm in range(native.MAX_ARM + 1):
        for bits in range(2 ** n_arm):
            prism = [(bits >> j) & 1 == 1 for j in range(n_arm)]
            for kind, variants in enumerate(VARIANTS.values()):
                for variant in range(variants):
                    i = native.program_index(kind, n_arm, prism, variant)
                    assert 0 <= i < len(native.SLOTS) and i not in seen
                    seen.add(i)


@pytest.fixture
def kept_slots():
    """Restore the slots and libraries a test empties or replaces."""
    slots, libraries = native.SLOTS.copy(), dict(native._LIBRARIES)
    yield
    native.SLOTS[:] = slots
    native._LIBRARIES.clear()
    native._LIBRARIES.update(libraries)


def test_a_structures_first_call_loads_its_programs(kept_slots):
    """A program is loaded on its first compiled call (not when the robot's arrays are
    made: a process that stays on NumPy loads nothing), and only the variant called."""
    C = robot_arrays(oc.load_robot()).kane
    index = [native.program_index(0, C.n_arm, C.arm_prism, m) for m in (0, 1)]
    q, qd, qdd = _states(9, 1, seed=1)
    ref = _run(c.explicit_sample, C, q[0], qd[0], qdd[0], True)
    native.SLOTS[index] = 0
    for a, b in zip(_run(c.explicit_sample, C, q[0], qd[0], qdd[0], True), ref):
        np.testing.assert_array_equal(a, b)
    assert native.SLOTS[index[1]] != 0 and native.SLOTS[index[0]] == 0   # only what ran


def test_a_signal_during_a_load_ends_the_run_after_the_call(kept_slots, monkeypatch):
    """Ctrl-C while a program loads from inside a compiled call: the load completes, the
    pass gives its numbers (bit for bit), and KeyboardInterrupt is raised once Python
    resumes after the call; lost inside the loader's C callback before, the pass raised
    "could not be loaded" (a SIGTERM then ended the CLI with 1, not 143)."""
    import signal
    import time

    C = robot_arrays(oc.load_robot()).kane
    index = [native.program_index(0, C.n_arm, C.arm_prism, m) for m in (0, 1)]
    q, qd, qdd = _states(9, 1, seed=4)
    ref = _run(c.explicit_sample, C, q[0], qd[0], qdd[0], True)
    native.SLOTS[index] = 0
    load = native.ensure_slot

    def interrupted(i):
        signal.raise_signal(signal.SIGINT)          # the handler runs inside the loader
        load(i)

    monkeypatch.setattr(native, "ensure_slot", interrupted)
    # Python's own Ctrl-C handler, whatever this process inherited (a job started in the
    # background of a shell starts with SIGINT ignored, and Python then keeps it so)
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    got = []
    try:
        with pytest.raises(KeyboardInterrupt):
            got.append(_run(c.explicit_sample, C, q[0], qd[0], qdd[0], True))
            deadline = time.monotonic() + 5.0       # sent again once the call returned
            while time.monotonic() < deadline:
                time.sleep(0.01)
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler   # restored
    finally:
        signal.signal(signal.SIGINT, inherited)
    assert got, "the interrupt came before the pass returned"
    for a, b in zip(got[0], ref):
        np.testing.assert_array_equal(a, b)


def test_making_a_robots_arrays_loads_no_compiler():
    import subprocess
    import sys

    code = ("import sys, offshore_crane as oc\n"
            "from offshore_crane.dynamics.constants import robot_arrays\n"
            "robot_arrays(oc.load_robot())\n"
            "print(sorted(m for m in ('numba', 'llvmlite') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


def test_a_damaged_program_file_is_compiled_again(kept_slots, tmp_path, monkeypatch):
    monkeypatch.setattr(native, "_cache_folder", lambda: tmp_path / "native")
    C = robot_arrays(oc.load_robot()).kane
    q, qd, qdd = _states(9, 1, seed=2)
    ref = _run(c.explicit_sample, C, q[0], qd[0], qdd[0], True)
    index = [native.program_index(0, C.n_arm, C.arm_prism, m) for m in (0, 1)]
    native.SLOTS[index] = 0
    stale = tmp_path / "native" / "offshore_crane_explicit_0123456789abcdef_19_x.bin"
    stale.parent.mkdir()
    stale.write_bytes(b"another version of the programs' text")
    for m in (0, 1):
        native.ensure("explicit", C, m)                 # compiled, written
    files = sorted((tmp_path / "native").glob("*.bin"))
    assert len(files) == 2 and not stale.exists()
    native.SLOTS[index] = 0
    for m in (0, 1):
        native.ensure("explicit", C, m)                 # read back: no warning
    data = bytearray(files[1].read_bytes())
    data[-100] ^= 0xFF
    files[1].write_bytes(bytes(data))
    native.SLOTS[index] = 0
    with pytest.warns(GeneratedProgramWarning, match="does not match its checksum"):
        native.ensure("explicit", C, 1)
    for a, b in zip(_run(c.explicit_sample, C, q[0], qd[0], qdd[0], True), ref):
        np.testing.assert_array_equal(a, b)
    assert native._read(files[1])[1] is None            # rewritten whole


def test_an_arm_beyond_the_table_is_refused_when_packed():
    arrays = robot_arrays(oc.load_robot())
    nine = arrays.kane._replace(n_arm=9, arm_prism=np.zeros(9, bool))
    with pytest.raises(oc.ModelError, match="an arm of 9 joints.*at most 8"):
        pack(nine, arrays.limits)


def test_a_leg_model_out_of_range_is_refused_not_mistaken_for_another_slot():
    """The variant number is arithmetic on the flags: a leg model beyond 0..2 would read
    another variant's slot."""
    C = _structures()["robot"]
    q, qd, qdd = _states(9, 1, seed=12)
    with pytest.raises(ValueError, match="leg_model must be 0, 1 or 2"):
        _fused(c.kane_pass, C, q[0], qd[0], qdd[0], False, 3, True)
