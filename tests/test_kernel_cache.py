"""The compiled-kernel cache recovers from damaged entries (issue 21, item 7): a truncated
or garbled index or data file of Numba's cache is removed, reported in one line, and the
kernel compiled again, in a fresh process each time, as users meet it.

Each run is a new Python process importing a small module made with
``offshore_crane.kernel_cache.njit(cache=True)`` in a temporary directory (so the
package's own cache, shared by the test session's workers, is never touched).
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import offshore_crane

#: Where the package the tests import lives (the source tree, or the installed copy in
#: CI): subprocesses import the same one, whose compiled kernels are already cached.
SRC = Path(offshore_crane.__file__).resolve().parents[1]

MODULE = '''
from offshore_crane.kernel_cache import njit


@njit(cache=True, nogil=True)
def kernel(x):
    return 2.0 * x + 1.0
'''

RUN = '''
import warnings
warnings.simplefilter("always")
import mod
print(mod.kernel(3.0), mod.kernel(3))
'''


def _run(where: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": f"{SRC}{os.pathsep}{where}"}
    env.pop("NUMBA_CACHE_DIR", None)
    return subprocess.run([sys.executable, "-c", RUN], cwd=where, env=env,
                          capture_output=True, text=True, timeout=120)


def _entry(where: Path) -> list[Path]:
    return sorted((where / "__pycache__").glob("mod.kernel-*.nb*"))


@pytest.mark.parametrize("damage", ["truncated index", "truncated data", "garbled data",
                                    "empty index"])
def test_a_damaged_entry_is_removed_reported_and_compiled_again(tmp_path, damage):
    (tmp_path / "mod.py").write_text(MODULE)
    first = _run(tmp_path)
    assert first.returncode == 0 and first.stdout.split() == ["7.0", "7.0"], first.stderr
    files = _entry(tmp_path)
    index = [p for p in files if p.suffix == ".nbi"]
    data = [p for p in files if p.suffix == ".nbc"]
    assert len(index) == 1 and len(data) == 2            # one file per signature
    target = index[0] if "index" in damage else data[0]
    content = target.read_bytes()
    target.write_bytes(b"" if damage == "empty index" else
                       content[:len(content) // 3] if "truncated" in damage else
                       content[:40] + bytes(255 - b for b in content[40:]))
    second = _run(tmp_path)
    assert second.returncode == 0, second.stderr
    assert second.stdout.split() == ["7.0", "7.0"]          # compiled again, same results
    lines = [ln for ln in second.stderr.splitlines() if "KernelCacheWarning" in ln]
    assert len(lines) == 1, second.stderr                 # once, one line
    assert "mod.kernel-" in lines[0] and "could not be loaded" in lines[0]
    assert "compiling kernel again" in lines[0]
    assert "Traceback" not in second.stderr
    third = _run(tmp_path)                                # the fresh entry loads: silent
    assert third.returncode == 0 and third.stdout.split() == ["7.0", "7.0"]
    assert "KernelCacheWarning" not in third.stderr, third.stderr
    assert [p.suffix for p in _entry(tmp_path)].count(".nbc") == 2


def test_njit_keeps_numbas_forms():
    """Both forms of the decorator, and no cache when not asked for."""
    from numba.core.caching import FunctionCache

    from offshore_crane.kernel_cache import njit

    def f(x):
        return x + 1.0

    plain = njit(f)
    cached = njit(cache=True)(lambda x: x * 2.0)
    assert plain(1.0) == 2.0 and cached(2.0) == 4.0
    assert type(cached._cache).__name__ == "RecoveringCache"
    assert isinstance(cached._cache, FunctionCache)
    assert type(plain._cache).__name__ == "NullCache"


def test_the_package_kernels_skip_the_lone_function_pass_and_others_keep_it():
    """This package's kernels get LLVM's module pipeline only; a kernel of other code
    compiled in the same process still gets Numba's function pass first; the two give
    the same numbers (a loop with a callee, so that the module pass has inlining to do).
    """
    import numba
    from numba.core import codegen

    from offshore_crane import kernel_cache
    from offshore_crane.kernel_cache import njit

    def make(jit):
        @jit
        def callee(x, k):
            return x * (k + 0.5) - 1.0 / (k + 1.0)

        @jit
        def total(n):
            s = 0.0
            for k in range(n):
                s += callee(0.3, k)
            return s

        return total

    ran = []
    original = codegen.CPUCodeLibrary._optimize_functions
    ours = make(njit)
    before = kernel_cache.SKIPPED_FUNCTION_PASSES[0]
    assert ours(1000) == ours(1000)
    skipped = kernel_cache.SKIPPED_FUNCTION_PASSES[0] - before
    assert skipped >= 2                     # the kernel's module and its callee's
    codegen.CPUCodeLibrary._optimize_functions = lambda self, m: (ran.append(m),
                                                                  original(self, m))
    try:
        theirs = make(numba.njit)
        assert theirs(1000) == ours(1000)   # bit for bit
    finally:
        codegen.CPUCodeLibrary._optimize_functions = original
    assert ran and kernel_cache.SKIPPED_FUNCTION_PASSES[0] - before == skipped


def test_lean_kernels_run_on_their_callers_arrays_and_refuse_to_allocate():
    """:data:`~offshore_crane.kernel_cache.LEAN` (no reference counts): a kernel that
    writes into the arrays it is given runs; one that allocates is refused when it
    compiles, not run without its array's owner. The stage kernels are compiled so."""
    from numba.core.errors import TypingError

    from offshore_crane.dynamics import linear
    from offshore_crane.dynamics.cable import elastic_plant as ep
    from offshore_crane.kernel_cache import LEAN, njit

    @njit(**{**LEAN, "cache": False})
    def fill(x, v):
        for i in range(x.shape[0]):
            x[i] = v
        return x.shape[0]

    @njit(**{**LEAN, "cache": False})
    def allocate(n):
        return np.empty(n).sum()

    x = np.zeros(5)
    assert fill(x, 2.0) == 5 and (x == 2.0).all()
    with pytest.raises(TypingError, match="np_empty"):
        allocate(3)
    for kernel in (ep.measure, ep.computed_torque_share, ep.derivative, ep.accelerate,
                   linear.cholesky_solve, linear.solve6, linear.solve6_many):
        assert kernel.targetoptions.get("_nrt") is False, kernel.py_func.__qualname__


RACE = '''
import sys, time
from numba.core import caching
from offshore_crane import kernel_cache
import mod

# widen the race: Numba's save reads the index, picks the new entry's data file name,
# then writes the index; a pause before that write lets the other processes read the
# same index (without the entry's lock they would all pick data file 1)
save_index = caching.IndexDataCacheFile._save_index
caching.IndexDataCacheFile._save_index = lambda self, o: (time.sleep(0.5), save_index(self, o))
start = float(sys.argv[1])
while time.time() < start:          # both processes compile at the same moment
    time.sleep(0.001)
x = {"float": 3.0, "int": 3, "complex": 3 + 0j}[sys.argv[2]]
print(mod.kernel(x), kernel_cache.COMPILED[0])
'''

LOAD = '''
from offshore_crane import kernel_cache
import mod
print(mod.kernel(3.0), mod.kernel(3), mod.kernel(3 + 0j), kernel_cache.COMPILED[0])
'''


def _script(where: Path, code: str, *args, cache: Path | None = None):
    env = {**os.environ, "PYTHONPATH": f"{SRC}{os.pathsep}{where}"}
    env.pop("NUMBA_CACHE_DIR", None)
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = str(cache)
    return subprocess.Popen([sys.executable, "-c", code, *map(str, args)], cwd=where,
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


def test_processes_compiling_at_once_keep_every_signature_and_a_copied_cache_loads(tmp_path):
    """Three processes compile three signatures of one kernel at the same moment into one
    cache (what ``offshore-crane compile``'s workers and a sweep's do): a fourth process
    then loads all three without compiling (the entry's lock keeps Numba from giving two
    signatures one data file); so does a process reading a copy of that cache folder
    elsewhere (NUMBA_CACHE_DIR), as on another machine of the same architecture."""
    import shutil
    import time

    (tmp_path / "mod.py").write_text(MODULE)
    cache = tmp_path / "cache"
    start = time.time() + 3.0                   # after the three have imported Numba
    procs = [_script(tmp_path, RACE, start, kind, cache=cache)
             for kind in ("float", "int", "complex")]
    outs = [p.communicate(timeout=120) for p in procs]
    assert all(p.returncode == 0 for p in procs), [o[1] for o in outs]
    assert [o[0].split()[1] for o in outs] == ["1", "1", "1"]     # each compiled its own
    for where in (cache, tmp_path / "copied"):
        if where != cache:
            shutil.copytree(cache, where)
        p = _script(tmp_path, LOAD, cache=where)
        out, err = p.communicate(timeout=120)
        assert p.returncode == 0, err
        assert out.split() == ["7.0", "7.0", "(7+0j)", "0"], (out, err)


def test_compile_runs_its_groups_and_refuses_no_workers(capsys):
    """``offshore-crane compile`` (warm here: every group loads from the cache): each
    group reported once; ``--jobs 0`` is one line, exit 2."""
    from offshore_crane.__main__ import main
    from offshore_crane.cli.compile import PARTS

    assert main(["compile", "--jobs", "1"]) == 0
    out = capsys.readouterr().out
    assert "compiled kernels ready in" in out
    lines = out.splitlines()
    assert all(sum(line.startswith(f"{name}:") for line in lines) == 1 for name in
               ("kane kernels", "rnea kernels", "simulation loop", "hanging-load kernels",
                "elastic-cable simulation loop", "trajectory interpolation"))
    assert len(PARTS) == 7
    assert main(["compile", "--jobs", "0"]) == 2
    err = capsys.readouterr().err
    assert "--jobs 0: give at least 1" in err and err.count("\n") == 1


def test_a_new_process_loads_every_group_without_compiling():
    """After the session's compile (conftest), a new process finds every kernel of every
    group in the cache: none is compiled again. (The serial chain's loops once closed
    over their inlined helper's dispatcher, whose per-process id entered Numba's cache
    key: they compiled again in every process, 10 s, and their index grew a signature
    each time.)"""
    code = ("from offshore_crane import kernel_cache\n"
            "from offshore_crane.cli.compile import compile_all\n"
            "compile_all(jobs=1)\n"
            "print(kernel_cache.COMPILED[0])\n")
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    run = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split()[-1] == "0", run.stderr


def test_constant_arguments_do_not_make_a_called_kernel_compile_again():
    """A compiled function called from compiled code with constants (``True``, ``0``)
    compiles once, for the plain types: Numba types a constant as a literal and made a
    specialisation per value (the explicit formulas three times, ~5 s each). Inlined
    functions keep Numba's typing (they are not compiled on their own)."""
    from offshore_crane.kernel_cache import njit

    @njit
    def callee(x, flag, k):
        return x + k if flag else x - k

    @njit(inline="always")
    def inlined(x, k):
        return x * k

    @njit
    def caller(x):
        return (callee(x, True, 1) + callee(x, False, 2) + callee(x, x > 0.0, 3)
                + inlined(x, 2) + inlined(x, 3))

    assert caller(1.0) == 2.0 + -1.0 + 4.0 + 2.0 + 3.0
    assert len(callee.signatures) == 1
    assert [str(t) for t in callee.signatures[0]] == ["float64", "bool", "int64"]


def test_no_two_texts_of_compiled_kernels_share_a_symbols_name():
    """Numba names a compiled function's symbol by its module, qualified name and
    argument types, and a library loaded from the disk cache links its callees by that
    name, the first loaded one winning: two texts with one name and types ran each
    other's code (a plain elastic lift after a commanded one: a heap overrun). The
    driver's loop instances (one per plant, variant and law) and the elastic plant's two
    variants have names of their own; the compile-time record still names each by its
    template."""
    from offshore_crane.compile_times import kernel_name
    from offshore_crane.simulation.loop import instantiate
    from offshore_crane.simulation.laws.computed_torque import command
    from offshore_crane.simulation.laws._registry import no_state
    from offshore_crane.simulation.plants import _elastic_kernels as ek

    laws = {"command": command, "law_rate": no_state}
    a, b = (instantiate(ek, laws, {"IQ": 0, "IQD": 12}, False, key)
            for key in ("elastic computed-torque", "elastic (commanded winch) computed-torque"))
    for name in ("loop", "evaluate", "sense", "command"):
        assert a[name].__qualname__ != b[name].__qualname__, name
        assert a[name].__template__ == b[name].__template__ == name
    assert kernel_name(a["loop"]) == ("offshore_crane.simulation.loop.loop "
                                      "[elastic computed-torque]")
    commanded = ek._commanded()
    for name in ("keep", "gravity", "arm_tip", "winch_to"):
        mine, theirs = getattr(ek, name).py_func, getattr(commanded, name).py_func
        assert mine.__qualname__ != theirs.__qualname__, name
