"""How the figures read: a target met or not, short scientific notation, thousands apart."""

from __future__ import annotations


def _met(ok: bool) -> str:
    return "met" if ok else "NOT met"


def _sci(x: float) -> str:
    """``6.4e-5``: two digits, no padded exponent."""
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def _count(n: int) -> str:
    """``241 496``: thousands apart by a space."""
    return f"{n:,}".replace(",", " ")
