"""A fifth backend of the one text: numbers that write down the operations done on them.

:func:`trace_kane` runs the fused Kane formulas (:func:`.formulas.kane_sample`, the same
code objects every backend runs, bound by :func:`.backends.bind`) on :class:`Symbol`\\ s:
each ``+ − × ÷``, ``sqrt``, ``sin``, ``cos``, ``atan2`` between them appends one line of
Python (``t12 = t7 * c_40``) to the trace, in the order the formulas do them. The lines
are a straight-line program for one sample, with no branch: the branches of the text are
decided while tracing, by the robot's structure (the arm's joint count and types, the
leg model), which is fixed for a robot; a branch on a *value* cannot be decided and
stops the trace (:class:`TraceError`; the caller keeps the per-sample kernel).

Run as it is written, the program does the same IEEE operations in the same order as the
compiled per-sample formulas, so it gives the same numbers bit for bit; written as the
body of a loop over samples (:mod:`.lanes`), LLVM vectorises it; translated into LLVM's
own text (:mod:`.native`), it compiles in a second where Numba's front end takes twenty.
The robot's constants stay in the description's arrays: the trace reads them by index
(``c_40`` is ``flat[40]``, or ``k3_5`` element 5 of the constants' field 3), it copies no
value.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import OffshoreCraneError


class TraceError(OffshoreCraneError):
    """The formulas branched on a value, which a straight-line program cannot do."""


class Symbol:
    """A number of the traced program: its expression (a name, an input or a literal)."""

    __slots__ = ("expr", "column")

    def __init__(self, expr: str, column: int | None = None):
        self.expr = expr
        self.column = column        # the input's column when it is one, else None

    def _bool(self, *_):
        raise TraceError(f"the formulas compare or test the value {self.expr}: a branch "
                         "on a value cannot be traced")

    __bool__ = __lt__ = __le__ = __gt__ = __ge__ = __eq__ = __ne__ = _bool
    __hash__ = None

    def __neg__(self):
        return _TRACE.line(f"-{self.expr}")

    def __pos__(self):
        return self

    def __abs__(self):
        return _TRACE.line(f"abs({self.expr})")


def _operand(x) -> str:
    if isinstance(x, Symbol):
        return x.expr
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.integer,
                                                              np.floating)):
        raise TraceError(f"cannot trace an operation with {type(x).__name__} {x!r}")
    x = float(x)
    if np.isnan(x):
        return "np.nan"
    if np.isinf(x):
        return "np.inf" if x > 0 else "-np.inf"
    return repr(x)


def _binary(op: str):
    def forward(a, b):
        return _TRACE.line(f"{_operand(a)} {op} {_operand(b)}")

    def reflected(a, b):
        return _TRACE.line(f"{_operand(b)} {op} {_operand(a)}")

    return forward, reflected


for _name, _op in (("add", "+"), ("sub", "-"), ("mul", "*"), ("truediv", "/")):
    _f, _r = _binary(_op)
    setattr(Symbol, f"__{_name}__", _f)
    setattr(Symbol, f"__r{_name}__", _r)


@dataclass
class Trace:
    """What :func:`trace_kane` wrote: ``lines`` (one assignment each), ``trig`` (the
    ``(function, input column)`` of each trigonometric call of an input, read from
    ``trig_input(m)`` in the lines: they are computed before the loop that vectorises,
    as library calls do not) and ``outputs`` (expressions)."""

    lines: list
    trig: list
    outputs: list
    trig_input: object = None
    #: Lines traced now are lanes' (named ``v…``, :func:`trace_pass`).
    lane: bool = False

    def line(self, expr: str) -> Symbol:
        name = f"{'v' if self.lane else 't'}{len(self.lines)}"
        self.lines.append(f"{name} = {expr}")
        return Symbol(name)

    def function(self, name: str):
        def call(*args):
            if len(args) == 1 and isinstance(args[0], Symbol) and args[0].column is not None \
                    and name in ("sin", "cos"):
                key = (name, args[0].column)
                if key not in self.trig:
                    self.trig.append(key)
                return Symbol(self.trig_input(self.trig.index(key)))
            return self.line(f"np.{name}({', '.join(_operand(a) for a in args)})")
        return call


_TRACE = Trace([], [], [])


def trace_kane(arrays, leg_model: int, inputs, trig_input, flat_name,
               cable: bool = False) -> Trace:
    """The fused Kane formulas of one sample with every leg force wanted (platform in
    motion), traced for the robot of ``arrays``
    (:class:`~offshore_crane.dynamics.constants.RobotArrays`) and ``leg_model``.

    Args:
        inputs: ``inputs(column)``: the expression of input column ``0 .. 3 n − 1``
            (q, q̇, q̈ of the n = 6 + n_arm coordinates, each ``n`` columns).
        trig_input: ``trig_input(m)``: the expression of the m-th trigonometric value.
        flat_name: ``flat_name(i)``: the expression of the constant ``flat[i]``.
        cable: The arm continued by the two sway joints and the payload
            (:func:`~offshore_crane.dynamics.constants.cable_arrays`): the cable's pull
            and tension are traced too (:func:`~offshore_crane.dynamics.sway.cable_force`).

    Returns:
        A :class:`Trace` whose ``outputs`` are, in order, the arm's rows (n_arm), the
        Stewart matrix A by rows (36), its right-hand side (6), the legs' diagnostics
        by rows (7 x 6) (:func:`~offshore_crane.dynamics.formulas.kane_sample`'s
        workspaces) and with ``cable`` the pull (3) [N] and the tension [N].

    Raises:
        TraceError: the formulas branched on a value.
    """
    from offshore_crane.dynamics.backends import bind
    from offshore_crane.dynamics.layout import FIELDS, field_view
    from offshore_crane.dynamics.formulas import DIAG_ROWS, STORE_WIDTH, KaneConstants

    global _TRACE
    trace = _TRACE = Trace([], [], [], trig_input)
    try:
        F = bind({name: trace.function(name) for name in ("sqrt", "sin", "cos", "arctan2")})
        real = arrays.kane
        flat = np.array([Symbol(flat_name(i)) for i in range(len(arrays.flat))],
                        dtype=object)
        fields = {name: field_view(flat, o, np.shape(getattr(real, name)), lambda x: x)
                  for name, (o, *_) in zip(FIELDS, arrays.layout)
                  if name in KaneConstants._fields}
        C = KaneConstants(**fields, n_arm=real.n_arm, arm_prism=real.arm_prism)
        n = 6 + real.n_arm
        q, qd, qdd = ([Symbol(inputs(n * v + j), n * v + j) for j in range(n)]
                      for v in range(3))
        g = (Symbol("g0"), Symbol("g1"), Symbol("g2"))

        def zeros(*shape):
            out = np.empty(shape, dtype=object)
            out.fill(0.0)
            return out

        na = C.n_arm
        rows, A, rhs = zeros(max(na, 1)), zeros(6, 6), zeros(6)
        diag, store = zeros(DIAG_ROWS, 6), zeros(max(na, 1), STORE_WIDTH)
        F.kane_sample(C, q, qd, qdd, g, False, leg_model, True, rows, A, rhs, diag, store)
        extra = ()
        if cable:
            f, tension = F.cable_force(C, store)
            extra = (*f, tension)
        trace.outputs = [_operand(x) for x in (*rows[:na], *A.ravel(), *rhs, *diag.ravel(),
                                               *extra)]
    finally:
        _TRACE = Trace([], [], [])
    return trace


#: The passes :func:`trace_pass` traces, and how many variants each has: the explicit
#: pass with or without the mass matrix (``want_mass``), the fused pass for each
#: ``static`` x ``leg_model`` x ``want_legs`` (:func:`kane_variant`), the pass with a pull,
#: and that pass twice at one state (:data:`PULL2`).
VARIANTS = {"explicit": 2, "kane": 12, "kane_pull": 1, "kane_pull2": 1}
#: The two passes with a pull of ``"kane_pull2"``, by the names of their accelerations
#: and pulls: at ``qdd`` with ``pull``, at ``qdd`` with ``pz`` (the elastic plant's law
#: at its commanded accelerations, and, less the second, its pull's share of X; ``pz``
#: the pull times 0). One program: what the two share (all but the pull's terms) is
#: computed once, each pass's numbers bit for bit its own. (The share was the pass at
#: rest less the same without the pull, a third pass: X is affine in the pull, the
#: share the same at any accelerations up to round-off, measured in
#: ``tests/dynamics/test_elastic_plant.py``; the law's program 1.14 -> 0.93 us.)
PULL2 = (("qdd", "pull"), ("qdd", "pz"))


def kane_variant(static, leg_model, want_legs):
    """The fused pass's variant number of its flags (``leg_model`` 0, 1 or 2)."""
    return (6 if static else 0) + 2 * leg_model + (1 if want_legs else 0)


class _Unwritten:
    """What a pass's output holds until the pass writes it (any use of it stops the
    trace: the formulas read it before writing it)."""

    def __repr__(self):
        return "unwritten"


UNWRITTEN = _Unwritten()


def _unwritten(*shape):
    out = np.empty(shape, dtype=object)
    out.fill(UNWRITTEN)
    return out


def _zeros(*shape):
    out = np.empty(shape, dtype=object)
    out.fill(0.0)
    return out


def trace_pass(kind: str, kane, variant: int) -> tuple:
    """One sample of a Kane pass, traced for the arm structure of ``kane`` (a
    :class:`~offshore_crane.dynamics.formulas.KaneConstants`: its joint count and types;
    no value of it is read): ``kind`` ``"explicit"``
    (:func:`~offshore_crane.dynamics.formulas.explicit_sample`, ``variant`` =
    ``want_mass``), ``"kane"`` (:func:`~offshore_crane.dynamics.formulas.kane_sample`,
    ``variant`` = :func:`kane_variant` of its flags) or ``"kane_pull"``
    (:func:`~offshore_crane.dynamics.formulas.kane_sample_pull`).

    Names in the lines: ``k{f}_{i}`` element ``i`` (C order) of the constants' field
    ``f`` (its index in ``KaneConstants._fields``; a scalar field has ``i = 0``),
    ``q_{j}``, ``qd_{j}``, ``qdd_{j}`` the inputs (n = 6 + n_arm each), ``g_{i}``
    gravity [m/s²], ``pull_{i}`` [N] and ``at_{i}`` [m] the pull and its point,
    ``s_{m}`` the m-th trigonometric value of an input (``trace.trig``).

    The six legs (:func:`~offshore_crane.dynamics.formulas.explicit_leg`,
    :func:`~offshore_crane.dynamics.formulas.stewart_leg`: each depends on no other leg)
    are traced once, as *lanes*: lines named ``v…`` whose operands may be ``V{f}_{j}``,
    element ``j`` of row l of a per-leg field ``f``, leg l being lane l; ``e{l}_{x}`` is
    lane l of the value ``x`` (``x`` itself when it is no lane's). What the legs give is
    then added in leg order, as the formulas do.

    Returns:
        ``(trace, outputs)``: ``outputs`` maps each array the pass is given to write
        (explicit: ``B`` (n,), ``J`` (6, 6), ``Mm`` (n, n: all ``None`` without
        ``want_mass``), ``store``
        (max(n_arm, 1), 27), ``diag`` (7, 6), ``mc`` (1, 3); fused: ``rows``
        (max(n_arm, 1),), ``A`` (6, 6), ``rhs`` (6,), ``diag``, ``store``) to an object
        array of operand texts, ``None`` where the pass leaves the element as it was
        (the explicit pass adds to ``B`` and ``Mm``, which the caller zeroes; ``Vw, Ww,
        Vs`` are its scratch, all zero before it).

    Raises:
        TraceError: the formulas branched on a value, or read an output before
            writing it.
    """
    from offshore_crane.dynamics.backends import bind
    from offshore_crane.dynamics.formulas import DIAG_ROWS, STORE_WIDTH, KaneConstants

    global _TRACE
    trace = _TRACE = Trace([], [], [], lambda m: f"s_{m}")
    try:
        F = bind({name: trace.function(name) for name in ("sqrt", "sin", "cos", "arctan2")})
        fields = {}
        for f, name in enumerate(KaneConstants._fields):
            if name in ("n_arm", "arm_prism"):          # the structure: decided here
                continue
            shape = np.shape(getattr(kane, name))
            if not shape:
                fields[name] = Symbol(f"k{f}_0")
                continue
            out = np.empty(shape, dtype=object)
            out.ravel()[:] = [Symbol(f"k{f}_{i}") for i in range(out.size)]
            fields[name] = out
        C = KaneConstants(**fields, n_arm=int(kane.n_arm),
                          arm_prism=np.asarray(kane.arm_prism, dtype=bool))
        n, r = 6 + C.n_arm, max(C.n_arm, 1)
        q = [Symbol(f"q_{j}", j) for j in range(n)]
        qd, qdd = ([Symbol(f"{v}_{j}") for j in range(n)] for v in ("qd", "qdd"))
        g, pull, at = (tuple(Symbol(f"{v}_{i}") for i in range(3))
                       for v in ("g", "pull", "at"))
        ns = F.explicit_sample.__globals__           # the formulas' bound namespace
        ns["explicit_leg"] = _legs_as_lanes(trace, F, C, "explicit_leg",
                                            {13: "row", 14: "all", 15: "all", 16: "column"})
        ns["stewart_leg"] = _legs_as_lanes(trace, F, C, "stewart_leg",
                                           {12: "column", 13: "column"})
        if kind == "explicit":
            work = {"B": _zeros(n), "J": _unwritten(6, 6), "Mm": _zeros(n, n),
                    "store": _unwritten(r, STORE_WIDTH), "diag": _unwritten(DIAG_ROWS, 6),
                    "mc": _unwritten(1, 3)}
            F.explicit_sample(C, q, qd, qdd, g, bool(variant), work["B"], work["J"],
                              work["Mm"], work["store"], *(_zeros(n, 3) for _ in range(3)),
                              work["diag"], work["mc"])
            if not variant:                     # not touched: nothing is stored into it
                work["Mm"] = _unwritten(n, n)
        else:
            work = {"rows": _unwritten(r), "A": _unwritten(6, 6), "rhs": _unwritten(6),
                    "diag": _unwritten(DIAG_ROWS, 6), "store": _unwritten(r, STORE_WIDTH)}
            if kind == "kane":
                F.kane_sample(C, q, qd, qdd, g, variant >= 6, (variant % 6) // 2,
                              variant % 2 == 1, *work.values())
            elif kind == "kane_pull":
                F.kane_sample_pull(C, q, qd, qdd, g, pull, at, *work.values())
            else:
                work = _pull2(trace, F, C, n, r, q, qd, g, at, ns)
    finally:
        _TRACE = Trace([], [], [])

    def text(x):
        return None if x is UNWRITTEN else _operand(x)

    outputs = {name: np.vectorize(text, otypes=[object])(a) for name, a in work.items()}
    return trace, outputs


def _pull2(trace: Trace, F, C, n: int, r: int, q, qd, g, at, ns) -> dict:
    """The outputs of ``"kane_pull2"`` (:data:`PULL2`): ``rows`` (2, r) and ``rhs`` (2,
    6), pass k in row k; ``A``, ``diag`` and ``store`` of the last pass (the Stewart
    matrix is the same for both). Each pass gets stand-ins of its own for the per-leg
    formulas (a stand-in replays its first call's legs)."""
    from offshore_crane.dynamics.formulas import DIAG_ROWS, STORE_WIDTH

    rows, rhs = _unwritten(len(PULL2), r), _unwritten(len(PULL2), 6)
    for k, (acc, force) in enumerate(PULL2):
        ns["explicit_leg"] = _legs_as_lanes(trace, F, C, "explicit_leg",
                                            {13: "row", 14: "all", 15: "all", 16: "column"})
        ns["stewart_leg"] = _legs_as_lanes(trace, F, C, "stewart_leg",
                                           {12: "column", 13: "column"})
        work = {"rows": _unwritten(r), "A": _unwritten(6, 6), "rhs": _unwritten(6),
                "diag": _unwritten(DIAG_ROWS, 6), "store": _unwritten(r, STORE_WIDTH)}
        qdd = [Symbol(f"{acc}_{j}") for j in range(n)]
        pull = tuple(Symbol(f"{force}_{i}") for i in range(3))
        F.kane_sample_pull(C, q, qd, qdd, g, pull, at, *work.values())
        rows[k], rhs[k] = work["rows"], work["rhs"]
    return {"rows": rows, "A": work["A"], "rhs": rhs, "diag": work["diag"],
            "store": work["store"]}


#: The constants' per-leg fields (first axis: the six legs), by their names' prefixes.
PER_LEG = ("leg_", "lo_", "up_", "thin_")


def _legs_as_lanes(trace: Trace, F, C, name: str, writes: dict):
    """The stand-in for the per-leg formula ``name`` while :func:`trace_pass` traces:
    its first call traces leg 0 with lane constants (``V{f}_{j}``); each call returns
    leg l's lanes (``e{l}_…``) where the real function returns leg l's values, and
    writes them where it writes: ``writes`` maps the index of each array argument to
    ``"row"`` (the function writes row l), ``"column"`` (column l) or ``"all"``."""
    from offshore_crane.dynamics.formulas import KaneConstants

    lanes = {}
    for f, field in enumerate(KaneConstants._fields):
        if field.startswith(PER_LEG):
            real = np.asarray(getattr(C, field))
            out = np.empty(real.shape, dtype=object)           # rows 1..5: not read
            if real.ndim == 1:
                out[0] = Symbol(f"V{f}_0")
            else:
                out[0].ravel()[:] = [Symbol(f"V{f}_{j}") for j in range(out[0].size)]
            lanes[field] = out
    lane_C = C._replace(**lanes)
    traced: list = []

    def lane(x, l):
        if isinstance(x, Symbol):
            return Symbol(f"e{l}_{x.expr}")
        if isinstance(x, tuple):
            return tuple(lane(y, l) for y in x)
        return x

    def per_leg(*args):
        l = args[1]
        if not traced:
            mine = list(args)
            mine[0], mine[1] = lane_C, 0
            for i, how in writes.items():
                mine[i] = (_zeros if how == "all" else _unwritten)(*np.shape(args[i]))
            trace.lane = True
            try:
                out = getattr(F, name)(*mine)
            finally:
                trace.lane = False
            traced.append((out, mine))
        out, mine = traced[0]
        for i, how in writes.items():
            theirs, dest = mine[i], args[i]
            for idx in np.ndindex(theirs.shape):
                x = theirs[idx]
                if x is UNWRITTEN:
                    continue
                at = ((l,) + idx[1:] if how == "row" else idx[:-1] + (l,) if how == "column"
                      else idx)
                dest[at] = lane(x, l)
        return lane(out, l)

    return per_leg
