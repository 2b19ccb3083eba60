"""Compiled calls by address (offshore_crane.kernel_calls) and the cache key that does not
change between processes (kernel_cache.stable_key).

The callee's results through its address are compared with a direct call, bit for bit
(the same compiled code runs); the errors are the typing check of each argument and
the call through a slot nothing filled.
"""

from __future__ import annotations

import collections
import subprocess
import sys

import numba
import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import kernel_calls
from offshore_crane.kernel_cache import njit, stable_key


@numba.njit
def _weighted(x, w, out):
    """A callee: writes ``x * w`` into ``out``, returns its sum."""
    total = 0.0
    for i in range(x.shape[0]):
        out[i] = x[i] * w
        total += out[i]
    return total


WEIGHTED = kernel_calls.Entry.typed("test_weighted", lambda: _weighted,
                                    "float64(float64[::1], float64, float64[::1])", "test")
call_weighted = WEIGHTED.call


@njit
def _caller(x, w, out):
    """Calls the callee by address, twice (the second on its own output)."""
    a = call_weighted(x, w, out)
    b = call_weighted(out.copy(), 0.5, out)
    return a + b


def _direct(x, w, out):
    a = _weighted(x, w, out)
    return a + _weighted(out.copy(), 0.5, out)


def test_a_call_by_address_gives_the_direct_call_bit_for_bit():
    x = np.random.default_rng(7).normal(size=17)
    got, want = np.empty(17), np.empty(17)
    assert _caller(x, 3.0, got) == _direct(x, 3.0, want)
    assert np.array_equal(got, want)
    assert WEIGHTED.slot[0] != 0                   # the caller's compile loaded it


def test_a_caller_by_address_links_none_of_the_callees_code():
    """The point of an entry: the caller's module declares the slot and defines nothing of
    the callee, where a direct call links the callee's definition into it."""
    @numba.njit
    def by_address(x, out):
        return call_weighted(x, 2.0, out)

    @numba.njit
    def direct(x, out):
        return _weighted(x, 2.0, out)

    x, out = np.ones(3), np.empty(3)
    by_address(x, out)
    direct(x, out)
    callee = WEIGHTED._cres.library

    def linked(f):            # the libraries Numba links into f's module (a private list)
        return f.overloads[f.signatures[0]].library._linking_libraries

    assert callee in linked(direct)
    assert callee not in linked(by_address)
    assert WEIGHTED.symbol in by_address.inspect_llvm(by_address.signatures[0])


def test_an_argument_of_another_type_is_refused_when_the_caller_compiles():
    @njit
    def wrong(x, out):
        return call_weighted(x, 2, out.astype(np.float32))   # float32 where float64 is

    with pytest.raises(numba.core.errors.TypingError,
                       match=r"test_weighted: argument 2 is array\(float32"):
        wrong(np.zeros(3), np.zeros(3))


def test_a_call_through_an_empty_slot_raises_instead_of_jumping_to_zero():
    empty = kernel_calls.Entry.typed("test_never_loaded", lambda: _weighted,
                                     "float64(float64[::1], float64, float64[::1])", "test")
    call = empty.call

    @numba.njit                                    # Numba's own: nothing loads the entry
    def unguarded(x):
        return call(x, 1.0, x)

    with pytest.raises(RuntimeError, match="test_never_loaded was not loaded"):
        unguarded(np.zeros(2))


Pair = collections.namedtuple("Pair", "first second")
_PAIR = Pair(None, WEIGHTED.call)


def _through_attribute(x):
    return _PAIR.second(x, 1.0, x)


def test_reached_finds_entries_through_globals_closures_attributes_and_kernels():
    assert kernel_calls.reached(_caller.py_func) == (WEIGHTED,)
    assert kernel_calls.reached(_through_attribute) == (WEIGHTED,)
    c = call_weighted

    def closure(x):
        return c(x, 1.0, x)

    assert kernel_calls.reached(closure) == (WEIGHTED,)

    def above(x):                                  # through a compiled function it calls
        return _caller(x, 1.0, x)

    assert kernel_calls.reached(above) == (WEIGHTED,)
    assert kernel_calls.reached(_direct) == ()


@njit
def _outer_pass(x, w, out):
    """An entry's function that itself calls an entry by address."""
    return call_weighted(x, w, out)


OUTER = kernel_calls.Entry.typed("test_outer", lambda: _outer_pass,
                                 "float64(V, float64, V)", "test")
call_outer = OUTER.call


def test_reached_all_follows_the_entries_own_calls_by_address():
    """What must be loaded before a kernel runs: the entries it calls and theirs."""
    def above(x):
        return call_outer(x, 1.0, x)

    assert kernel_calls.reached(above) == (OUTER,)
    assert kernel_calls.reached_all(above) == (OUTER, WEIGHTED)
    assert kernel_calls.reached_all(_direct) == ()


def test_the_explicit_pass_is_declared_with_the_types_the_kernels_give_it(robot):
    from offshore_crane.dynamics import compiled as c
    from offshore_crane.dynamics.constants import robot_arrays

    assert numba.typeof(robot_arrays(robot).kane) == c.kane_constants_type()
    assert c.EXPLICIT.argtypes[0] == c.kane_constants_type()


def test_a_signatures_short_names_are_the_types_the_packed_arrays_and_work_give():
    """``PACKED``, ``V``, ``M``, ``T3`` of a signature's text are what ``numba.typeof``
    gives the description's packed arrays, a work vector, a work matrix, gravity; a name
    given as a keyword is used as it is."""
    from offshore_crane.dynamics.constants import robot_arrays
    from numba import types

    a = robot_arrays(oc.load_robot())
    e = kernel_calls.Entry.typed("test_short_names", lambda: _weighted,
                                 "float64(*PACKED, V, M, T3, W)", "test", W=types.int8)
    given = (a.flat, a.layout, a.prismatic, np.zeros(3), np.zeros((2, 3)), (0.0, 0.0, -9.81))
    assert e.argtypes[:6] == tuple(numba.typeof(x) for x in given)
    assert e.argtypes[6] == types.int8 and e.restype == types.float64


def test_a_signature_with_an_unknown_name_is_refused_where_it_is_declared():
    with pytest.raises(NameError, match="'Q'"):
        kernel_calls.Entry.typed("test_unknown", lambda: _weighted, "float64(V, Q)", "test")


def test_the_cache_key_of_a_closure_does_not_hold_an_intrinsics_random_id():
    """Two intrinsics of one definition pickle with two random ids; their keys agree."""
    from numba.extending import intrinsic

    def definition(typingctx, x):
        return None

    assert stable_key((intrinsic(definition), 1.5)) == stable_key((intrinsic(definition), 1.5))
    assert stable_key(np.arange(3.0)) != stable_key(np.arange(4.0))


def test_the_one_sample_kernels_cache_key_is_the_same_in_every_process():
    """``forward_one`` closes over the batch kernel, which uses intrinsics: pickled, its
    closure gave a new cache key in every process (a compile at every first call)."""
    code = ("import hashlib; from offshore_crane.dynamics import compiled as c; "
            "from offshore_crane.kernel_cache import stable_key; f = c.forward_one.py_func; "
            "print(hashlib.sha256(repr(stable_key(tuple(x.cell_contents for x in "
            "f.__closure__))).encode()).hexdigest())")
    keys = {subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True).stdout for _ in range(2)}
    assert len(keys) == 1
