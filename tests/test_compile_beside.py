"""The passes a kernel calls by address compile in a helper process beside it
(:mod:`offshore_crane.compile_beside`): each case runs a small kernel and its entry in a
fresh Python process with an empty disk cache, as a first run does."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import pytest

from offshore_crane import compile_beside, compile_times

pytestmark = pytest.mark.skipif(compile_beside.usable_cores() < 2,
                                reason="the helper runs only with a second core")

MODULE = '''
from offshore_crane import kernel_calls
from offshore_crane.kernel_cache import njit


@njit(cache=True)
def weighted(x, w, y):
    return w * x[0] + y[0]


ENTRY = kernel_calls.Entry.typed("beside_test_weighted", lambda: weighted,
                                 "float64(V, float64, V)", "test")
call = ENTRY.call


@njit(cache=True)
def caller(x):
    return call(x, 2.0, x)
'''

SCRIPT = '''
import json, sys, warnings
import numpy as np
from offshore_crane import compile_beside
import beside_case as m

started = []
start = compile_beside.start
compile_beside.start = lambda entries, own=None: started.append(
    [e.name for e in entries]) or start(entries, own)
if sys.argv[1] == "broken":
    m.ENTRY.module = "no_such_module_of_this_test"
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    value = m.caller(np.array([1.5]))
d = m.weighted
print(json.dumps(dict(value=value, started=started,
                      hits=sum(d._cache_hits.values()), misses=sum(d._cache_misses.values()),
                      warnings=[str(w.message) for w in caught])))
'''


def _run(folder, case: str, switch: str = "1") -> dict:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(folder), *sys.path]),
               NUMBA_CACHE_DIR=str(folder / "cache"), XDG_CACHE_HOME=str(folder / "xdg"),
               **{compile_beside.SWITCH: switch})
    out = subprocess.run([sys.executable, str(folder / "script.py"), case], env=env,
                         capture_output=True, text=True, timeout=600, cwd=folder)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "beside_case.py").write_text(textwrap.dedent(MODULE))
    (tmp_path / "script.py").write_text(textwrap.dedent(SCRIPT))
    return tmp_path


def test_a_cold_kernels_pass_compiles_in_a_helper_and_loads_from_its_cache(folder):
    """Cold: the helper compiles the entry (this process only loads it: a cache hit, no
    miss); warm: no helper starts; the value is the call's either way."""
    cold = _run(folder, "cold")
    assert cold["value"] == 2.0 * 1.5 + 1.5
    assert cold["started"] == [["beside_test_weighted"]]
    assert (cold["hits"], cold["misses"]) == (1, 0)
    assert cold["warnings"] == []
    warm = _run(folder, "warm")
    assert warm["value"] == cold["value"] and warm["started"] == []
    assert (warm["hits"], warm["misses"]) == (1, 0)


def test_with_the_switch_off_the_pass_compiles_in_the_process_itself(folder):
    off = _run(folder, "off", switch="0")
    assert off["value"] == 4.5
    assert (off["hits"], off["misses"]) == (0, 1)        # compiled here, not loaded


def test_a_helper_that_fails_is_reported_and_the_pass_compiles_here(folder):
    broken = _run(folder, "broken")
    assert broken["value"] == 4.5
    assert (broken["hits"], broken["misses"]) == (0, 1)
    assert len(broken["warnings"]) == 1
    assert "helper process compiling beside_test_weighted" in broken["warnings"][0]
    assert "no_such_module_of_this_test" in broken["warnings"][0]


def test_off_turns_the_helper_off_for_a_block_and_restores_the_switch(monkeypatch):
    monkeypatch.setenv(compile_beside.SWITCH, "1")
    with compile_beside.off():
        assert os.environ[compile_beside.SWITCH] == "0"
        assert compile_beside.start([object()]) is None
    assert os.environ[compile_beside.SWITCH] == "1"


def test_passes_are_dealt_longest_first_to_the_least_busy_helper():
    """The elastic lift's passes (their recorded compile times [s]) on 2 helpers:
    20.4 s against 22.0 s; an unknown time counts as a small one."""
    names = ["explicit", "pulled", "cable", "derivative", "measure", "torque"]
    shares, loads = compile_beside.deal(names, 2, [18.3, 11.9, 5.0, 5.1, 1.1, None])
    assert shares == [["explicit", "measure", "torque"], ["pulled", "derivative", "cable"]]
    assert loads == pytest.approx([20.4, 22.0])
    assert compile_beside.deal(names[:1], 4, [3.0]) == ([["explicit"]], [3.0])
    assert compile_beside.deal([], 2, []) == ([], [])


def test_processes_sharing_cores_end_when_their_fair_shares_have_done_their_work():
    """Two cores: two processes run at full speed; three at 2/3 of a core each until
    the first ends (4 s of work: at 6 s), then the kernel's 6.5 s left at full speed."""
    assert compile_times.finish([10.0, 5.0], 2) == pytest.approx(10.0)
    assert compile_times.finish([10.5, 4.0, 4.0], 2) == pytest.approx(12.5)
    assert compile_times.finish([], 2) == 0.0


def test_as_many_helpers_as_end_the_wait_first():
    """The rigid robot's first ``simulate`` on 2 cores (its loop 10.5 s, its passes
    6.5 s in all): one helper (10.5 s against 12.2 s with two). The elastic lift's
    (loop 10 s, passes 15.8 s): two helpers end first. No kernel time known: one helper
    per core, as :func:`deal` alone."""
    rigid = ["law", "prepare", "inverse", "explicit"]
    shares, loads = compile_beside.plan(rigid, 2, [3.2, 1.5, 1.4, 0.4], 10.5)
    assert shares == [rigid] and loads == pytest.approx([6.5])
    elastic = ["cable", "derivative", "torque", "pulled", "measure"]
    times = [6.0, 5.5, 2.0, 1.2, 1.1]
    shares, loads = compile_beside.plan(elastic, 2, times, 10.0)
    assert len(shares) == 2
    assert compile_times.finish([10.0, *loads], 2) < compile_times.finish([10.0, 15.8], 2)
    assert compile_beside.plan(rigid, 2, [3.2, 1.5, 1.4, 0.4], None) == \
        compile_beside.deal(rigid, 2, [3.2, 1.5, 1.4, 0.4])
    assert compile_beside.plan([], 2, [], 10.0) == ([], [])
