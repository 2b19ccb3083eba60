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
body of a loop over samples (:mod:`.lanes`), LLVM vectorises it. The robot's constants
stay in the description's arrays: the trace reads them by index (``c_40`` is
``flat[40]``), it copies no value.
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

    def line(self, expr: str) -> Symbol:
        name = f"t{len(self.lines)}"
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
    from offshore_crane.dynamics.constants import FIELDS, field_view
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
