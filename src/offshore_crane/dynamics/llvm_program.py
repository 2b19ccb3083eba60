"""A traced Kane pass written as LLVM's own text (:mod:`.native` compiles it).

Each line of the trace (:func:`~.tracing.trace_pass`) becomes one instruction: ``fadd``,
``fsub``, ``fmul``, ``fdiv``, ``fneg`` with no fast-math flag, ``llvm.sqrt``,
``llvm.fabs``, ``llvm.sin``, ``llvm.cos`` and ``atan2`` (what Numba emits for the same
operations of a float), in the trace's order; the legs' lines (``v…``) on vectors of
:data:`LANES` lanes, leg l in lane l, a leg constant gathered from its six rows, a value
common to the legs splatted, a leg's value extracted where the formulas use it. Every
output is stored right after the line that makes it.
"""

from __future__ import annotations

import re
import struct

import numpy as np

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


def _parse(line: str) -> tuple[str, str, list]:
    """``(name, operation, operands)`` of a trace's line: the operation a call's function
    (``"sqrt"``, ``"abs"``, ``"sin"``, ``"cos"``, ``"arctan2"``), a binary operator (``"+"``,
    ``"-"``, ``"*"``, ``"/"``) or ``"neg"``."""
    lhs, rhs = line.split(" = ", 1)
    call = re.fullmatch(r"(?:np\.)?(\w+)\((.*)\)", rhs)
    if call:
        return lhs, call[1], call[2].split(", ")
    parts = rhs.split(" ")
    if len(parts) == 3:
        return lhs, parts[1], [parts[0], parts[2]]
    assert len(parts) == 1 and rhs.startswith("-"), line
    return lhs, "neg", [rhs[1:]]


#: The trace's non-finite literals (NumPy's names) as LLVM's doubles.
_SPECIAL = {"np.nan": "0x7FF8000000000000", "np.inf": "0x7FF0000000000000",
            "-np.inf": "0xFFF0000000000000"}


def _constant(x: str) -> str:
    """A literal of the trace in LLVM's text: its bits exactly (:func:`_literal`)."""
    return _SPECIAL[x] if x in _SPECIAL else _literal(float(x))


def _splat(body: list, tag: str, value: str, lanes: int) -> str:
    """``value`` in each of ``lanes`` lanes: a constant vector for a constant, else the
    register ``tag`` (its insertelement and shufflevector appended to ``body``)."""
    vec = f"<{lanes} x double>"
    if not value.startswith("%"):
        return "<" + ", ".join([f"double {value}"] * lanes) + ">"
    body.append(f"  {tag}.i = insertelement {vec} poison, double {value}, i32 0")
    body.append(f"  {tag} = shufflevector {vec} {tag}.i, {vec} poison, "
                f"<{lanes} x i32> zeroinitializer")
    return tag


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


def program_ir(kind: str, kane, variant: int, name: str) -> str:
    """The LLVM function ``name`` of pass ``kind``'s ``variant`` for the arm structure
    of ``kane`` (:mod:`.native`), from :func:`~.tracing.trace_pass`: the
    legs' lines as vectors of :data:`LANES` lanes, leg l in lane l. Its parameters: the
    constants' fields, then the pass's arguments as :func:`caller` passes them (an array
    by its data pointer, followed by its row length when it has two axes; a tuple by its
    elements)."""
    from offshore_crane.dynamics.tracing import trace_pass

    trace, outputs = trace_pass(kind, kane, variant)
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
        m = re.fullmatch(r"(q|qd|qdd|qz)_(\d+)", x)
        if m:
            return load(x, f"%{m[1]}", int(m[2]))
        if re.fullmatch(r"(g|pull|pz|at)_\d", x):
            return f"%{x}"
        return _constant(x)

    def is_vector(x: str) -> bool:
        return x in vectors or x.startswith("V")

    def vector(x: str) -> str:
        if x in vectors:
            return known.get(x, f"%{x}")
        m = re.fullmatch(r"V(\d+)_(\d+)", x)
        if m:
            return gather(x, int(m[1]), int(m[2]))
        if x not in splats:                   # a scalar or a literal in every lane
            splats[x] = _splat(body, f"%splat.{len(splats)}", scalar(x), LANES)
        return splats[x]

    for m, (f, col) in enumerate(trace.trig):
        body.append(f"  %s_{m} = call double @llvm.{f}.f64(double {scalar(f'q_{col}')})")
        known[f"s_{m}"] = f"%s_{m}"
    stores: dict = {}               # each output stored right after its value's line
    for out, array in outputs.items():
        for idx in np.ndindex(array.shape):
            x = array[idx]
            if x is None or (out == "Mm" and idx[1] > idx[0]):
                continue                # left as it was; the mass matrix's lower triangle
            line = re.fullmatch(r"(?:e\d_)?[tv](\d+)", x)    # a line's value, or a lane of it
            stores.setdefault(int(line[1]) if line else -1, []).append((out, idx, x))

    def store(out, idx, x):
        tag = f"{out}.{'.'.join(map(str, idx))}"
        if len(idx) == 2:
            body.append(f"  %{tag}.r = mul i64 %{out}.stride, {idx[0]}")
            body.append(f"  %{tag}.i = add i64 %{tag}.r, {idx[1]}")
            at = f"%{tag}.i"
        else:
            at = str(idx[0])
        body.append(f"  %{tag}.p = getelementptr double, ptr %{out}, i64 {at}")
        body.append(f"  store double {scalar(x)}, ptr %{tag}.p")

    for item in stores.get(-1, ()):              # inputs, constants and literals
        store(*item)
    for n, line in enumerate(trace.lines):
        lhs, op, args = _parse(line)
        call = op not in _BINARY and op != "neg"
        if call:
            fn, arity = _CALLS[op] if op != "abs" else ("@llvm.fabs.f64", 1)
            assert len(args) == arity, line
        if any(is_vector(x) for x in args):
            vectors.add(lhs)
            if call and fn not in _VECTOR_CALLS:
                raise ValueError(f"{line}: no vector form of {fn}")
            ops = [vector(x) for x in args]
            ty = _VEC
            fn = _VECTOR_CALLS.get(fn, fn) if call else None
        else:
            ops = [scalar(x) for x in args]
            ty = "double"
        if call:
            body.append(f"  %{lhs} = call {ty} {fn}("
                        + ", ".join(f"{ty} {o}" for o in ops) + ")")
        elif op == "neg":
            body.append(f"  %{lhs} = fneg {ty} {ops[0]}")
        else:
            body.append(f"  %{lhs} = {_BINARY[op]} {ty} {ops[0]}, {ops[1]}")
        for item in stores.get(n, ()):
            store(*item)
    inp = "ptr noalias readonly"
    params = [f"{inp if ty == 'ptr' else ty} %c{f}" for f, _, ty in fields]
    params += [f"{inp} %q", f"{inp} %qd", f"{inp} %qdd"]
    params += ["double %g_0", "double %g_1", "double %g_2"]
    if kind.startswith("kane_pull"):
        forces = ("pull", "pz", "at") if kind == "kane_pull2" else ("pull", "at")
        params += [f"double %{v}_{i}" for v in forces for i in range(3)]
    for out, array in outputs.items():
        params.append(f"ptr noalias %{out}")
        if array.ndim == 2:
            params.append(f"i64 %{out}.stride")
    text = (_DECLARE + f"define void @{name}({', '.join(params)}) nounwind {{\n"
            + "\n".join(body) + "\n  ret void\n}\n")
    return text


def block_ir(trace, name: str, lanes: int) -> str:
    """The LLVM function ``name(ptr ib, ptr ob, ptr flat, double g0, double g1, double
    g2)`` of a fused pass traced for blocks (:func:`~.tracing.trace_kane` with inputs
    named ``in_<row>`` and constants ``c_<i>``, :mod:`.lanes`): every line on vectors of
    ``lanes`` samples (L), sample k in lane k; input row r read from ``ib[r L : (r + 1)
    L]``, constant i from ``flat[i]`` (splat), output r written to ``ob[r L : (r + 1)
    L]`` right after the line that makes it. The instructions are those Numba emits for
    the same operations of a float (no fast-math flag), so each lane gives the
    per-sample formulas' numbers bit for bit."""
    body, known = [], {}
    vec = f"<{lanes} x double>"

    def operand(x: str) -> str:
        if x in known:
            return known[x]
        if re.fullmatch(r"t\d+", x):
            return f"%{x}"
        m = re.fullmatch(r"in_(\d+)", x)
        if m:
            body.append(f"  %{x}.p = getelementptr double, ptr %ib, i64 {int(m[1]) * lanes}")
            body.append(f"  %{x} = load {vec}, ptr %{x}.p, align 8")
            known[x] = f"%{x}"
            return known[x]
        m = re.fullmatch(r"c_(\d+)", x)
        if m:
            body.append(f"  %{x}.p = getelementptr double, ptr %flat, i64 {m[1]}")
            body.append(f"  %{x}.s = load double, ptr %{x}.p")
            value = f"%{x}.s"
        elif re.fullmatch(r"g[012]", x):
            value = f"%{x}"
        else:
            value = _constant(x)
        known[x] = _splat(body, f"%splat.{len(known)}", value, lanes)
        return known[x]

    stores: dict = {}
    for r, x in enumerate(trace.outputs):
        line = re.fullmatch(r"t(\d+)", x)
        stores.setdefault(int(line[1]) if line else -1, []).append((r, x))

    def store(r, x):
        body.append(f"  %o{r}.p = getelementptr double, ptr %ob, i64 {r * lanes}")
        body.append(f"  store {vec} {operand(x)}, ptr %o{r}.p, align 8")

    for item in stores.get(-1, ()):              # inputs, constants and literals
        store(*item)
    for n, line in enumerate(trace.lines):
        lhs, op, args = _parse(line)
        ops = [operand(x) for x in args]
        if op in _BINARY:
            body.append(f"  %{lhs} = {_BINARY[op]} {vec} {ops[0]}, {ops[1]}")
        elif op == "neg":
            body.append(f"  %{lhs} = fneg {vec} {ops[0]}")
        elif op in ("sqrt", "abs") and len(ops) == 1:
            fn = f"@llvm.{'fabs' if op == 'abs' else op}.v{lanes}f64"
            body.append(f"  %{lhs} = call {vec} {fn}({vec} {ops[0]})")
        else:
            raise ValueError(f"{line}: no vector form of {op}")
        for item in stores.get(n, ()):
            store(*item)
    inp = "ptr noalias readonly"
    params = (f"{inp} %ib, ptr noalias %ob, {inp} %flat, double %g0, double %g1, "
              "double %g2")
    declare = "".join(f"declare {vec} @llvm.{f}.v{lanes}f64({vec})\n" for f in ("sqrt", "fabs"))
    return (declare + f"define void @{name}({params}) nounwind {{\n" + "\n".join(body)
            + "\n  ret void\n}\n")
