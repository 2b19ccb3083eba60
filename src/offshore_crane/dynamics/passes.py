"""The Kane passes every compiled kernel calls by address (imports Numba).

Each pass (:func:`explicit_sample`, :func:`kane_pass`, :func:`kane_pull_pass`,
:func:`kane_pull2_pass`) runs the
straight-line program of the robot's arm structure and of the pass's flags that
:mod:`.native` compiles with LLVM from the formulas' trace; :data:`EXPLICIT`,
:data:`KANE` and :data:`KANE_PULL` are them as
:class:`~offshore_crane.kernel_calls.Entry` objects, each compiled once in its own library:
kernels call ``call_explicit`` (…) with its exact types. A pass's first call for a
structure and flags loads or compiles that program (:func:`.native.ensure_slot`, called
back from the compiled call: under a second on a cold cache). Before the programs, these
were the formulas inlined by Numba, 16–23 s each to compile and slower to run
(``benchmarks/passes.py``, docs/simulation.md).
"""

from __future__ import annotations

from offshore_crane import kernel_calls
from offshore_crane.dynamics import backends, native
from offshore_crane.dynamics.formulas import KaneConstants
from offshore_crane.dynamics.jit import JIT
from offshore_crane.dynamics.tracing import kane_variant
from offshore_crane.kernel_cache import njit

STAMP = backends.source_stamp()
_FAILED = ("a compiled Kane pass could not be loaded (the error is printed above): report "
           "this as a bug")
_EXPLICIT, _KANE, _KANE_PULL, _KANE_PULL2 = (native.KINDS.index(k) for k in (
    "explicit", "kane", "kane_pull", "kane_pull2"))


def _make(stamp):
    @njit(**JIT)
    def explicit_sample(C, q, qd, qdd, g, want_mass, B, J, Mm, store, Vw, Ww, Vs, diag, mc):
        """:func:`~offshore_crane.dynamics.formulas.explicit_sample` (``Vw, Ww, Vs``
        are not touched: the program's scratch is its own)."""
        if len(stamp) == 0:
            return
        v = 1 if want_mass else 0
        i = _index(_EXPLICIT, C.n_arm, C.arm_prism, v)
        if not _call11(i, C, q, qd, qdd, g, B, J, Mm, store, diag, mc):
            raise RuntimeError(_FAILED)

    @njit(**JIT)
    def kane_pass(C, q, qd, qdd, g, static, leg_model, want_legs, rows, A, rhs, diag,
                  store):
        """:func:`~offshore_crane.dynamics.formulas.kane_sample`."""
        if len(stamp) == 0:
            return
        if leg_model < 0 or leg_model > 2:
            raise ValueError("leg_model must be 0, 1 or 2 (FULL, THIN_ROD, MASSLESS)")
        v = _variant(static, leg_model, want_legs)
        i = _index(_KANE, C.n_arm, C.arm_prism, v)
        if not _call10(i, C, q, qd, qdd, g, rows, A, rhs, diag, store):
            raise RuntimeError(_FAILED)

    @njit(**JIT)
    def kane_pull_pass(C, q, qd, qdd, g, pull, at, rows, A, rhs, diag, store):
        """:func:`~offshore_crane.dynamics.formulas.kane_sample_pull`."""
        if len(stamp) == 0:
            return
        i = _index(_KANE_PULL, C.n_arm, C.arm_prism, 0)
        if not _call12(i, C, q, qd, qdd, g, pull, at, rows, A, rhs, diag, store):
            raise RuntimeError(_FAILED)

    @njit(**JIT)
    def kane_pull2_pass(C, q, qd, qdd, g, pull, pz, at, rows, A, rhs, diag, store):
        """:func:`kane_pull_pass` at ``(qdd, pull)`` and ``(qdd, pz)``
        (:data:`~offshore_crane.dynamics.tracing.PULL2`) in one program: ``rows`` (2,
        r) and ``rhs`` (2, 6) pass k's in row k, ``A``, ``diag``, ``store`` the last's;
        each pass's numbers bit for bit its own call's."""
        if len(stamp) == 0:
            return
        i = _index(_KANE_PULL2, C.n_arm, C.arm_prism, 0)
        if not _call13(i, C, q, qd, qdd, g, pull, pz, at, rows, A, rhs, diag, store):
            raise RuntimeError(_FAILED)

    return explicit_sample, kane_pass, kane_pull_pass, kane_pull2_pass


_index = njit(**JIT)(native.program_index)
_variant = njit(**JIT)(kane_variant)
_call10, _call11, _call12, _call13 = (native.caller(n) for n in (10, 11, 12, 13))
explicit_sample, kane_pass, kane_pull_pass, kane_pull2_pass = _make(STAMP + native.stamp())


def kane_constants_type():
    """The Numba type of :class:`~.formulas.KaneConstants` as :func:`unpack` makes it
    (C-contiguous float64 arrays, ``n_arm`` an int64, ``arm_prism`` booleans)."""
    from numba import types

    f8 = types.float64
    nd = {"plat_m": 0, "plat_c": 1, "plat_I": 2, "n_arm": -1, "arm_t": 2, "arm_Ro": 3,
          "arm_axis": 2, "arm_prism": -2, "arm_m": 1, "arm_c": 2, "arm_I": 3, "leg_s": 2,
          "leg_P": 2, "leg_X": 2, "leg_Y": 2, "leg_Z": 2, "lo_m": 1, "lo_c": 2, "up_m": 1,
          "up_c": 2, "leg_I": 3, "thin_It": 1, "lo_cz": 1, "up_cz": 1, "L": 0}
    kind = {0: f8, -1: types.int64, -2: types.Array(types.boolean, 1, "C")}
    return types.NamedTuple([kind[nd[n]] if nd[n] <= 0 else types.Array(f8, nd[n], "C")
                             for n in KaneConstants._fields], KaneConstants)


#: :func:`explicit_sample` called by address (:mod:`offshore_crane.kernel_calls`): every
#: kernel that runs it calls ``call_explicit`` with its arguments, exactly typed (``C``
#: from :func:`unpack`; ``q, qd, qdd, B`` (n,) and the work arrays C-contiguous, ``g`` a
#: tuple of 3 floats). Its code is compiled once, in its own library, not again in each
#: caller.
EXPLICIT = kernel_calls.Entry.typed(
    "explicit_sample", lambda: explicit_sample,
    "none(C, V, V, V, T3, boolean, V, M, M, M, M, M, M, M, M)", STAMP,
    C=kane_constants_type())
call_explicit = EXPLICIT.call
#: The fused Kane pass and the one with a pull at the tip, called by address by the
#: hanging load's and the elastic cable's kernels.
KANE = kernel_calls.Entry.typed(
    "kane_sample", lambda: kane_pass,
    "none(C, V, V, V, T3, boolean, int64, boolean, V, M, V, M, M)", STAMP,
    C=kane_constants_type())
KANE_PULL = kernel_calls.Entry.typed(
    "kane_sample_pull", lambda: kane_pull_pass,
    "none(C, V, V, V, T3, T3, T3, V, M, V, M, M)", STAMP, C=kane_constants_type())
KANE_PULL2 = kernel_calls.Entry.typed(
    "kane_sample_pull2", lambda: kane_pull2_pass,
    "none(C, V, V, V, T3, T3, T3, T3, M, M, M, M, M)", STAMP, C=kane_constants_type())
call_kane, call_kane_pull, call_kane_pull2 = KANE.call, KANE_PULL.call, KANE_PULL2.call
