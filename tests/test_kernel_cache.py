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
