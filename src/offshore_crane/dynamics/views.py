"""A compiled view of part of a flat buffer, without NumPy's reshape and without an owner
(imports Numba).

:func:`~offshore_crane.dynamics.compiled.unpack` rebuilds the robot's 26 constant arrays
from one flat buffer at every kernel call, and the elastic plant carves its work buffer
into 23 arrays (``elastic_plant._carve``). As ``flat[o:o + n].reshape(shape)`` each view
is a slice, then a call of Numba's run-time reshape helper (which searches for strides
that need no copy): 1.15 µs for the 26, what a one-sample call or a plant's stage of the
simulation loop notices. :func:`c_view` writes the view's array structure directly: the
buffer's data pointer moved by ``offset`` elements, ``shape`` and its C-order strides.

**The view has no owner** (a null meminfo and parent): it neither keeps the buffer alive
nor is reference-counted. Every view shared the buffer's owner before, so that each time
a view was handed to a called kernel, stored in a tuple or dropped, Numba changed the
owner's reference count with an atomic operation: 26 constants a pass, several passes a
stage. Without the owner, the rigid loop runs at a real-time factor of 63.5 against 50.1
and the elastic lift at 23.1 against 15.2 (one core, one session). The rule that makes it
safe: ``flat`` is an argument of the running kernel (or an element of one), which its
caller keeps alive for the call, never an array the kernel made (a temporary can be freed
while its views are in use); a view never leaves compiled code (from Python, as the test
of :func:`~offshore_crane.dynamics.compiled.unpack` calls it, the returned arrays do not
keep the buffer: keep it alive while they are used). Every call site is such an argument
(``tests/dynamics/test_kernels.py`` checks the rule on the package's sources).

Nothing is checked: the caller guarantees ``offset + prod(shape) <= flat.size`` (the
layout of :func:`~offshore_crane.dynamics.constants.build`, tested against the slices'
views in ``tests/dynamics/test_kernels.py``).
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic
from numba.np.arrayobj import make_array, populate_array


@intrinsic
def c_view(typingctx, flat, offset, shape):
    """``flat[offset : offset + prod(shape)]`` as a C-contiguous array of ``shape``, with
    no owner (module docstring: ``flat`` must outlive it).

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
        src = make_array(signature.args[0])(context, builder, args[0])
        dims = [context.cast(builder, d, t, types.intp)
                for d, t in zip(cgutils.unpack_tuple(builder, args[2]),
                                signature.args[2].types)]
        start = context.cast(builder, args[1], signature.args[1], types.intp)
        return view_value(context, builder, signature.return_type, src, start, dims)

    return sig, codegen


def view_value(context, builder, out_type, src, start, dims):
    """The LLVM value of :func:`c_view`'s array ``out_type``: ``dims`` (LLVM intp
    values) C-ordered from element ``start`` of the array structure ``src``, no owner
    (for intrinsics that make many views at once)."""
    out = make_array(out_type)(context, builder)
    stride = src.itemsize
    strides = []
    for d in reversed(dims):                  # C order: the last axis moves fastest
        strides.insert(0, stride)
        stride = builder.mul(stride, d)
    populate_array(out, data=builder.gep(src.data, [start], inbounds=True), shape=dims,
                   strides=strides, itemsize=src.itemsize,
                   meminfo=cgutils.get_null_value(src.meminfo.type),
                   parent=cgutils.get_null_value(src.parent.type))
    return out._getvalue()


@intrinsic
def unowned(typingctx, x):
    """``x`` (an array, or a tuple of arrays, numbers and such tuples) with each array's
    owner dropped
    (the same data, shape and strides; module docstring: ``x`` must be an argument of the
    running kernel, which its caller keeps alive). A loop that hands the arrays of its
    arguments' tuples to called kernels at every stage no longer changes their reference
    counts."""
    def allowed(t):
        return isinstance(t, (types.Array, types.Number, types.Boolean)) or (
            isinstance(t, types.BaseTuple) and all(allowed(e) for e in t.types))

    if not allowed(x):
        return None
    sig = x(x)

    def strip(context, builder, typ, value):
        if isinstance(typ, types.BaseTuple):
            for i, t in enumerate(typ.types):
                value = builder.insert_value(value, strip(
                    context, builder, t, builder.extract_value(value, i)), i)
            return value
        if not isinstance(typ, types.Array):
            return value
        ary = make_array(typ)(context, builder, value=value)
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        ary.parent = cgutils.get_null_value(ary.parent.type)
        return ary._getvalue()

    def codegen(context, builder, signature, args):
        return strip(context, builder, signature.args[0], args[0])

    return sig, codegen
