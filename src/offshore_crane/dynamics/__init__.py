"""Dynamics of the hybrid robot: inverse dynamics (:mod:`.inverse`: Kane fused and
explicit, the RNEA reference path), forward dynamics (:mod:`.forward`), the hanging load
(:mod:`.cable`); the formulas (:mod:`.formulas`), their backends (:mod:`.backends`,
:mod:`.compiled`, :mod:`.extended`, :mod:`.tracing` with :mod:`.lanes`) and where they
run (:mod:`.runtime`).
"""

from __future__ import annotations

import numpy as np

from offshore_crane.lazy import submodule_getattr
from offshore_crane.conventions import GRAVITY, LANES
from offshore_crane.dynamics.inverse import (APPROXIMATIONS, LEG_MODELS, METHODS, PYTHON_MAX, REGISTRY,
                                             STATIC_MIN, Result, inverse_dynamics, solve)
from offshore_crane.dynamics.runtime import BACKENDS, numba_available, quick_backend, resolve_backend

__all__ = ["APPROXIMATIONS", "BACKENDS", "LEG_MODELS", "METHODS", "PYTHON_MAX", "REGISTRY",
           "STATIC_MIN", "Result", "inverse_dynamics", "numba_available", "quick_backend",
           "resolve_backend", "solve", "warm_up"]


def warm_up(robot=None, methods: tuple[str, ...] = METHODS,
            forward: bool = True) -> list[tuple[str, float]]:
    """Compile (or load from the cache) the compiled kernels: ``[(name, seconds), ...]``.

    Call it once before starting parallel workers, so that they load the cache rather
    than compile the same kernels at once.

    Args:
        robot: The robot whose kernels to load (default: the default description).
        methods: The inverse-dynamics methods to load (default all of :data:`METHODS`;
            ``"rnea"`` also imports Pinocchio).
        forward: Load the forward-dynamics kernel too.
    """
    import time

    from offshore_crane.robot import load_robot

    robot = robot or load_robot()
    q = robot.home_pose()[None, :]
    out = []
    for method in dict.fromkeys(methods):
        t0 = time.perf_counter()
        solve(robot, q, 0 * q, 0 * q, method=method, backend="numba", limits=False)
        if method == "kane":                  # and the block kernel of longer motions
            moving = np.repeat(q, LANES, axis=0)
            solve(robot, moving, np.full_like(moving, 1e-3), 0 * moving, backend="numba",
                  limits=False)
        if method == "rnea":                  # more samples: Fortran-ordered tree states
            from offshore_crane.reference.rnea.regressor import regressor

            two = np.repeat(q, 2, axis=0)     # (one sample's are C-ordered too: another type)
            solve(robot, two, 0 * two, 0 * two, method=method, backend="numba", limits=False)
            regressor(robot, two, 0 * two, 0 * two, GRAVITY)   # identification's projection
        out.append((f"{method} kernels", time.perf_counter() - t0))
    if not forward:
        return out
    from offshore_crane.dynamics.forward import forward_dynamics

    t0 = time.perf_counter()
    forward_dynamics(robot, q, 0 * q, 0 * q, limits=False)
    out.append(("forward dynamics", time.perf_counter() - t0))
    return out


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
