"""One text, four backends: how the formulas are run.

The formulas (:mod:`offshore_crane.robot.kinematics.formulas`, :mod:`.formulas`,
:mod:`.sway`) are written once as plain arithmetic on 3-tuples. This module *binds* their code objects to other
namespaces, so that each backend runs exactly the same text:

- ``numpy`` — the modules as they are: every scalar of the text is an ``(n,)`` array
  (n samples at once), NumPy's ``sqrt``, ``sin``, ``cos``, ``arctan2``;
- ``python`` — Python floats with :mod:`math`: one sample without NumPy's per-call cost
  (about 1 µs a call), for a handful of samples when Numba is not loaded;
- ``mpmath`` — ``mpf`` numbers at :data:`MP_DPS` digits: the extended-precision
  reference that measures the float64 paths' rounding (:mod:`.extended`);
- ``numba`` — every function wrapped in ``numba.njit`` (:mod:`.compiled`).

Binding copies each module's namespace, replaces the math functions, re-creates every
function of the formula modules from its code object in that namespace and points the
names the modules import from each other at the re-created functions.
"""

from __future__ import annotations

import hashlib
import inspect
import math
import types

from offshore_crane.robot.kinematics import formulas as _kinematics
from offshore_crane.dynamics import formulas as _dynamics
from offshore_crane.dynamics import sway as _sway

#: The formula modules, in import order.
MODULES = (_kinematics, _dynamics, _sway)
#: Decimal digits of the extended-precision reference (~133 bits, rounding ~1e-40).
MP_DPS = 40


def _functions(module) -> dict:
    return {name: f for name, f in vars(module).items()
            if isinstance(f, types.FunctionType) and f.__module__ == module.__name__}


def bind(math_functions: dict, wrap=lambda f: f) -> types.SimpleNamespace:
    """The formula functions re-bound to ``math_functions`` (``{"sqrt": ..., ...}``).

    Args:
        math_functions: Replacements for the names ``sqrt``, ``sin``, ``cos``,
            ``arctan2`` of the formula modules' globals.
        wrap: Applied to every re-created function (``numba.njit`` for the compiled
            backend); the wrapped objects are what the other functions call.

    Returns:
        A namespace with every formula function (and constant) by name.
    """
    namespaces = {m.__name__: {**vars(m), **math_functions} for m in MODULES}
    rebound = {}
    for m in MODULES:
        ns = namespaces[m.__name__]
        for name, f in _functions(m).items():
            g = types.FunctionType(f.__code__, ns, name, f.__defaults__, f.__closure__)
            g.__qualname__, g.__module__, g.__doc__ = f.__qualname__, f.__module__, f.__doc__
            rebound[f] = wrap(g)
    out = {}
    for ns in namespaces.values():
        for key, value in list(ns.items()):
            if isinstance(value, types.FunctionType) and value in rebound:
                ns[key] = rebound[value]
        out.update({k: v for k, v in ns.items() if not k.startswith("__")})
    return types.SimpleNamespace(**out)


#: Modules whose code the compiled kernels embed besides the formulas: the RK4 tableau,
#: the views without an owner, the calls by address (read, not imported:
#: importing them would import Numba).
INLINED = ("offshore_crane.dynamics.integrator", "offshore_crane.dynamics.views",
           "offshore_crane.kernel_calls")


def source_stamp() -> str:
    """A hash of the source of the formula modules and of :data:`INLINED`: compiled code
    that inlines them keys its disk cache on it, so that an edit rebuilds it."""
    import importlib.util
    from pathlib import Path

    h = hashlib.sha256()
    for m in MODULES:
        h.update(inspect.getsource(m).encode())
    for name in INLINED:
        h.update(Path(importlib.util.find_spec(name).origin).read_bytes())
    return h.hexdigest()[:16]


#: The vectorised backend: the modules themselves.
NUMPY = types.SimpleNamespace(**{**vars(_kinematics), **vars(_dynamics), **vars(_sway)})
#: One sample in Python floats.
PYTHON = bind({"sqrt": math.sqrt, "sin": math.sin, "cos": math.cos, "arctan2": math.atan2})

_MPMATH: list = []


def mpmath_backend() -> types.SimpleNamespace:
    """The formulas in mpmath (bound on first use; mpmath is a test/study dependency)."""
    if not _MPMATH:
        from offshore_crane.errors import require

        mp = require("mpmath", "mpmath", "The extended-precision reference")
        _MPMATH.append(bind({"sqrt": mp.sqrt, "sin": mp.sin, "cos": mp.cos,
                             "arctan2": mp.atan2}))
    return _MPMATH[0]
