"""Compiled calls of a big compiled function through its address, with nothing linked.

Numba links a callee's code into every compiled function that calls it (the callee's
library joins the caller's module) and has LLVM optimise it again there: a big pass
called by many kernels (the explicit Kane pass: forward dynamics, every plant of every
simulation loop) is compiled again inside each of them, seconds each (measured: the rigid
robot's loop 26.7 s of a first ``simulate``, against 17.5 s when the pass was not inlined
into it). An :class:`Entry` is such a function called by address instead:

- ``entry.call(*args)``, in compiled code, calls the compiled function with Numba's own
  calling convention (the same arguments, the same errors), reading its address from
  the entry's *slot*, an ``int64`` the JIT knows by a symbol of the entry's name
  (registered when the entry is made, before any caller can be compiled or loaded);
  the arguments must have exactly the entry's types, but numbers that convert without
  loss (checked when the caller compiles: an error names the argument). The callee's
  code stays in its own library, compiled and cached once; a caller compiles in the time
  of its own code.
- :meth:`Entry.ensure` fills the slot: the function compiled for the entry's types, or
  loaded from the disk cache. :func:`offshore_crane.kernel_cache.njit` does it, before a
  kernel is compiled or loaded, for every entry that kernel's Python text reaches
  (:func:`reached`: its globals and closure, through the kernels it calls), so a cached
  caller never runs before its callee is loaded; a call through an empty slot raises
  ``RuntimeError`` instead of jumping to address 0.

Nothing here imports Numba until an entry is made.
"""

from __future__ import annotations

import hashlib
import types as _pytypes

import numpy as np

#: Every entry made, by the id of its ``call`` (what compiled code references).
_BY_CALL: dict = {}
#: Per Python function, the entries its text reaches (:func:`reached`).
_REACHED: dict = {}


class Entry:
    """A compiled function called by address (module docstring).

    Args:
        name: Its name, in the slot's symbol and in messages.
        dispatcher: A function returning the compiled function (a Numba dispatcher that
            caches); called once, by :meth:`ensure`.
        argtypes: Its Numba argument types, exactly.
        restype: Its Numba return type.
        stamp: What identifies its text (a hash of the formulas): part of the symbol, so
            that a caller compiled against one text never calls another.
    """

    def __init__(self, name: str, dispatcher, argtypes: tuple, restype, stamp: str):
        from llvmlite import binding

        self.name, self.argtypes, self.restype = name, tuple(argtypes), restype
        self._dispatcher = dispatcher
        #: The module that makes the entry (where a helper process finds it by name).
        self.module = getattr(dispatcher, "__module__", None)
        digest = hashlib.sha1(f"{stamp}|{self.argtypes}|{restype}".encode()).hexdigest()[:16]
        self.symbol = f"offshore_crane_slot_{name}_{digest}"
        self.slot = np.zeros(1, dtype=np.int64)     # the address, once ensured
        binding.add_symbol(self.symbol, self.slot.ctypes.data)
        self.call = _caller(self)
        _BY_CALL[id(self.call)] = self

    @classmethod
    def typed(cls, name: str, dispatcher, signature: str, stamp: str, **named) -> "Entry":
        """An entry whose types are a signature's text: Numba's names
        (``"float64(float64[::1], int64)"``), the short names of :func:`short_names`
        (``"none(*PACKED, V, T3)"``) and the types given as keywords (``C=...``).
        The one way entries declare their types."""
        from numba.core import sigutils

        scope = {**short_names(), **named}
        sig = eval(signature, {"__builtins__": {}}, scope)      # noqa: S307 (our text)
        argtypes, restype = sigutils.normalize_signature(sig)
        return cls(name, dispatcher, argtypes, restype, stamp)

    def kernel(self) -> str:
        """The compiled function's name in the compile-time record
        (:func:`offshore_crane.compile_times.kernel_name`)."""
        from offshore_crane.compile_times import kernel_name

        return kernel_name(self._dispatcher().py_func)

    def cached(self) -> bool:
        """Whether the function is in the disk cache for :attr:`argtypes`
        (:func:`cached`)."""
        return cached(self._dispatcher(), self.argtypes)

    def compile(self):
        """Compile the function for :attr:`argtypes`, or load it from the disk cache
        (its compile result)."""
        dispatcher = self._dispatcher()
        dispatcher.compile(self.argtypes)
        return dispatcher.overloads[self.argtypes]

    def ensure(self) -> None:
        """:meth:`compile` and put the function's address in the slot; nothing when it
        is there already."""
        if self.slot[0]:
            return
        cres = self.compile()
        if cres.signature.return_type != self.restype:
            raise TypeError(f"{self.name} returns {cres.signature.return_type}, declared "
                            f"{self.restype}")
        self._cres = cres                                  # keeps its code alive
        self.slot[0] = cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name)


def cached(dispatcher, sig) -> bool:
    """Whether ``dispatcher`` has ``sig`` in its disk cache (nothing is loaded or
    compiled; the cache of :mod:`offshore_crane.kernel_cache` answers, another says no)."""
    has = getattr(dispatcher._cache, "has", None)
    return bool(has is not None and has(sig, dispatcher.targetctx))


def short_names() -> dict:
    """The names a signature's text may use (:meth:`Entry.typed`): Numba's types, and
    ``V`` a C-contiguous float64 vector, ``M`` a C-contiguous float64 matrix, ``T3`` a
    tuple of 3 floats (a point, gravity) and ``PACKED`` the three packed arrays of a
    robot's description (``flat``, ``layout``, ``prismatic``:
    :class:`~offshore_crane.dynamics.constants.RobotArrays`), to unpack (``*PACKED``)."""
    from numba.core import types

    f8 = types.float64
    return {**vars(types), "V": types.Array(f8, 1, "C"), "M": types.Array(f8, 2, "C"),
            "T3": types.UniTuple(f8, 3),
            "PACKED": (types.Array(f8, 1, "C"), types.Array(types.int64, 2, "C"),
                       types.Array(types.boolean, 1, "C"))}


def named(name: str) -> Entry:
    """The entry made under ``name`` in this process.

    Raises:
        KeyError: none was.
    """
    for entry in _BY_CALL.values():
        if entry.name == name:
            return entry
    raise KeyError(f"no entry named {name!r} was made in this process")


def _caller(entry: Entry):
    """The intrinsic that calls ``entry`` through its slot."""
    from llvmlite import ir
    from numba.core import cgutils, types
    from numba.core.callconv import excinfo_t
    from numba.core.errors import TypingError
    from numba.extending import intrinsic

    def call(typingctx, *args):
        given = tuple(types.unliteral(a) for a in args)
        if len(given) != len(entry.argtypes):
            raise TypingError(f"{entry.name} takes {len(entry.argtypes)} arguments, "
                              f"given {len(given)}")
        for i, (a, want) in enumerate(zip(given, entry.argtypes)):
            if a != want and not _converts(typingctx, a, want):
                raise TypingError(f"{entry.name}: argument {i} is {a}, the entry takes "
                                  f"{want} (pass exactly its types)")
        sig = entry.restype(*entry.argtypes)

        def codegen(context, builder, signature, values):
            conv = context.call_conv
            address = builder.load(_global(builder.module, entry.symbol))
            with cgutils.if_unlikely(builder, cgutils.is_null(builder, address)):
                conv.return_user_exc(builder, RuntimeError, (
                    f"{entry.name} was not loaded before a kernel that calls it ran "
                    "(offshore_crane.kernel_calls): report this as a bug",))
            fnty = conv.get_function_type(entry.restype, entry.argtypes)
            callee = builder.inttoptr(address, fnty.as_pointer())
            retty = conv.get_return_type(entry.restype).pointee
            ret = cgutils.alloca_once(builder, retty)
            builder.store(cgutils.get_null_value(retty), ret)
            excinfo = cgutils.alloca_once(builder, ir.PointerType(excinfo_t), name="excinfo")
            packed = list(conv._get_arg_packer(entry.argtypes).as_arguments(builder,
                                                                               values))
            code = builder.call(callee, [ret, excinfo] + packed)
            status = conv._get_return_status(builder, code, builder.load(excinfo))
            with cgutils.if_unlikely(builder, status.is_error):
                conv.return_status_propagate(builder, status)
            return context.get_returned_value(builder, entry.restype, builder.load(ret))

        return sig, codegen

    # a fixed arity: Numba lowers an intrinsic's *args as one packed argument
    names = ", ".join(f"a{i}" for i in range(len(entry.argtypes)))
    scope = {"call": call}
    exec(f"def call_{entry.name}(typingctx, {names}):\n"
         f"    return call(typingctx, {names})\n", scope)
    # importable by name: a caller's cache key pickles what it references, by reference
    fn = scope[f"call_{entry.name}"]
    fn.__module__, fn.__qualname__ = __name__, f"call_{entry.symbol}"
    globals()[fn.__qualname__] = fn
    return intrinsic(fn)


def _converts(typingctx, given, want) -> bool:
    """A number converts to a number without loss (an int where a float is declared:
    Numba casts it); arrays and everything else must be exactly the declared type."""
    from numba.core import types
    from numba.core.typeconv import Conversion

    if not (isinstance(given, types.Number) and isinstance(want, types.Number)):
        return False
    kind = typingctx.can_convert(given, want)
    return kind is not None and kind <= Conversion.safe


def _global(module, name):
    """An external ``i64`` global of ``module`` named ``name`` (declared once)."""
    from llvmlite import ir

    if name in module.globals:
        return module.globals[name]
    gv = ir.GlobalVariable(module, ir.IntType(64), name)
    gv.linkage = "external"
    return gv


def _names(code) -> set:
    """Every global or attribute name ``code`` and the code nested in it use."""
    out = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, _pytypes.CodeType):
            out |= _names(const)
    return out


def reached(py_func) -> tuple:
    """The entries ``py_func``'s text reaches: the entries' calls it names (as globals,
    closure variables, or attributes of them, two deep: ``c.KE.f``) and, the same way,
    those of every compiled function it names; cached per function."""
    out = _REACHED.get(py_func)
    if out is not None:
        return out
    from numba.core.dispatcher import Dispatcher

    found, seen, todo = [], set(), [py_func]
    while todo:
        f = todo.pop()
        if id(f) in seen or not hasattr(f, "__code__"):
            continue
        seen.add(id(f))
        names = _names(f.__code__)
        objects = [f.__globals__[n] for n in names if n in f.__globals__]
        for cell in f.__closure__ or ():
            try:
                objects.append(cell.cell_contents)
            except ValueError:                   # an empty cell
                pass
        for depth in range(3):
            deeper = []
            for obj in objects:
                if id(obj) in _BY_CALL:
                    entry = _BY_CALL[id(obj)]
                    if entry not in found:
                        found.append(entry)
                elif isinstance(obj, Dispatcher):
                    todo.append(obj.py_func)
                elif isinstance(obj, (tuple, list)):       # a namedtuple too
                    deeper.extend(obj)
                if depth < 2 and (isinstance(obj, _pytypes.ModuleType)
                                  or hasattr(obj, "_fields")):
                    deeper.extend(getattr(obj, n) for n in names if hasattr(obj, n))
            objects = deeper
    out = _REACHED[py_func] = tuple(found)
    return out


def reached_all(py_func) -> tuple:
    """The entries ``py_func``'s text reaches (:func:`reached`) and, the same way, those
    the entries' own texts reach: every function called by address that must be loaded
    before ``py_func`` runs."""
    out, todo = [], list(reached(py_func))
    while todo:
        entry = todo.pop(0)
        if entry not in out:
            out.append(entry)
            todo.extend(reached(entry._dispatcher().py_func))
    return tuple(out)
