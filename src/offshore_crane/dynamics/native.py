"""The explicit Kane pass as straight-line programs compiled by LLVM, not by Numba.

Numba's front end types and lowers every operation of a function on its own, about
1.7 ms each (profiled: ``get_call_type``, ``lower_binop``): the explicit pass, its formulas
inlined, compiled in 20 s; traced into a straight-line Python program, in 21 s. The same
trace (:func:`.tracing.trace_explicit`) written in LLVM's own text compiles in under a
second. Straight-line code is also long (13 600 instructions with the mass matrix, all
run once: the processor's front end, not its arithmetic, then sets the pace, 2.3 µs a
call against 1.87 µs for Numba's looped code), so the six legs, whose formulas
(:func:`~offshore_crane.dynamics.formulas.explicit_leg`) depend on no other leg, are
traced once and run as the :data:`LANES` lanes of vectors, leg l in lane l: 8 300
instructions and 1.52 µs a call (0.70 µs without the mass matrix, against 1.24 µs).

For each arm structure (joint count and types) and with or without the mass matrix, one
function ``void offshore_crane_explicit_<stamp>_<index>(<the constants' fields>, q, qd,
qdd, g0, g1, g2, B, J, Mm, m_stride, store, diag, mc)`` (arrays by their data pointers, C
order; ``m_stride`` Mm's row length) does the operations of
:func:`~offshore_crane.dynamics.formulas.explicit_sample` in the formulas' order, with
the instructions Numba emits for them (``fadd``, ``fmul``, …, no fast-math flag: nothing
is reassociated or fused; a vector instruction does in each lane what the scalar one does)
and the same library calls (``llvm.sin``, ``llvm.cos``, ``atan2``; ``llvm.sqrt``, correctly
rounded as ``sqrt`` is): the same numbers bit for bit (tested against the Python-float
backend, and every golden run is unchanged). The legs' sums stay in leg order.

A program's address goes into :data:`SLOTS` at :func:`program_index` (the structure and
``want_mass``); the compiled wrapper :func:`~offshore_crane.dynamics.explicit_pass.
explicit_sample` reads it there at each call, and on a structure's first call loads or
compiles its programs (:func:`ensure`): a process that stays on NumPy loads nothing.

Compiled objects are kept beside the package's Numba cache (:func:`~.lanes.
package_cache`), named by the SHA-256 of the program's text and of the compiler's target
(CPU and its features), with the SHA-256 of their content in front: a damaged file is
reported in one line (:class:`~offshore_crane.kernel_cache.GeneratedProgramWarning`) and
compiled again.
"""

from __future__ import annotations

import contextlib
import hashlib
import re
import struct
import threading

import numpy as np

from offshore_crane.dynamics.lanes import package_cache, read_file, write_atomically

#: The largest arm (joints, sway joints included) whose programs have a slot.
MAX_ARM = 8
_LOCK = threading.Lock()
#: Per slot index, the compiled library (kept alive: its code is what the slot points at).
_LIBRARIES: dict = {}
_MAGIC = b"offshore-crane native program 1\n"
_BINARY = {"+": "fadd", "-": "fsub", "*": "fmul", "/": "fdiv"}
#: The library calls, as Numba lowers np.sqrt, np.sin, np.cos and np.arctan2 of a float
#: (its ``sqrt`` is declared without side effects, so LLVM makes it the instruction:
#: correctly rounded, as ``llvm.sqrt`` is; a plain call would spill every live register).
_CALLS = {"sqrt": ("@llvm.sqrt.f64", 1), "sin": ("@llvm.sin.f64", 1), "cos": ("@llvm.cos.f64", 1),
          "arctan2": ("@atan2", 2)}
_VECTOR_CALLS = {"@llvm.sqrt.f64": "@llvm.sqrt.v8f64", "@llvm.fabs.f64": "@llvm.fabs.v8f64"}
_DECLARE = ("declare double @llvm.sin.f64(double)\ndeclare double @llvm.cos.f64(double)\n"
            "declare double @llvm.fabs.f64(double)\ndeclare double @llvm.sqrt.f64(double)\n"
            "declare double @atan2(double, double) nounwind memory(none)\n"
            "declare <8 x double> @llvm.sqrt.v8f64(<8 x double>)\n"
            "declare <8 x double> @llvm.fabs.v8f64(<8 x double>)\n")


def program_index(n_arm, arm_prism, want_mass):
    """The slot of the program of an arm of ``n_arm`` joints whose types are
    ``arm_prism`` (True: prismatic), with (``want_mass``) or without the mass matrix:
    ``2 · (binary 1 p_0 p_1 … p_{n−1}) + want_mass``, below ``2 ** (MAX_ARM + 2)``.
    Plain arithmetic: compiled into the wrapper as it is run here."""
    code = 1
    for j in range(n_arm):
        code = 2 * code + (1 if arm_prism[j] else 0)
    return 2 * code + (1 if want_mass else 0)


#: The programs' addresses by :func:`program_index` (0: not loaded).
SLOTS = np.zeros(2 ** (MAX_ARM + 2), dtype=np.int64)


def stamp() -> str:
    """What the programs' text comes from: the formulas, the tracer and this module."""
    if not _STAMP:
        import inspect
        import sys

        from offshore_crane.dynamics import tracing
        from offshore_crane.dynamics.backends import source_stamp

        h = hashlib.sha256(source_stamp().encode())
        for module in (tracing, sys.modules[__name__]):
            h.update(inspect.getsource(module).encode())
        _STAMP.append(h.hexdigest()[:16])
    return _STAMP[0]


_STAMP: list = []
#: The symbol of :data:`SLOTS` in the JIT (named by the programs' text: a wrapper
#: compiled against one text never reads another's table).
SYMBOL = "offshore_crane_native_slots"


def register() -> str:
    """Make :data:`SLOTS` known to LLVM under its symbol (once); the symbol."""
    from llvmlite import binding

    name = f"{SYMBOL}_{stamp()}"
    if not _REGISTERED:
        binding.add_symbol(name, SLOTS.ctypes.data)
        _REGISTERED.append(name)
    return name


_REGISTERED: list = []


def _literal(x: float) -> str:
    """A double in LLVM's text: its bits, exactly."""
    return "0x%016X" % struct.unpack("<Q", struct.pack("<d", x))[0]


def _fields(kane) -> list:
    """``(field index, name, kind)`` of the constants' fields in order, ``kind`` one of
    ``"i64"`` (n_arm), ``"ptr"`` (an array, arm_prism too) or ``"double"``."""
    from offshore_crane.dynamics.formulas import KaneConstants

    out = []
    for f, name in enumerate(KaneConstants._fields):
        value = getattr(kane, name)
        kind = ("i64" if name == "n_arm" else "ptr" if np.ndim(value) or name == "arm_prism"
                else "double")
        out.append((f, name, kind))
    return out


#: Lanes of the legs' vectors (6 legs; lanes 6 and 7 repeat leg 0): the width of an
#: AVX-512 register, two AVX2 registers.
LANES = 8
_VEC = f"<{LANES} x double>"


def explicit_ir(kane, want_mass: bool) -> tuple:
    """``(name, text)``: the LLVM function of the explicit pass for the structure of
    ``kane`` (module docstring), from :func:`~.tracing.trace_explicit`: the legs' lines
    as vectors of :data:`LANES` lanes, leg l in lane l."""
    from offshore_crane.dynamics.tracing import trace_explicit

    trace, outputs = trace_explicit(kane, want_mass)
    index = program_index(int(kane.n_arm), np.asarray(kane.arm_prism), want_mass)
    name = f"offshore_crane_explicit_{stamp()}_{index}"
    fields = _fields(kane)
    body, known, vectors, splats = [], {}, set(), {}

    def load(value, pointer, i):
        known[value] = f"%{value}"
        body.append(f"  %{value}.p = getelementptr double, ptr {pointer}, i64 {i}")
        body.append(f"  %{value} = load double, ptr %{value}.p")
        return known[value]

    def gather(x, f, j):
        """The lanes of element j of a per-leg field f's rows (lane l: leg l)."""
        row = int(np.prod(np.shape(getattr(kane, fields[f][1]))[1:], dtype=int))
        prev = "poison"
        for lane in range(LANES):
            leg = lane if lane < 6 else 0
            loaded = load(f"{x}.{lane}", f"%c{f}", leg * row + j)
            body.append(f"  %{x}.i{lane} = insertelement {_VEC} {prev}, double {loaded}, "
                        f"i32 {lane}")
            prev = f"%{x}.i{lane}"
        known[x] = prev
        vectors.add(x)
        return prev

    def scalar(x: str) -> str:
        if x in known:
            return known[x]
        if re.fullmatch(r"[tv]\d+", x):
            return f"%{x}"
        m = re.fullmatch(r"e(\d)_(.+)", x)
        if m:
            inner = m[2]
            if inner in vectors or inner.startswith("V"):
                vec = vector(inner)
                body.append(f"  %{x} = extractelement {_VEC} {vec}, i32 {m[1]}")
                known[x] = f"%{x}"
                return known[x]
            return scalar(inner)
        m = re.fullmatch(r"k(\d+)_(\d+)", x)
        if m:
            f, i = int(m[1]), int(m[2])
            if fields[f][2] == "double":
                return f"%c{f}"
            return load(x, f"%c{f}", i)
        m = re.fullmatch(r"(q|qd|qdd)_(\d+)", x)
        if m:
            return load(x, f"%{m[1]}", int(m[2]))
        if re.fullmatch(r"g_\d", x):
            return f"%{x}"
        special = {"np.nan": "0x7FF8000000000000", "np.inf": "0x7FF0000000000000",
                   "-np.inf": "0xFFF0000000000000"}
        return special[x] if x in special else _literal(float(x))

    def is_vector(x: str) -> bool:
        return x in vectors or x.startswith("V")

    def vector(x: str) -> str:
        if x in vectors:
            return known.get(x, f"%{x}")
        m = re.fullmatch(r"V(\d+)_(\d+)", x)
        if m:
            return gather(x, int(m[1]), int(m[2]))
        if x not in splats:                   # a scalar or a literal in every lane
            value = scalar(x)
            if value.startswith("%"):
                tag = f"%splat.{len(splats)}"
                body.append(f"  {tag}.i = insertelement {_VEC} poison, double {value}, i32 0")
                body.append(f"  {tag} = shufflevector {_VEC} {tag}.i, {_VEC} poison, "
                            f"<{LANES} x i32> zeroinitializer")
                splats[x] = tag
            else:
                splats[x] = "<" + ", ".join([f"double {value}"] * LANES) + ">"
        return splats[x]

    for m, (f, col) in enumerate(trace.trig):
        body.append(f"  %s_{m} = call double @llvm.{f}.f64(double {scalar(f'q_{col}')})")
        known[f"s_{m}"] = f"%s_{m}"
    stores: dict = {}               # each output stored right after its value's line
    for out, array in outputs.items():
        for idx in np.ndindex(array.shape):
            if out == "Mm" and idx[1] > idx[0]:
                continue                                 # the lower triangle only
            x = array[idx]
            after = int(x[1:]) if re.fullmatch(r"t\d+", x) else -1
            stores.setdefault(after, []).append((out, idx, x))

    def store(out, idx, x):
        tag = f"{out}.{'.'.join(map(str, idx))}"
        if out == "Mm":
            body.append(f"  %{tag}.r = mul i64 %m_stride, {idx[0]}")
            body.append(f"  %{tag}.i = add i64 %{tag}.r, {idx[1]}")
            at = f"%{tag}.i"
        else:
            at = str(int(np.ravel_multi_index(idx, outputs[out].shape)))
        body.append(f"  %{tag}.p = getelementptr double, ptr %{out}, i64 {at}")
        body.append(f"  store double {scalar(x)}, ptr %{tag}.p")

    late = [item for item in stores.get(-1, ()) if item[2].startswith("e")]  # lanes'
    for item in stores.get(-1, ()):
        if not item[2].startswith("e"):
            store(*item)
    for n, line in enumerate(trace.lines):
        lhs, rhs = line.split(" = ", 1)
        call = re.fullmatch(r"(np\.(\w+)|abs)\((.*)\)", rhs)
        parts = rhs.split(" ")
        if call:
            fn, arity = _CALLS[call[2]] if call[2] else ("@llvm.fabs.f64", 1)
            args = call[3].split(", ")
            assert len(args) == arity, line
        elif len(parts) == 3:
            args = [parts[0], parts[2]]
        else:
            assert len(parts) == 1 and rhs.startswith("-"), line
            args = [rhs[1:]]
        if any(is_vector(x) for x in args):
            vectors.add(lhs)
            if call and fn not in _VECTOR_CALLS:
                raise ValueError(f"{line}: no vector form of {fn}")
            ops = [vector(x) for x in args]
            kind = _VEC
            fn = _VECTOR_CALLS.get(fn, fn) if call else None
        else:
            ops = [scalar(x) for x in args]
            kind = "double"
        if call:
            body.append(f"  %{lhs} = call {kind} {fn}("
                        + ", ".join(f"{kind} {o}" for o in ops) + ")")
        elif len(parts) == 3:
            body.append(f"  %{lhs} = {_BINARY[parts[1]]} {kind} {ops[0]}, {ops[1]}")
        else:
            body.append(f"  %{lhs} = fneg {kind} {ops[0]}")
        for item in stores.get(n, ()):
            store(*item)
    for item in late:
        store(*item)
    inp, out = "ptr noalias readonly", "ptr noalias"
    params = [f"{inp if kind == 'ptr' else kind} %c{f}" for f, _, kind in fields]
    params += [f"{inp} %q", f"{inp} %qd", f"{inp} %qdd", "double %g_0", "double %g_1",
               "double %g_2", f"{out} %B", f"{out} %J", f"{out} %Mm", "i64 %m_stride",
               f"{out} %store", f"{out} %diag", f"{out} %mc"]
    text = (_DECLARE + f"define void @{name}({', '.join(params)}) nounwind {{\n"
            + "\n".join(body) + "\n  ret void\n}\n")
    return name, text


def ensure(kane) -> None:
    """Load or compile the explicit pass's two programs (with and without the mass
    matrix) for the arm structure of ``kane`` into :data:`SLOTS`; nothing when they are
    there. Imports Numba's code generator.

    Raises:
        ModelError: an arm of more than :data:`MAX_ARM` joints.
    """
    n_arm, prism = int(kane.n_arm), np.asarray(kane.arm_prism)
    if n_arm > MAX_ARM:
        from offshore_crane.errors import ModelError

        raise ModelError(f"an arm of {n_arm} joints: the compiled passes handle at most "
                         f"{MAX_ARM} (offshore_crane.dynamics.native.MAX_ARM); use fewer "
                         "joints")
    wanted = [m for m in (False, True) if not SLOTS[program_index(n_arm, prism, m)]]
    if not wanted:
        return
    with _LOCK:
        register()
        for want_mass in wanted:
            index = program_index(n_arm, prism, want_mass)
            if not SLOTS[index]:
                name, text = explicit_ir(kane, want_mass)
                library = _library(name, text)
                _LIBRARIES[index] = library
                SLOTS[index] = library.get_pointer_to_function(name)


def _cache_folder():
    """Where the compiled programs live (:func:`~.lanes.package_cache`)."""
    return package_cache("native")


def _codegen():
    from numba.core.registry import cpu_target

    return cpu_target.target_context.codegen()


def _library(name: str, text: str):
    """The compiled library of the program ``text``: read from its cache file when that
    holds the object of this text for this target, else compiled and written."""
    import llvmlite
    import numba
    from numba.core.compiler_lock import global_compiler_lock

    codegen = _codegen()
    key = hashlib.sha256("\0".join([text, repr(codegen.magic_tuple()), numba.__version__,
                                    llvmlite.__version__]).encode()).hexdigest()[:24]
    path = _cache_folder() / f"{name}_{key}.bin"
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
    """Write the object (:func:`~.lanes.write_atomically`), removing the files of other
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


def caller():
    """The intrinsic ``call(index, C, q, qd, qdd, g, B, J, Mm, store, diag, mc)`` that
    calls the program in slot ``index`` (the arrays by their data pointers, C order;
    ``g`` a tuple of three floats) and returns True; False, calling nothing, when the
    slot is empty (:func:`ensure` fills it)."""
    from llvmlite import ir
    from numba.core import cgutils, types
    from numba.core.errors import TypingError
    from numba.extending import intrinsic

    symbol = register()

    def flatten(context, builder, typ, value, out):
        if isinstance(typ, types.Array):
            if typ.layout != "C":
                raise TypingError(f"the native explicit pass takes C-contiguous arrays, "
                                  f"given {typ}")
            if value is not None:
                data = context.make_array(typ)(context, builder, value).data
                out.append(data)
        elif isinstance(typ, types.BaseTuple):
            for i, t in enumerate(typ):
                flatten(context, builder, t, None if value is None
                        else builder.extract_value(value, i), out)
        elif isinstance(typ, types.Integer):
            if value is not None:
                out.append(context.cast(builder, value, typ, types.int64))
        elif isinstance(typ, types.Float):
            if value is not None:
                out.append(context.cast(builder, value, typ, types.float64))
        else:
            raise TypingError(f"the native explicit pass cannot take {typ}")

    def call_explicit_program(typingctx, index, C, q, qd, qdd, g, B, J, Mm, store, diag,
                              mc):
        args = (C, q, qd, qdd, g, B, J, Mm, store, diag, mc)
        for a in args:
            flatten(None, None, a, None, [])
        sig = types.boolean(index, *args)

        def codegen(context, builder, signature, values):
            table = builder.module.globals.get(symbol)
            if table is None:
                table = ir.GlobalVariable(builder.module, ir.IntType(64), symbol)
                table.linkage = "external"
            i = context.cast(builder, values[0], signature.args[0], types.int64)
            address = builder.load(builder.gep(table, [i]))
            loaded = builder.not_(cgutils.is_null(builder, address))
            with builder.if_then(loaded, likely=True):
                flat = []
                for k, (t, v) in enumerate(zip(signature.args[1:], values[1:])):
                    flatten(context, builder, t, v, flat)
                    if k == 7:                               # Mm's row length
                        shape = cgutils.unpack_tuple(
                            builder, context.make_array(t)(context, builder, v).shape,
                            t.ndim)
                        flat.append(shape[1])
                fnty = ir.FunctionType(ir.VoidType(), [a.type for a in flat])
                builder.call(builder.inttoptr(address, fnty.as_pointer()), flat)
            return loaded

        return sig, codegen

    call_explicit_program.__qualname__ = f"call_explicit_program_{stamp()}"
    globals()[call_explicit_program.__qualname__] = call_explicit_program
    return intrinsic(call_explicit_program)
