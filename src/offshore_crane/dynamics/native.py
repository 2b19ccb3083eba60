"""The Kane passes as straight-line programs compiled by LLVM, not by Numba.

Numba's front end types and lowers every operation of a function on its own, about
1.7 ms each (profiled: ``get_call_type``, ``lower_binop``): the explicit pass, its formulas
inlined, compiled in 20 s (the fused pass 14 s, the one with a pull 15 s); traced into a
straight-line Python program, in 21 s. The same trace (:func:`.tracing.trace_pass`)
written in LLVM's own text (:mod:`.llvm_program`) compiles in under a second. Straight,
the code is long (13 600 instructions for the explicit pass with the mass matrix, all run
once: the processor's front end, not its arithmetic, then sets the pace, 2.3 µs a call
against 1.87 µs for Numba's looped code), so the six legs, whose formulas
(:func:`~offshore_crane.dynamics.formulas.explicit_leg`,
:func:`~offshore_crane.dynamics.formulas.stewart_leg`) depend on no other leg, are traced
once and run as the lanes of vectors, leg l in lane l: 8 300 instructions and 1.52 µs a
call (0.70 µs without the mass matrix, against 1.24 µs).

A program does the operations of its formula in the formulas' order, with the
instructions Numba emits for them (no fast-math flag: nothing is reassociated or fused;
a vector instruction does in each lane what the scalar one does), the same library calls
and the legs' sums in leg order: the same numbers bit for bit (tested against the
Python-float backend for every pass and variant; every golden run is unchanged). Its
parameters are the constants' fields and the pass's arguments as :func:`caller` passes
them (an array by its data pointer, a matrix followed by its row length).

There is one program per arm structure (joint count and types), pass and variant (the
explicit pass with or without the mass matrix, the fused pass's flags): its address goes
into :data:`SLOTS` at :func:`program_index`, where the compiled wrappers
(:mod:`.passes`) read it at each call. The block programs of :mod:`.lanes` (the fused pass
on vectors of samples) have slots of their own after those (:func:`load_block`), filled
before their drivers run. A call finding its slot empty calls back into
Python (:func:`ensure_slot`: the structure's constants kept when the robot was packed,
:func:`remember`), which loads or compiles the program: only what runs is loaded, and a
process that stays on NumPy loads nothing.

Compiled objects are kept beside the package's Numba cache (:func:`~.lanes.
package_cache`), named by the SHA-256 of the program's text and of the compiler's target
(CPU and its features), with the SHA-256 of their content in front: a damaged file is
reported in one line (:class:`~offshore_crane.kernel_cache.GeneratedProgramWarning`) and
compiled again; files of another version of the text are removed.
"""

from __future__ import annotations

import contextlib
import hashlib
import signal
import struct
import sys
import threading

import numpy as np

from offshore_crane.dynamics.program_files import package_cache, read_file, write_atomically
from offshore_crane.dynamics.llvm_program import program_ir
from offshore_crane.dynamics.tracing import VARIANTS

#: The largest arm (joints, sway joints included) whose programs have a slot.
MAX_ARM = 8
_LOCK = threading.Lock()
#: Per slot index, the compiled library (kept alive: its code is what the slot points at).
_LIBRARIES: dict = {}
_MAGIC = b"offshore-crane native program 1\n"
#: The passes, in slot order (:data:`~.tracing.VARIANTS`' kinds).
KINDS = tuple(VARIANTS)
_NKINDS = len(KINDS)
#: The variants a pass's slots leave room for: the most any pass has (the fused pass's).
_VARIANTS = max(VARIANTS.values())


def program_index(kind, n_arm, arm_prism, variant):
    """The slot of pass ``kind`` (its index in :data:`KINDS`), ``variant``, for an arm
    of ``n_arm`` joints whose types are ``arm_prism`` (True: prismatic): the structure's
    code ``binary 1 p_0 p_1 … p_{n−1}``, then the kind, then the variant, below
    ``2 ** (MAX_ARM + 1) · len(KINDS) · _VARIANTS``. Plain arithmetic: compiled into the
    wrappers as it is run here."""
    code = 1
    for j in range(n_arm):
        code = 2 * code + (1 if arm_prism[j] else 0)
    return (code * _NKINDS + kind) * _VARIANTS + variant


#: Where the block programs' slots start (:func:`load_block`), after the passes', and
#: how many there are.
BLOCK_BASE, BLOCKS = 2 ** (MAX_ARM + 1) * _NKINDS * _VARIANTS, 1024
#: The programs' addresses by :func:`program_index`, then the block programs' (0: not
#: loaded).
SLOTS = np.zeros(BLOCK_BASE + BLOCKS, dtype=np.int64)
#: Per block slot, the structure key whose program it holds.
_BLOCK_KEYS: dict = {}


def block_index(key: str) -> int:
    """The slot of the block program of structure ``key`` (hex): from the key alone, so
    that a driver compiled in one process calls the same slot in the next."""
    return BLOCK_BASE + int(key[:12], 16) % BLOCKS


def load_block(key: str, name: str, text: str) -> bool:
    """Load or compile the block program ``text`` (function ``name``) of structure
    ``key`` into its slot (:func:`block_index`); False when the slot holds another
    structure's program (two keys of one slot in a process: the caller keeps its
    per-sample kernel)."""
    index = block_index(key)
    with _LOCK:
        if _BLOCK_KEYS.get(index, key) != key:
            return False
        if not SLOTS[index]:
            library = _library(name, text)
            _LIBRARIES[index] = library
            SLOTS[index] = library.get_pointer_to_function(name)
            _BLOCK_KEYS[index] = key
    return True


def stamp() -> str:
    """What the programs' text and calling convention come from: the formulas, the
    tracer, the writer of LLVM text and this module (the wrappers close over it)."""
    if not _STAMP:
        import inspect
        import sys

        from offshore_crane.dynamics import llvm_program, tracing
        from offshore_crane.dynamics.backends import source_stamp

        h = hashlib.sha256(source_stamp().encode())
        for module in (tracing, llvm_program, sys.modules[__name__]):
            h.update(inspect.getsource(module).encode())
        _STAMP.append(h.hexdigest()[:16])
    return _STAMP[0]


_STAMP: list = []
#: The symbol of :data:`SLOTS` in the JIT (named by the programs' text: a wrapper
#: compiled against one text never reads another's table).
SYMBOL = "offshore_crane_native_slots"


def register() -> tuple:
    """Make :data:`SLOTS` and the loader known to LLVM under their symbols (once):
    ``(slots' symbol, loader's symbol)``. The loader is :func:`ensure_slot` behind a C
    function pointer: a compiled call finding its slot empty calls it (taking the GIL),
    so the passes need no call of their own on that path (a Numba call there, even one
    never made, cost them their arrays' reference counts: 0.67 → 1.1 µs a call)."""
    import ctypes

    from llvmlite import binding

    if not _REGISTERED:
        names = (f"{SYMBOL}_{stamp()}", f"offshore_crane_native_load_{stamp()}")

        def load(index):
            with _signals_deferred(sys._getframe().f_code):
                try:
                    ensure_slot(index)
                except Exception:                      # noqa: BLE001 (a C caller)
                    import traceback

                    traceback.print_exc()              # the pass then raises

        callback = ctypes.CFUNCTYPE(None, ctypes.c_int64)(load)
        binding.add_symbol(names[0], SLOTS.ctypes.data)
        binding.add_symbol(names[1], ctypes.cast(callback, ctypes.c_void_p).value)
        _REGISTERED.extend([names, callback])             # the callback kept alive
    return _REGISTERED[0]


_REGISTERED: list = []


@contextlib.contextmanager
def _signals_deferred(code):
    """Hold back SIGINT and SIGTERM while a program loads from compiled code.

    The loader runs Python inside a C callback: an exception a signal's handler raises
    there (Ctrl-C's ``KeyboardInterrupt``, the CLI's ``Terminated``) cannot pass the
    compiled caller, and was printed and lost, leaving the program half loaded and the
    pass raising instead of the run ending as the signal asked (exit 1 with a traceback,
    not 143). In the main thread, a signal whose handler is Python's is recorded
    meanwhile, the load completes, the handlers are restored, and the signal is sent again
    once the thread has left the loader, so its handler runs where Python resumes, after
    the compiled call (the way a signal during any compiled call is handled). Elsewhere,
    or with a handler that is not Python's (the default, ignored), nothing changes.
    ``code``: the loader's code (the frame the signal must not be handled in)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    got: list = []
    held = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    held = {s: h for s, h in held.items() if callable(h)}
    for s in held:
        signal.signal(s, lambda signum, frame: got.append(signum))
    try:
        yield
    finally:
        for s, h in held.items():
            signal.signal(s, h)
        if got:
            _send_when_left(got, code, threading.get_ident())


def _send_when_left(signums: list, code, thread: int) -> None:
    """Raise ``signums`` again from a helper thread once ``thread`` no longer runs
    ``code`` (the loader: a handler run inside it would be lost as above)."""
    import time

    def inside() -> bool:
        frame = sys._current_frames().get(thread)
        while frame is not None:
            if frame.f_code is code:
                return True
            frame = frame.f_back
        return False

    def send():
        while inside():
            time.sleep(0.001)
        for s in signums:
            signal.raise_signal(s)

    threading.Thread(target=send, name="offshore-crane signal", daemon=True).start()


def ensure(kind: str, kane, variant: int) -> None:
    """Load or compile the program of pass ``kind``'s ``variant`` for the arm structure
    of ``kane`` into :data:`SLOTS`; nothing when it is there. Imports Numba's code
    generator (a structure's arm has at most :data:`MAX_ARM` joints: :func:`remember`
    refuses more).
    """
    n_arm, prism = int(kane.n_arm), np.asarray(kane.arm_prism)
    index = program_index(KINDS.index(kind), n_arm, prism, variant)
    if SLOTS[index]:
        return
    with _LOCK:
        if not SLOTS[index]:
            name = f"offshore_crane_{kind}_{stamp()}_{index}"
            text = program_ir(kind, kane, variant, name)
            library = _library(name, text)
            _LIBRARIES[index] = library
            SLOTS[index] = library.get_pointer_to_function(name)


def remember(kane) -> None:
    """Keep ``kane`` (a robot's constants: :func:`~.constants.pack` calls this) as its
    arm structure's template: :func:`ensure_slot` traces from it. Imports nothing; a
    serial chain (no leg) has no Kane pass and is not kept.

    Raises:
        ModelError: a hybrid robot whose arm has more than :data:`MAX_ARM` joints.
    """
    if not len(kane.leg_s):
        return
    n_arm = int(kane.n_arm)
    if n_arm > MAX_ARM:
        from offshore_crane.errors import ModelError

        raise ModelError(f"an arm of {n_arm} joints: the compiled passes handle at most "
                         f"{MAX_ARM} (offshore_crane.dynamics.native.MAX_ARM); use fewer "
                         "joints")
    code = program_index(0, n_arm, np.asarray(kane.arm_prism), 0) // (_NKINDS * _VARIANTS)
    _TEMPLATES.setdefault(code, kane)


#: Per arm-structure code, the constants of a robot of that structure (:func:`remember`).
_TEMPLATES: dict = {}


def ensure_slot(index: int) -> None:
    """:func:`ensure` the program of slot ``index``: its structure's template (a robot
    of that structure packed in this process), its pass and variant. A block program's
    slot is filled before its driver runs (:func:`load_block`), never here."""
    if index >= BLOCK_BASE:
        raise RuntimeError(f"the block program of slot {index} was not loaded before its "
                           "driver ran: report this as a bug")
    code, rest = divmod(int(index), _NKINDS * _VARIANTS)
    kind, variant = divmod(rest, _VARIANTS)
    kane = _TEMPLATES.get(code)
    if kane is None:
        raise RuntimeError(f"no robot of the arm structure of slot {index} was packed in "
                           "this process (offshore_crane.dynamics.constants.pack): report "
                           "this as a bug")
    ensure(KINDS[kind], kane, variant)


def _cache_folder():
    """Where the compiled programs live (:func:`~.program_files.package_cache`)."""
    return package_cache("native")


def _codegen():
    from numba.core.registry import cpu_target

    return cpu_target.target_context.codegen()


def _library(name: str, text: str, folder=None):
    """The compiled library of the program ``text``: read from its cache file (in
    ``folder``, by default :func:`_cache_folder`) when that holds the object of this
    text for this target, else compiled and written."""
    import llvmlite
    import numba
    from numba.core.compiler_lock import global_compiler_lock

    codegen = _codegen()
    key = hashlib.sha256("\0".join([text, repr(codegen.magic_tuple()), numba.__version__,
                                    llvmlite.__version__]).encode()).hexdigest()[:24]
    path = (folder or _cache_folder()) / f"{name}_{key}.bin"
    with global_compiler_lock:
        data, problem = _read(path)
        if data is not None:
            return codegen.unserialize_library((name, "object", data))
        if problem is not None:
            _warn(f"compiled program {path} {problem}: compiled again")
        from llvmlite import binding

        module = binding.parse_assembly(text)
        module.verify()
        library = codegen.create_library(name)
        library.enable_object_caching()
        library.add_llvm_module(module)
        library.finalize()
        _, _, data = library.serialize_using_object_code()
        problem = _write(path, data)
        if problem is not None:
            _warn(f"compiled program {path} {problem}: compiled in each process")
        return library


def _pack(data: tuple) -> bytes:
    obj, bitcode = data
    body = struct.pack("<Q", len(obj)) + obj + bitcode
    return _MAGIC + hashlib.sha256(body).hexdigest().encode() + b"\n" + body


def _read(path) -> tuple:
    """``(data, None)`` from an intact file, ``(None, None)`` when there is none,
    ``(None, what is wrong)`` otherwise."""
    raw, problem = read_file(path)
    if raw is None:
        return None, problem
    head = len(_MAGIC) + 65
    body = raw[head:]
    if not raw.startswith(_MAGIC) or raw[len(_MAGIC):head] != (
            hashlib.sha256(body).hexdigest().encode() + b"\n") or len(body) < 8:
        return None, "does not match its checksum (truncated, edited or not this version's)"
    n = struct.unpack("<Q", body[:8])[0]
    return (body[8:8 + n], body[8 + n:]), None


def _write(path, data: tuple) -> str | None:
    """Write the object (:func:`~.program_files.write_atomically`), removing the files of other
    versions of the programs' text; None, or what went wrong."""
    def remove_stale():
        for old in path.parent.glob("offshore_crane_*.bin"):
            if f"_{stamp()}_" not in old.name:
                with contextlib.suppress(OSError):
                    old.unlink()

    return write_atomically(path, _pack(data), remove_stale)


def _warn(message: str) -> None:
    import warnings

    from offshore_crane.kernel_cache import GeneratedProgramWarning

    warnings.warn(GeneratedProgramWarning(message), stacklevel=4)


def caller(arity: int):
    """The intrinsic ``call(index, *args)`` (``arity`` arguments after the index) that
    calls the program in slot ``index`` with ``args`` flattened (an array by its data
    pointer, C order, followed by its row length when it has two axes and is not inside
    a tuple; a tuple by its elements; numbers as int64 or double) and returns True;
    False, calling nothing, when the slot is empty (:func:`ensure` fills it)."""
    from llvmlite import ir
    from numba.core import cgutils, types
    from numba.core.errors import TypingError
    from numba.extending import intrinsic

    symbol, loader = register()

    def flatten(context, builder, typ, value, out, top=False):
        if isinstance(typ, types.Array):
            if typ.layout != "C" or typ.ndim > 2 and top:
                raise TypingError(f"a compiled pass takes C-contiguous arrays of one or "
                                  f"two axes, given {typ}")
            if value is not None:
                array = context.make_array(typ)(context, builder, value)
                out.append(array.data)
                if top and typ.ndim == 2:
                    out.append(cgutils.unpack_tuple(builder, array.shape, 2)[1])
        elif isinstance(typ, types.BaseTuple):
            for i, t in enumerate(typ):
                flatten(context, builder, t, None if value is None
                        else builder.extract_value(value, i), out)
        elif isinstance(typ, (types.Integer, types.Boolean)):
            if value is not None:
                out.append(context.cast(builder, value, typ, types.int64))
        elif isinstance(typ, types.Float):
            if value is not None:
                out.append(context.cast(builder, value, typ, types.float64))
        else:
            raise TypingError(f"a compiled pass cannot take {typ}")

    def call(typingctx, index, *args):
        for a in args:
            flatten(None, None, a, None, [], top=True)
        sig = types.boolean(index, *args)

        def codegen(context, builder, signature, values):
            table = builder.module.globals.get(symbol)
            if table is None:
                table = ir.GlobalVariable(builder.module, ir.IntType(64), symbol)
                table.linkage = "external"
            i = context.cast(builder, values[0], signature.args[0], types.int64)
            slot = builder.gep(table, [i])
            with builder.if_then(cgutils.is_null(builder, builder.load(slot)), likely=False):
                load = cgutils.get_or_insert_function(
                    builder.module, ir.FunctionType(ir.VoidType(), [ir.IntType(64)]),
                    loader)
                builder.call(load, [i])                 # Python: ensure_slot(i)
            address = builder.load(slot)
            loaded = builder.not_(cgutils.is_null(builder, address))
            with builder.if_then(loaded, likely=True):
                flat = []
                for t, v in zip(signature.args[1:], values[1:]):
                    flatten(context, builder, t, v, flat, top=True)
                fnty = ir.FunctionType(ir.VoidType(), [a.type for a in flat])
                builder.call(builder.inttoptr(address, fnty.as_pointer()), flat)
            return loaded

        return sig, codegen

    # a fixed arity: Numba lowers an intrinsic's *args as one packed argument
    names = ", ".join(f"a{i}" for i in range(arity))
    scope = {"call": call}
    exec(f"def call_program(typingctx, index, {names}):\n"
         f"    return call(typingctx, index, {names})\n", scope)
    fn = scope["call_program"]
    # importable by name: a caller's cache key pickles what it references, by reference
    fn.__module__, fn.__qualname__ = __name__, f"call_program_{arity}_{stamp()}"
    globals()[fn.__qualname__] = fn
    return intrinsic(fn)
