"""The explicit Kane pass every compiled kernel calls by address (imports Numba).

:func:`explicit_sample` runs the straight-line program of the robot's arm structure that
:mod:`.native` compiles with LLVM from the formulas' trace; :data:`EXPLICIT` is it as a
:class:`~offshore_crane.kernel_calls.Entry`, compiled once in its own library: kernels
call ``call_explicit`` with its exact types. (Before the program, this was the formulas
inlined by Numba, 20 s to compile and 1.87 µs a call with the mass matrix, against about
1 s and 1.52 µs: the six legs run as the lanes of vectors.)
"""

from __future__ import annotations

from numba import objmode

from offshore_crane import kernel_calls
from offshore_crane.dynamics import backends, native
from offshore_crane.dynamics.formulas import KaneConstants
from offshore_crane.dynamics.jit import JIT
from offshore_crane.kernel_cache import njit

STAMP = backends.source_stamp()


def _explicit(stamp):
    @njit(**JIT)
    def explicit_sample(C, q, qd, qdd, g, want_mass, B, J, Mm, store, Vw, Ww, Vs, diag, mc):
        """:func:`~offshore_crane.dynamics.formulas.explicit_sample`: the straight-line
        program of ``C``'s arm structure compiled by LLVM (:mod:`.native`), called
        through its slot. Compiled once (closed over the formulas' and the programs'
        hash ``stamp``, which keys its disk cache) and called by address by every kernel
        (:data:`call_explicit`); its first call for an arm structure loads or compiles
        that structure's program (:func:`.native.ensure`, in object mode: about 1 s on a
        cold cache). ``Vw, Ww, Vs`` are not touched."""
        if len(stamp) == 0:
            return
        i = _program_index(C.n_arm, C.arm_prism, want_mass)
        if not _call_program(i, C, q, qd, qdd, g, B, J, Mm, store, diag, mc):
            _load(C)                        # once per arm structure and process
            if not _call_program(i, C, q, qd, qdd, g, B, J, Mm, store, diag, mc):
                raise RuntimeError("the explicit pass was not loaded: report this as a bug")

    return explicit_sample


@njit(cache=True)             # not nogil: its object-mode block takes the GIL anyway
def _load(C):
    """Load or compile the programs of ``C``'s arm structure (:func:`.native.ensure`)."""
    with objmode():
        _ensure(C)


_program_index = njit(inline="always", **JIT)(native.program_index)
_call_program, _ensure = native.caller(), native.ensure    # globals: cacheable
explicit_sample = _explicit(STAMP + native.stamp())


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
