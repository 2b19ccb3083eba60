"""A compiled view of part of a flat buffer, without NumPy's reshape (imports Numba).

:func:`~offshore_crane.dynamics.compiled.unpack` rebuilds the robot's 26 constant arrays
from one flat buffer at every kernel call. As ``flat[o:o + n].reshape(shape)`` each view
is a slice, then a call of Numba's run-time reshape helper (which searches for strides
that need no copy): 1.15 µs for the 26, what a one-sample call or a plant's stage of the
simulation loop notices. :func:`c_view` writes the view's array structure directly: the
buffer's data pointer moved by ``offset`` elements, ``shape`` and its C-order strides,
the buffer's reference-counted owner shared (a borrowed view, like a slice).

Nothing is checked: the caller guarantees ``offset + prod(shape) <= flat.size`` (the
layout of :func:`~offshore_crane.dynamics.constants.build`, tested against the slices'
views in ``tests/dynamics/test_kernels.py``).
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.core.imputils import impl_ret_borrowed
from numba.extending import intrinsic
from numba.np.arrayobj import make_array, populate_array


@intrinsic
def c_view(typingctx, flat, offset, shape):
    """``flat[offset : offset + prod(shape)]`` as a C-contiguous array of ``shape``.

    Args:
        flat: A 1-D C-contiguous array.
        offset: Its first element of the view (an integer).
        shape: A tuple of 1 to 3 integers.
    """
    if not (isinstance(flat, types.Array) and flat.ndim == 1 and flat.layout == "C"
            and isinstance(offset, types.Integer) and isinstance(shape, types.BaseTuple)
            and 1 <= len(shape.types) <= 3
            and all(isinstance(d, types.Integer) for d in shape.types)):
        return None
    out_type = flat.copy(ndim=len(shape.types), layout="C")
    sig = out_type(flat, offset, shape)

    def codegen(context, builder, signature, args):
        flat_type = signature.args[0]
        src = make_array(flat_type)(context, builder, args[0])
        out = make_array(signature.return_type)(context, builder)
        dims = [context.cast(builder, d, t, types.intp)
                for d, t in zip(cgutils.unpack_tuple(builder, args[2]),
                                signature.args[2].types)]
        start = context.cast(builder, args[1], signature.args[1], types.intp)
        stride = src.itemsize
        strides = []
        for d in reversed(dims):                  # C order: the last axis moves fastest
            strides.insert(0, stride)
            stride = builder.mul(stride, d)
        populate_array(out, data=builder.gep(src.data, [start], inbounds=True), shape=dims,
                       strides=strides, itemsize=src.itemsize, meminfo=src.meminfo,
                       parent=src.parent)
        return impl_ret_borrowed(context, builder, signature.return_type, out._getvalue())

    return sig, codegen
