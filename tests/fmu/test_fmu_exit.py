"""The FMU leaves its master's exit clean: PythonFMU's binary (0.6.4 and later) frees its
interpreter's state in the C++ static destructors, then resets that destroyed pointer
again in its ``__attribute__((destructor))`` function, a write into freed memory that
aborted FMPy's exit once in CI ("corrupted double-linked list"). The FMU's model
releases that state from Python's ``atexit`` (``offshore_crane.fmu.model``), so both
clean-ups find it empty.

The check reads the binary's global ``pyState`` itself (its address from the binary's
own symbol table, parsed here), in a fresh Python process that loads the FMU with FMPy:
set after ``fmi2Instantiate``, empty after the process's ``atexit`` functions. Without
the release it stays set, and Valgrind reports the invalid access at every exit; with
it, Valgrind reports none (checked by hand, in FMPy and in a C master)."""

from __future__ import annotations

import ast
import struct
import subprocess
import sys
from pathlib import Path

import pytest

from offshore_crane.fmu import export_fmu

SCENES = Path(__file__).parents[2] / "scenes"
STATE = "_ZN12_GLOBAL__N_17pyStateE"        # PythonFMU's `pyState` (anonymous namespace)
RELEASE = "finalizePythonInterpreter"       # exported: its address places the binary

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="the use after free is in the ELF clean-up order")


def symbols(binary: Path, names: set[str]) -> dict[str, int]:
    """The offsets [byte] of ``names`` from the load base of an ELF64 little-endian
    shared library, read from its ``.symtab`` (local symbols included)."""
    data = binary.read_bytes()
    assert data[:4] == b"\x7fELF" and data[4] == 2 and data[5] == 1, binary
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum = struct.unpack_from("<HH", data, 0x3A)
    heads = [struct.unpack_from("<IIQQQQIIQQ", data, shoff + k * shentsize)
             for k in range(shnum)]
    found = {}
    for _, kind, _, _, offset, size, link, _, _, entsize in heads:
        if kind != 2:                                       # SHT_SYMTAB
            continue
        strings = heads[link][4]
        for at in range(offset, offset + size, entsize):
            name_at, _, _, _, value, _ = struct.unpack_from("<IBBHQQ", data, at)
            end = data.index(b"\0", strings + name_at)
            name = data[strings + name_at:end].decode()
            if name in names:
                found[name] = value
    return found


HOST = """
import atexit, ctypes, os, sys
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
path, state, release = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
md = read_model_description(path)
unzipped = extract(path)
fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                modelIdentifier=md.coSimulation.modelIdentifier, instanceName="exit")
fmu.instantiate()
binary = os.path.join(unzipped, "binaries", "linux64",
                      md.coSimulation.modelIdentifier + ".so")
lib = ctypes.CDLL(binary, mode=os.RTLD_NOLOAD | os.RTLD_LAZY)   # the loaded copy
base = ctypes.cast(lib.finalizePythonInterpreter, ctypes.c_void_p).value - release
words = (ctypes.c_uint64 * 2).from_address(base + state)        # (pointer, its count)
set_ = list(words)
fmu.freeInstance()                      # FMPy closes the library: it stays (NODELETE)
freed = list(words)
atexit._run_exitfuncs()                 # what ends the interpreter runs them first
print((set_, freed, list(words)))
"""


def test_the_loaders_state_is_empty_before_the_masters_exit(tmp_path):
    """After ``fmi2Instantiate`` the state is set (so the check can see it); freeing
    the instance leaves it set (the library is not unloaded: what the exit then runs
    meets it); after the interpreter's ``atexit`` functions it is empty, both words."""
    fmu = export_fmu(SCENES / "hanging_load.toml", tmp_path / "crane.fmu",
                     control_period=0.01, duration=0.05)
    import pythonfmu
    binary = (Path(pythonfmu.__file__).parent / "resources" / "binaries" / "linux64"
              / "libpythonfmu-export.so")
    at = symbols(binary, {STATE, RELEASE})
    assert set(at) == {STATE, RELEASE}, "PythonFMU's binary changed: re-check the release"
    run = subprocess.run([sys.executable, "-c", HOST, str(fmu), str(at[STATE]),
                          str(at[RELEASE])], capture_output=True, text=True,
                         cwd=tmp_path, timeout=300)
    assert run.returncode == 0, run.stderr
    set_, freed, after = ast.literal_eval(run.stdout.strip().splitlines()[-1])
    assert set_[0] != 0 and set_[1] != 0
    assert freed == set_
    assert after == [0, 0]
