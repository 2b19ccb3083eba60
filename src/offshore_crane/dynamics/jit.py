"""How every compiled kernel is compiled (Numba options), in one place:
:data:`offshore_crane.kernel_cache.JIT`, which the kernels below the dynamics (a
trajectory's interpolation) use too."""

from __future__ import annotations

from offshore_crane.kernel_cache import JIT, LEAN  # noqa: F401
