"""Arithmetic expressions in robot description files.

A number in a description file may be written as a TOML string holding an arithmetic
expression over other fields of the same file, named by their dotted names::

    [platform.joints]
    height = "-platform.shape.length / 2"      # the sphere centres on the plate's lower face

so that one design variable drives every number that depends on it, and an override of
that variable (``--set platform.shape.length=0.06``) moves them all. Expressions are
evaluated by walking Python's syntax tree with a whitelist, never by ``eval``:

- numbers, ``+ - * / ** %``, unary ``+ -``, parentheses;
- dotted names of other fields (``legs.lower.length``, ``payload.com.z``; a component of a
  3-vector is ``.x``, ``.y``, ``.z``, an entry of a per-leg list ``.1`` ... ``.6``);
- the constant ``pi`` and the functions ``sin cos tan asin acos atan atan2 sqrt radians
  degrees abs min max`` (angles in radians, as in :mod:`math`).

Anything else (attribute calls, subscripts, comparisons, strings) is refused with a
message naming the field. The caller resolves names (:func:`evaluate` takes a
``lookup(name) -> float`` callback), which lets it detect reference cycles.
"""

from __future__ import annotations

import ast
import math
import operator
import re

#: Functions an expression may call.
FUNCTIONS = {name: getattr(math, name) for name in
             ("sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "radians",
              "degrees")}
FUNCTIONS.update(abs=abs, min=min, max=max)
#: Constants an expression may use.
CONSTANTS = {"pi": math.pi}
_BINARY = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
           ast.Div: operator.truediv, ast.Pow: operator.pow, ast.Mod: operator.mod}
_UNARY = {ast.UAdd: operator.pos, ast.USub: operator.neg}


class ExpressionError(Exception):
    """An expression cannot be parsed or evaluated (the caller adds file and field)."""


def _dotted(node) -> str | None:
    """``a.b.c`` (also with numeric parts such as ``base.joints.1.z``) or None."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        head = _dotted(node.value)
        return None if head is None else f"{head}.{node.attr}"
    return None


_DOTTED = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:\.(?:[A-Za-z_][A-Za-z0-9_]*|[0-9]+))+")


def _prepare(text: str) -> str:
    """Numeric path parts (``joints.1.z``) are not Python attributes: write ``joints._1``."""
    return _DOTTED.sub(lambda m: ".".join(p if not p.isdigit() else f"_{p}"
                                          for p in m.group(0).split(".")), text)


def names(text: str) -> list[str]:
    """Dotted field names an expression refers to (in order of appearance)."""
    out = []

    def visit(node):
        name = _dotted(node)
        if name is not None:
            if name not in CONSTANTS:
                out.append(_unprepare(name))
            return
        if isinstance(node, ast.Call):
            node = ast.Tuple(elts=node.args)         # the function's name is no field
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(_parse(text))
    return list(dict.fromkeys(out))


def _unprepare(name: str) -> str:
    return ".".join(p[1:] if p[:1] == "_" and p[1:].isdigit() else p for p in name.split("."))


def _parse(text: str):
    try:
        tree = ast.parse(_prepare(text.strip()), mode="eval").body
        ast.unparse(tree)      # walks every node: a tree too deep for evaluate fails here
        return tree
    except SyntaxError:
        raise ExpressionError(f"'{shorten(text)}' is not a number nor an arithmetic "
                              "expression (values are SI numbers without unit strings)"
                              ) from None
    except (RecursionError, MemoryError):
        raise ExpressionError(f"'{shorten(text)}' ({len(text)} characters) is nested too "
                              "deeply to evaluate: simplify it") from None


def shorten(text: str, width: int = 60) -> str:
    """``text`` cut to ``width`` characters for a one-line message."""
    return text if len(text) <= width else f"{text[:width - 3]}..."


def evaluate(text: str, lookup) -> float:
    """Value of the expression ``text``.

    Args:
        text: The expression.
        lookup: ``lookup(dotted_name) -> float`` for the fields it names; it raises
            :class:`ExpressionError` for an unknown name.

    Raises:
        ExpressionError: syntax, a construct outside the whitelist, an unknown function,
            a domain error (``sqrt(-1)``, division by zero), a non-finite result.
    """
    tree = _parse(text)

    def ev(node):
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise ExpressionError(f"'{text}': {node.value!r} is not a number")
            return float(node.value)
        if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
            return _BINARY[type(node.op)](ev(node.left), ev(node.right))
        if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
            return _UNARY[type(node.op)](ev(node.operand))
        if isinstance(node, ast.Call):
            fname = node.func.id if isinstance(node.func, ast.Name) else None
            if fname not in FUNCTIONS or node.keywords:
                raise ExpressionError(f"'{text}': unknown function "
                                      f"{fname or ast.unparse(node.func)!r}; known: "
                                      f"{', '.join(FUNCTIONS)}")
            return float(FUNCTIONS[fname](*(ev(a) for a in node.args)))
        name = _dotted(node)
        if name is not None:
            if name in CONSTANTS:
                return CONSTANTS[name]
            return float(lookup(_unprepare(name)))
        raise ExpressionError(f"'{text}': '{ast.unparse(node)}' is not allowed in an "
                              "expression (numbers, + - * / ** %, field names, pi and "
                              f"{', '.join(FUNCTIONS)} only)")

    try:
        value = ev(tree)
    except (ZeroDivisionError, ValueError, OverflowError, TypeError, RecursionError) as exc:
        raise ExpressionError(f"'{text}' cannot be evaluated: {exc}") from None
    if not math.isfinite(value):
        raise ExpressionError(f"'{text}' evaluates to {value}")
    return value
