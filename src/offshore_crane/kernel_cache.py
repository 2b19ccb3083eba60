"""Numba's ``njit`` with an on-disk cache that recovers from damaged entries.

Numba keeps a compiled kernel beside its source (``__pycache__/<module>.<function>-<line>.
py311.nbi``, the index, and ``….<n>.nbc``, one file per compiled signature). A file cut
short (a full disk, a killed copy) or garbled made every later run fail with Numba's own
``UnpicklingError`` until the user deleted ``__pycache__`` by hand. Every kernel of this
package is made by :func:`njit` below, a drop-in for ``numba.njit`` whose cache, when an
entry cannot be loaded, removes that function's index and data files, warns once
(:class:`KernelCacheWarning`, one line naming the files and the reason) and lets Numba
compile the function again, which writes a fresh entry. Before the first kernel of a
process compiles, :data:`COMPILE_NOTICE` is said once (:func:`offshore_crane.progress.
notice`), and :data:`COMPILED` counts the kernels compiled.

The recovering cache subclasses ``numba.core.caching.FunctionCache`` (Numba's own cache
of ``cache=True``) and replaces it on the dispatcher; the file names come from that
class (``_cache_file``), so they follow Numba's layout. A generated program's entries
(:mod:`offshore_crane.dynamics.lanes`) are keyed by the checksum of its text as well
(:data:`PROGRAM_DIGEST`); a damaged program is reported as a
:class:`GeneratedProgramWarning`, a :class:`KernelCacheWarning`. Numba is imported only
when a kernel is made.
"""

from __future__ import annotations

import contextlib
import os
import threading
import warnings

from offshore_crane import compile_beside, compile_times, kernel_calls
from offshore_crane.progress import first_time, notice

#: Numba options of every compiled kernel (disk cache, no GIL, NumPy's float semantics).
JIT = dict(cache=True, nogil=True, error_model="numpy")
# No fastmath: measured on the fused driver, reassociation saves 8 % (1.37 against 1.50 µs
# a sample at N = 10⁴) but lets LLVM fold the drivers' own non-finite checks (a NaN input
# then passes as finite: the callees are compiled with the caller's flags); contraction,
# signless zeros and fast reciprocals alone save 4 %, not worth a second float model.
#: :data:`JIT` without Numba's reference counting, for kernels that allocate nothing and
#: return no array (their arrays are their callers'): Numba otherwise calls ``NRT_incref``
#: and ``NRT_decref`` on each array argument at entry and exit, even on the views without
#: an owner the drivers pass (measured: the rigid robot 102 -> 122 real-time with the
#: driver's stage and law templates so compiled, the elastic lift 62 -> 69 with its
#: plant's stage kernels too). A kernel that allocates fails to compile under it.
LEAN = {**JIT, "_nrt": False}

#: Kernels compiled (not found in the cache) by this process so far.
COMPILED = [0]
#: Said once per process before the first kernel compiles (:func:`offshore_crane.
#: progress.notice`), with the wait it expects when a record knows it (this machine's
#: last compile of that kernel, else the package's table of ``benchmarks/compile.py``:
#: :mod:`offshore_crane.compile_times`).
COMPILE_NOTICE = ("compiling the Numba kernels this run needs, once (they are cached "
                  "afterwards; the whole set takes minutes, 'offshore-crane compile' does "
                  "it up front in parallel processes)")


class KernelCacheWarning(UserWarning):
    """A damaged compiled-kernel cache entry was removed and the kernel compiled again."""


class GeneratedProgramWarning(KernelCacheWarning):
    """A generated program (:mod:`offshore_crane.dynamics.lanes`) did not match its
    checksum and was generated again, or could not be written (the per-sample kernel
    runs instead)."""


#: The name, in a generated program's namespace, of the program's checksum (hex SHA-256
#: of its file name and text): :class:`RecoveringCache` adds it to the key of each
#: compiled entry, so that the compiled code of one text is never loaded for another (a
#: damaged one).
PROGRAM_DIGEST = "__program_sha256__"


def njit(*args, **options):
    """``numba.njit`` (same arguments), with :class:`RecoveringCache` when
    ``cache=True``."""
    import numba

    from numba.core.dispatcher import Dispatcher

    _install_one_optimisation()
    if "_nrt" in options and not hasattr(_default_options(), "_nrt"):
        options = {k: v for k, v in options.items() if k != "_nrt"}   # (LEAN's, below)
    decorate = numba.njit(*args, **options)
    finish = _recovering if options.get("inline", "never") != "never" else _plain_calls
    if isinstance(decorate, Dispatcher):            # njit(f, ...)
        return finish(decorate)
    return lambda f: finish(decorate(f))            # njit(...)(f)


def _default_options():
    """Numba's table of its decorators' options (``_nrt`` is underscored there: a Numba
    without it compiles :data:`LEAN` kernels with reference counts, as :data:`JIT`)."""
    from numba.core import options

    return getattr(options, "DefaultOptions", object)


def _plain_calls(dispatcher):
    """:func:`_recovering`, and calls from compiled code compile ``dispatcher`` for the
    arguments' plain types: a constant argument (``True``, ``0``) otherwise makes a
    specialisation of its own per value (Numba types it as a literal), the same code
    compiled again (measured: 23 s of the 41 s cold compile of the explicit kernels and
    the simulation loop). Functions inlined into their callers (``inline="always"``)
    are not compiled on their own and keep Numba's typing."""
    from numba.core.types import unliteral

    dispatcher = _recovering(dispatcher)
    typed = dispatcher.get_call_template

    def get_call_template(args, kws):
        return typed(tuple(unliteral(a) for a in args),
                     {k: unliteral(v) for k, v in kws.items()})

    dispatcher.get_call_template = get_call_template
    return dispatcher


def _recovering(dispatcher):
    """Give ``dispatcher`` a :class:`RecoveringCache` in place of Numba's, if it caches."""
    from numba.core.caching import FunctionCache

    cache = getattr(dispatcher, "_cache", None)
    if type(cache) is FunctionCache:
        dispatcher._cache = _cache_class()(dispatcher.py_func)
    return _ensuring(dispatcher)


#: Per thread: inside an outermost compile (whose end loads what the kernels it
#: compiles call by address).
_LOCAL = threading.local()


def _ensuring(dispatcher):
    """When ``dispatcher`` compiles or loads a signature, the functions its text calls
    by address (:func:`offshore_crane.kernel_calls.reached`) are loaded before it
    returns (:meth:`~offshore_crane.kernel_calls.Entry.ensure`; and those they call by
    address, :func:`~offshore_crane.kernel_calls.reached_all`), so that no kernel runs
    before them. Compiling the kernel needs only their symbols: when the kernel is not in
    the disk cache, those of them that are not either compile in a helper process while
    this one compiles the kernel (:mod:`offshore_crane.compile_beside`). A kernel compiled
    inside another's compile leaves its passes to the outermost one, which reaches them
    too. Numba compiles and loads through ``compile``, from Python and when another
    kernel that calls it is typed."""
    compile_ = _optimised_once(dispatcher.compile)

    def compile(sig):
        entries = [e for e in kernel_calls.reached_all(dispatcher.py_func) if not e.slot[0]]
        if not entries or getattr(_LOCAL, "outer", False) or compile_beside.helping():
            return compile_(sig)          # (a helper only writes its kernels' cache)
        beside = None
        if not kernel_calls.cached(dispatcher, sig):
            beside = compile_beside.start(
                [e for e in entries if not e.cached()],
                compile_times.seconds(compile_times.kernel_name(dispatcher.py_func)))
        _LOCAL.outer = True
        try:
            out = compile_(sig)
        except BaseException:
            if beside is not None:
                beside.stop()
            raise
        finally:
            _LOCAL.outer = False
        if beside is not None:
            try:
                beside.wait()
            except BaseException:             # interrupted while waiting: stop them
                beside.stop()
                raise
        for entry in entries:
            entry.ensure()
        return out

    dispatcher.compile = compile
    return dispatcher


#: Per thread: how deep in compiles of this package's kernels (:func:`_optimised_once`).
_COMPILING = threading.local()
#: Functions whose lone pass of LLVM's function pipeline was skipped
#: (:func:`_install_one_optimisation`).
SKIPPED_FUNCTION_PASSES = [0]


def _install_one_optimisation() -> None:
    """Let this package's kernels be optimised by LLVM once, not twice.

    Numba runs LLVM's O3 function pipeline on each function of a kernel's module when it
    adds the module to a library (``CPUCodeLibrary._optimize_functions``), then, the
    callees linked in, the O3 module pipeline on the whole library, which runs the
    function passes again after inlining. While one of this package's kernels compiles
    (:func:`_optimised_once`) the first is skipped. Measured on the whole set in one
    process (2026-11-28, 2 cores): 62.0 -> 56.1 s (LLVM's module pass grew 7.4 -> 11.9
    s, the skipped one took 9.0 s); the run time the same (interleaved, rigid robot 100.4
    against 101.3, elastic lift 50.5 against 50.8 real-time); all 187 golden arrays bit
    for bit (no pass reassociates a float: no fast-math flag). Other code's kernels keep
    Numba's pipeline; a Numba without that method is left as it is."""
    from numba.core import codegen

    cls = codegen.CPUCodeLibrary
    original = getattr(cls, "_optimize_functions", None)
    if original is None or getattr(original, "__offshore_crane__", False):
        return

    def _optimize_functions(self, ll_module):
        if getattr(_COMPILING, "depth", 0) == 0:
            return original(self, ll_module)
        ll_module.data_layout = self._codegen._data_layout    # as the original does
        SKIPPED_FUNCTION_PASSES[0] += 1

    _optimize_functions.__offshore_crane__ = True
    cls._optimize_functions = _optimize_functions


def _optimised_once(compile_):
    """``compile_`` (a dispatcher's) run as one of this package's compiles: the kernels it
    compiles, its callees', get LLVM's module pipeline only
    (:func:`_install_one_optimisation`)."""

    def compile(sig):
        _COMPILING.depth = getattr(_COMPILING, "depth", 0) + 1
        try:
            return compile_(sig)
        finally:
            _COMPILING.depth -= 1

    return compile


_CLASS: list = []


#: What tells a template's instances apart (:data:`offshore_crane.compile_times.INSTANCE`).
INSTANCE = compile_times.INSTANCE
_name = compile_times.kernel_name


def _cache_class():
    """:class:`RecoveringCache`, defined on first use (it subclasses a Numba class)."""
    if not _CLASS:
        from numba.core.caching import FunctionCache

        class RecoveringCache(FunctionCache):
            """Numba's function cache; an entry that fails to load is removed (its index
            and data files), reported once, and compiled again. Reads and writes of one
            function's entry hold a lock on ``<index>.lock`` beside it (:func:`locked`),
            so that processes compiling at once (``offshore-crane compile``'s workers,
            a sweep's) never interleave: Numba picks a new entry's data file name from
            the index it has read, and two writers could otherwise give two signatures
            the same file. A generated program's entries are keyed by its text's
            checksum too (:data:`PROGRAM_DIGEST`)."""

            def load_overload(self, sig, target_context):
                try:
                    with locked(self._cache_file, shared=True):
                        found = super().load_overload(sig, target_context)
                except Exception as exc:        # any failure to read an entry: recompile
                    remove_entry(self._cache_file, self._py_func.__qualname__, exc)
                    found = None
                if found is None:               # Numba compiles it now
                    COMPILED[0] += 1
                    wait = compile_times.started(_name(self._py_func))
                    notice("compile", COMPILE_NOTICE if wait is None else
                           COMPILE_NOTICE.replace("once (", f"once, {wait} (", 1))
                return found

            def has(self, sig, target_context) -> bool:
                """Whether the index holds an entry for ``sig`` (nothing loaded)."""
                if not self._enabled:
                    return False
                try:
                    target_context.refresh()
                    key = self._index_key(sig, target_context.codegen())
                    with locked(self._cache_file, shared=True):
                        return key in self._cache_file._load_index()
                except Exception:               # unreadable: as if absent (it compiles)
                    return False

            def save_overload(self, sig, data):
                with locked(self._cache_file, shared=False):
                    super().save_overload(sig, data)
                compile_times.saved(_name(self._py_func))

            def _index_key(self, sig, codegen):
                # Numba's key: the byte code (which holds no constant's value) and the
                # closure's values pickled, where a compiled function pickles with the
                # random ids of the intrinsics it uses (a new key, a compile, in every
                # process): the closure is described by stable_key instead. A generated
                # program's checksum tells two of its texts apart.
                f = self._py_func
                cells = tuple(c.cell_contents for c in f.__closure__ or ())
                key = (sig, codegen.magic_tuple(), (_sha(f.__code__.co_code),
                                                     _sha(repr(stable_key(cells)))))
                digest = f.__globals__.get(PROGRAM_DIGEST)
                return key if digest is None else (*key, digest)

        _CLASS.append(RecoveringCache)
    return _CLASS[0]


@contextlib.contextmanager
def locked(cache_file, shared: bool):
    """Hold a POSIX advisory lock (``fcntl.flock``: shared to read, exclusive to write)
    on the cache entry's ``<index>.lock`` file while the block runs; where there is no
    ``fcntl`` (Windows) or the folder cannot hold the lock file, no lock (Numba's own
    behaviour)."""
    try:
        import fcntl

        os.makedirs(cache_file._cache_path, exist_ok=True)
        fd = os.open(os.path.join(cache_file._cache_path, cache_file._index_name + ".lock"),
                     os.O_RDWR | os.O_CREAT, 0o666)
    except (ImportError, OSError):
        yield
        return
    try:
        fcntl.flock(fd, fcntl.LOCK_SH if shared else fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)                      # closing releases the lock


def entry_files(cache_file) -> list[str]:
    """The files of one function's cache entry: its index and its data files."""
    directory = cache_file._cache_path
    base = cache_file._index_name[: -len(".nbi")]
    names = [n for n in os.listdir(directory) if n == cache_file._index_name
             or (n.startswith(base + ".") and n.endswith(".nbc"))] \
        if os.path.isdir(directory) else []
    return [os.path.join(directory, n) for n in sorted(names)]


def remove_entry(cache_file, name: str, exc: Exception) -> None:
    """Remove one function's damaged entry (what can be removed) and warn once."""
    files = entry_files(cache_file)
    for path in files:
        try:
            os.unlink(path)
        except OSError:
            pass
    reason = (str(exc).splitlines() or [""])[0]
    if not first_time(("kernel cache entry", cache_file._cache_path, cache_file._index_name)):
        return
    where = os.path.join(cache_file._cache_path, cache_file._index_name[: -len(".nbi")])
    warnings.warn(KernelCacheWarning(
        f"compiled-kernel cache entry {where}.* could not be loaded ({type(exc).__name__}: "
        f"{reason}): removed {len(files)} file(s), compiling {name} again"), stacklevel=2)


def _sha(data) -> str:
    import hashlib

    return hashlib.sha256(data if isinstance(data, bytes) else data.encode()).hexdigest()


_FILES: dict = {}


def _file_digest(path: str) -> str:
    """The checksum of a source file's text (once per process), or its path when it
    cannot be read."""
    if path not in _FILES:
        try:
            with open(path, "rb") as fh:
                _FILES[path] = _sha(fh.read())
        except OSError:
            _FILES[path] = path
    return _FILES[path]


def stable_key(obj, seen=None):
    """What a compiled kernel's closure holds, described the same in every process: a
    compiled function by its name, byte code, its source file's checksum and (the same
    way) its closure; an intrinsic by its name; arrays by their bytes; plain values by
    ``repr``; anything else pickled (Numba's pickler)."""
    from numba.core.dispatcher import Dispatcher
    from numba.core.extending import _Intrinsic

    seen = set() if seen is None else seen
    if isinstance(obj, (str, bytes, int, float, complex, bool, type(None))):
        return (type(obj).__name__, obj)
    if isinstance(obj, (tuple, list)):
        return (type(obj).__name__, tuple(stable_key(x, seen) for x in obj))
    if id(obj) in seen:
        return ("seen",)
    seen.add(id(obj))
    if isinstance(obj, Dispatcher):
        f = obj.py_func
        cells = tuple(c.cell_contents for c in f.__closure__ or ())
        return ("kernel", f.__module__, f.__qualname__, _sha(f.__code__.co_code),
                _file_digest(f.__code__.co_filename), stable_key(cells, seen))
    if isinstance(obj, _Intrinsic):
        return ("intrinsic", obj._name, getattr(obj._defn, "__module__", ""),
                getattr(obj._defn, "__qualname__", ""))
    import numpy as np

    if isinstance(obj, np.ndarray):
        return ("array", obj.dtype.str, obj.shape, _sha(np.ascontiguousarray(obj).tobytes()))
    from numba.core.serialize import dumps

    return ("pickled", _sha(dumps(obj)))
