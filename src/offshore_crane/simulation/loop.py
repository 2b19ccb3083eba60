"""The RK4 driver's text: one loop for every plant and law, compiled where the law is
built in and run as it is written where the law is Python (:func:`instantiate`).

:func:`loop` and :func:`evaluate` are templates: the names they call but do not define
(``prepare``, ``rhs``, ``check``, ``keep`` of the plant; ``command``, ``law_rate`` of the
law; ``IQ``, ``IQD`` where q and q̇ sit in the plant's state) are looked up in the namespace
they are instantiated in (:func:`instantiate`): a plant's compiled kernels
(:mod:`offshore_crane.simulation.plants`) and a law's templates
(:mod:`offshore_crane.simulation.laws`), compiled together by Numba; or the same with a
user's Python law, the loop then run by Python. Each compiled instance is cached on disk
under the checksum of its parts' texts (:data:`offshore_crane.kernel_cache.PROGRAM_DIGEST`),
so that two instances of one text never share an entry.

The integrated state is ``y = (plant state (n_p), law state (n_z), actuator lag (9 or
0))``; the reference is given at every stage time (2 per step); the semantics are the
module docstring's of :mod:`offshore_crane.simulation.driver`.
"""

from __future__ import annotations

import hashlib
import inspect
import os
import types

import numpy as np

from offshore_crane.dynamics.integrator import rk4_combine, rk4_stage
from offshore_crane.stops import CODES
from offshore_crane.simulation.templates import (IQ, IQD, check, command, keep,
                                                law_rate, prepare, rhs, unowned, winch)

OK, _WORKSPACE, _SINGULAR, DIVERGED, STOPPED, _SLACK = CODES


def quantised(x, r):
    """``x`` rounded to the resolution ``r`` (> 0), else ``x``."""
    if r > 0.0:
        return np.rint(x / r) * r
    return x


def evaluate(P, L, i, t, y, dy, qr, qdr, qddr, lo, hi, held, Xh, Xhin, dzh, lag, n_p, n_z,
             Xc, X, aux):
    """One stage at grid point ``i`` (time ``t`` [s]) and state ``y``: what the plant
    makes ahead at ``y`` (``prepare``: a pass the law may share), the law's command
    ``Xc`` (or the held one; a commanded winch's pull first from its drive, ``winch``,
    which the law may overwrite), the actuators (the lag's output or the command, clipped
    to ``[lo, hi]``, as many forces as ``lo`` holds) into ``X``, the plant's rates and the
    law's and the lag's into ``dy``; returns the plant's ``ok`` (False: a singular mass
    matrix)."""
    n_pz = n_p + n_z
    nl = lag.shape[0]
    nx = lo.shape[0]
    prepare(P, i, y, aux)
    if held:
        for j in range(nx):
            Xc[j] = Xh[j]
    else:
        winch(P, i, y, Xc)
        command(L, P, i, t, y, n_p, qr, qdr, qddr, Xc)
    for j in range(nx):
        src = y[n_pz + j] if j < nl else (Xhin[j] if held else Xc[j])
        X[j] = min(max(src, lo[j]), hi[j])
    ok = rhs(P, i, y, X, dy, aux)
    if n_z > 0:
        if held:
            for j in range(n_z):
                dy[n_p + j] = dzh[j]
        else:
            law_rate(L, P, i, t, y, n_p, qr, qdr, qddr, Xc, X, dy)
    for j in range(nl):
        dy[n_pz + j] = ((Xhin[j] if held else Xc[j]) - y[n_pz + j]) / lag[j]
    return ok


def sense(y, ym, hist, first, g, delay, nq, nqd, resq, resqd, sens, ctrl, n_p):
    """The measured state ``ym`` (as ``y``) at global step ``g``, control instant
    ``ctrl``: the state, with the sensors (``sens``) the plant's part ``delay`` steps old
    (``hist``, its row ``g`` written; ``first`` before the history fills) and q, q̇ with
    that instant's noise, quantised. The same numbers however often it is called at one
    instant (a stepper's observation, then the loop's own)."""
    for j in range(y.shape[0]):
        ym[j] = y[j]
    if sens:
        r = (g - delay) % (delay + 1)
        for j in range(n_p):
            ym[j] = hist[r, j] if g >= delay else first[j]
        for j in range(9):
            ym[IQ + j] = quantised(ym[IQ + j] + nq[ctrl, j], resq[j])
            ym[IQD + j] = quantised(ym[IQD + j] + nqd[ctrl, j], resqd[j])


def loop(P, L, tt, qr, qdr, qddr, y, h, n_steps, out_every, hold, lo, hi, lag, rlim, delay,
         nq, nqd, resq, resqd, sens, n_p, n_z, RQ, RQD, RQDD, RQR, RQDR, RXC, RX, SAT, EXTRA,
         status, halt, W, s0, finish):
    """RK4 from ``y`` (modified in place) for ``n_steps`` steps of ``h`` [s]; every
    ``out_every``-th step recorded (``RQ`` ... ``RQDR`` ``(n_out, 9)``, ``RXC``, ``RX``,
    ``SAT`` (bool) ``(n_out, nx)``, the plant's ``EXTRA``); ``nx``: the actuator forces,
    ``lo``'s length (9, or 10 with a commanded winch, its line pull last); ``hold`` steps
    a control period (0: the law at every stage); the sensors (``sens``: ``delay`` steps,
    noise rows ``nq``, ``nqd`` per control instant, resolutions ``resq``, ``resqd``), the
    rate limit ``rlim`` and lag ``lag`` (empty: none). ``status``: (stop code, its output
    sample, samples recorded, control instants); ends before a step when ``halt[0]`` is
    not zero (STOPPED). ``W``: the loop's zeroed scratch (:func:`scratch`).

    A run in pieces (a stepper): ``s0`` is the run's step at ``y`` (0: its start; the
    grid, the plant's and the law's stage points count from the run's start, the records
    from the piece's, the control instants on from ``status[3]``), and without
    ``finish`` the piece ends at its last step's state, neither evaluated nor recorded
    (the next piece's first sample)."""
    P, L = unowned(P), unowned(L)      # handed to the plant and the law at every stage
    # the arrays handed on at every stage, without their owner: the caller keeps them
    # alive for the call (their reference counts cost the rigid robot 3-4 %, measured)
    y, tt, qr, qdr, qddr, lo, hi, lag = unowned((y, tt, qr, qdr, qddr, lo, hi, lag))
    k1, k2, k3, k4, st, ym, dzb, Xc, X, Xh, Xhin, last, dzh, aux, hist, first = unowned(W)
    n = y.shape[0]
    n_pz = n_p + n_z
    nx = lo.shape[0]
    if s0 == 0:
        for j in range(n_p):
            first[j] = y[j]
    held = hold > 0
    period = h * hold
    ctrl = status[3]
    for s in range(n_steps + 1):
        if s == n_steps and not finish:
            return
        if halt[0] != 0:
            status[0] = STOPPED
            status[1] = s
            return
        g = s0 + s
        i0 = 2 * g
        if sens:
            for j in range(n_p):
                hist[g % (delay + 1), j] = y[j]
        if held and g % hold == 0:
            sense(y, ym, hist, first, g, delay, nq, nqd, resq, resqd, sens, ctrl, n_p)
            winch(P, i0, ym, Xh)
            command(L, P, i0, tt[i0], ym, n_p, qr[i0], qdr[i0], qddr[i0], Xh)
            for j in range(nx):
                if j < rlim.shape[0] and ctrl > 0:
                    step = rlim[j] * period
                    Xhin[j] = last[j] + min(max(Xh[j] - last[j], -step), step)
                else:
                    Xhin[j] = Xh[j]
                last[j] = Xhin[j]
            if n_z > 0:
                for j in range(nx):
                    X[j] = min(max(Xhin[j], lo[j]), hi[j])
                law_rate(L, P, i0, tt[i0], ym, n_p, qr[i0], qdr[i0], qddr[i0], Xh, X,
                         dzb)
                for j in range(n_z):
                    dzh[j] = dzb[n_p + j]
            ctrl += 1
            status[3] = ctrl
        if g == 0 and lag.shape[0] > 0:
            if not held:
                winch(P, i0, y, Xhin)
                command(L, P, i0, tt[i0], y, n_p, qr[i0], qdr[i0], qddr[i0], Xhin)
            for j in range(lag.shape[0]):
                y[n_pz + j] = Xhin[j]
        ok = evaluate(P, L, i0, tt[i0], y, k1, qr[i0], qdr[i0], qddr[i0], lo, hi, held, Xh,
                      Xhin, dzh, lag, n_p, n_z, Xc, X, aux)
        if s % out_every == 0:
            k = s // out_every
            for j in range(9):
                RQ[k, j] = y[IQ + j]
                RQD[k, j] = y[IQD + j]
                RQDD[k, j] = k1[IQD + j]
                RQR[k, j] = qr[i0, j]
                RQDR[k, j] = qdr[i0, j]
            for j in range(nx):
                RXC[k, j] = Xc[j]
                RX[k, j] = X[j]
                SAT[k, j] = Xc[j] < lo[j] or Xc[j] > hi[j]
            keep(P, EXTRA, k, y, k1, X, aux)
            status[2] = k + 1
            code = check(P, y, aux, ok)
            if code == OK:
                for j in range(n):
                    if not (np.isfinite(y[j]) and np.isfinite(k1[j])):
                        code = DIVERGED
            if code != OK:
                status[0] = code
                status[1] = k
                return
        if s == n_steps:
            break
        rk4_stage(y, k1, 0.5 * h, st)
        evaluate(P, L, i0 + 1, tt[i0 + 1], st, k2, qr[i0 + 1], qdr[i0 + 1], qddr[i0 + 1], lo,
                 hi, held, Xh, Xhin, dzh, lag, n_p, n_z, Xc, X, aux)
        rk4_stage(y, k2, 0.5 * h, st)
        evaluate(P, L, i0 + 1, tt[i0 + 1], st, k3, qr[i0 + 1], qdr[i0 + 1], qddr[i0 + 1], lo,
                 hi, held, Xh, Xhin, dzh, lag, n_p, n_z, Xc, X, aux)
        rk4_stage(y, k3, h, st)
        evaluate(P, L, i0 + 2, tt[i0 + 2], st, k4, qr[i0 + 2], qdr[i0 + 2], qddr[i0 + 2], lo,
                 hi, held, Xh, Xhin, dzh, lag, n_p, n_z, Xc, X, aux)
        rk4_combine(y, h, k1, k2, k3, k4)


def scratch(n: int, n_p: int, n_z: int, delay: int, nx: int = 9) -> tuple:
    """The loop's zeroed scratch ``W`` for a state of ``n`` entries (the plant's ``n_p``,
    the law's ``n_z``), ``nx`` actuator forces and a sensor delay of ``delay`` steps: the
    four RK4 slopes, the stage state, the measured state, the law's rate ``(n,)`` each;
    the command, the applied, held, held-in and last forces ``(nx,)`` each; the held law rate
    ``(max(n_z, 1),)``; the plant's ``aux`` ``(4,)``; the measurement history
    ``(delay + 1, n_p)`` and the first measured state ``(n_p,)``."""
    return (*(np.zeros(n) for _ in range(7)), *(np.zeros(nx) for _ in range(5)),
            np.zeros(max(n_z, 1)), np.zeros(4), np.zeros((delay + 1, n_p)), np.zeros(n_p))


#: The driver's own templates, instantiated in every namespace.
TEMPLATES = (quantised, evaluate, sense, loop)
#: The templates Python calls (:func:`instantiate` compiles them with a CPython wrapper).
FROM_PYTHON = ("loop", "sense")


def _text(f) -> str:
    """The source of the module that defines ``f`` (its code's bytes and constants where
    there is no source file)."""
    try:
        return inspect.getsource(inspect.getmodule(f))
    except (OSError, TypeError):
        return repr((f.__code__.co_code, f.__code__.co_consts, f.__code__.co_names))


def instantiate(kernels, law_templates: dict, names: dict, compiled: bool, key: str):
    """The driver's :func:`loop` in a namespace of its own.

    Args:
        kernels: The plant's kernel module (``prepare``, ``rhs``, ``check``, ``keep``,
            ``inverse``, ``gravity``, ``coords``, ``payload``, ``arm_tip``, ``winch``,
            ``winch_to``: compiled functions).
        law_templates: ``{name: function}``: the law's templates (``command``,
            ``law_rate`` and what they call), instantiated here.
        names: Constants of the namespace (``IQ``, ``IQD``).
        compiled: Compile the loop (Numba) or run it as Python.
        key: What tells this instance apart (the plant's and the law's names).

    Returns:
        The namespace: ``ns["loop"]`` the loop, ``ns["command"]``, ``ns["law_rate"]`` the
        law's (compiled, callable from compiled code only; or Python functions).
    """
    from offshore_crane.dynamics import compiled as c
    from offshore_crane.kernel_cache import INSTANCE, PROGRAM_DIGEST, njit

    ns: dict = {"__name__": __name__, "np": np, "OK": OK, "DIVERGED": DIVERGED, "STOPPED": STOPPED,
                "rk4_stage": rk4_stage, "rk4_combine": rk4_combine, INSTANCE: key, **names}
    for name in ("prepare", "rhs", "check", "keep", "inverse", "gravity", "coords",
                 "payload", "arm_tip", "winch", "winch_to"):
        ns[name] = getattr(kernels, name)
    if compiled:
        from offshore_crane.dynamics.views import unowned as strip

        ns["unowned"] = strip
    else:
        ns["unowned"] = unowned
    templates = {f.__name__: f for f in TEMPLATES} | dict(law_templates)
    parts = {id(f): f for f in [*templates.values(), kernels.rhs.py_func]}.values()
    from offshore_crane.dynamics import integrator

    stamp = f"{c.STAMP}{kernels.STAMP}{inspect.getsource(integrator)}"   # what it links
    ns[PROGRAM_DIGEST] = hashlib.sha256(
        f"{key}\n{stamp}\n{''.join(_text(f) for f in parts)}".encode()).hexdigest()
    # a template from a file Numba cannot cache beside (a notebook, a snippet): not cached
    cache = all(f.__code__.co_filename.endswith(".py") and
                os.path.isfile(f.__code__.co_filename) for f in templates.values())
    options = {**c.JIT, "cache": cache and c.JIT.get("cache", False)}
    # the templates the loop calls at every stage allocate nothing: no reference counts
    # (kernel_cache.LEAN); the loop keeps them: compiled LEAN it ran some 3 % slower
    # (interleaved runs, rigid robot and elastic lift, 2026-11-28)
    jit = njit(**options)
    inner = njit(**{**c.LEAN, **options}, no_cpython_wrapper=True)
    tag = hashlib.sha256(key.encode()).hexdigest()[:12]
    for name, f in templates.items():
        fn = types.FunctionType(f.__code__, ns, name, f.__defaults__)
        # a name of the instance's own: Numba names a compiled function's symbol by its
        # module, qualified name and argument types, and a library loaded from the disk
        # cache links its callees by those symbols, the first loaded one of a name
        # winning; two instances with one name and types (two plants' ``sense``, the
        # elastic plant's two variants' ``loop``) then ran each other's code (measured:
        # a heap overrun, a segfault later)
        fn.__qualname__, fn.__template__ = f"{name}__{tag}", name
        # called from Python: the loop and the sensors' model (a stepper's observation);
        # the rest only from the loop, compiled without the wrapper that unboxes Python
        # arguments (Numba's no_cpython_wrapper: such a function called from Python
        # crashes the process; nothing here does)
        ns[name] = (jit if name in FROM_PYTHON else inner)(fn) if compiled else fn
    return ns
