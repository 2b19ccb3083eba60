"""What stands between a law and its plant: sensors (noise, delay, quantisation of the
measured q and q̇) and actuators (rate limit, first-order lag, saturation), described in a
scene's ``[sensors]`` and ``[actuators]`` and applied by the driver
(:mod:`offshore_crane.simulation.driver`) the same way to every law and plant.

Sensors act at the control instants of a sampled law (``[control] rate``): the measured
state is the plant's state ``delay`` seconds earlier (a whole number of steps; the initial
state before the run has that much history), plus Gaussian noise (standard deviations per
coordinate, drawn with ``seed`` beforehand, one row per control instant), rounded to the
resolution (``round(x / r) r``; 0: none).

Actuators: the command held over a control period changes by at most ``rate_limit``
[N·m/s, N/s] × the period from the last one (the first command passes); a first-order lag
``τ Ẋ_a + X_a = X_cmd`` (``lag`` τ [s] > 0; its output is part of the integrated state,
starting at the first command); then the capacities clip the force (the controller's
``lower``/``upper``, the robot's capacities by default).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import InputError


def _nine(name: str, value, unit: str, positive: bool = False,
          winch: bool = False) -> np.ndarray | None:
    """None, or ``value`` as ``(9,)`` finite numbers ≥ 0 (> 0 with ``positive``); with
    ``winch``, 10 numbers too (a commanded winch's line pull last)."""
    if value is None:
        return None
    try:
        shape = (10,) if winch and np.shape(value) == (10,) else (9,)
        a = np.broadcast_to(np.asarray(value, dtype=float), shape).copy()
    except (TypeError, ValueError):
        more = " (10 with a commanded winch's line pull last)" if winch else ""
        raise InputError(f"{name} must be one number or 9 numbers{more} [{unit}], got "
                         f"{value!r}", name=name) from None
    bad = ~(np.isfinite(a) & ((a > 0.0) if positive else (a >= 0.0)))
    if bad.any():
        k = int(np.argmax(bad))
        need = "> 0" if positive else "≥ 0"
        raise InputError(f"{name}[{k}] = {float(a[k])!r} {unit}: must be finite and {need}",
                         name=name)
    return a


@dataclass(frozen=True)
class Sensors:
    """Sensor models of the measured q and q̇ (module docstring).

    Attributes:
        noise_q, noise_qd: Standard deviations [m, rad] and [m/s, rad/s], one number or
            ``(9,)``; None: none.
        delay: [s] ≥ 0, a whole number of integration steps.
        resolution_q, resolution_qd: Quantisation steps [m, rad], [m/s, rad/s]; None: none.
        seed: Seeds the noise.
    """

    noise_q: object = None
    noise_qd: object = None
    delay: float = 0.0
    resolution_q: object = None
    resolution_qd: object = None
    seed: int = 0

    def __post_init__(self):
        for name, unit in (("noise_q", "m, rad"), ("noise_qd", "m/s, rad/s"),
                           ("resolution_q", "m, rad"), ("resolution_qd", "m/s, rad/s")):
            object.__setattr__(self, name, _nine(name, getattr(self, name), unit))
        d = self.delay
        if isinstance(d, bool) or not isinstance(d, (int, float)) or not (
                math.isfinite(d) and d >= 0.0):
            raise InputError(f"sensor delay = {d!r} s: must be a finite number ≥ 0",
                             name="delay")
        if isinstance(self.seed, bool) or not isinstance(self.seed, int):
            raise InputError(f"sensor seed = {self.seed!r}: must be an integer", name="seed")

    @property
    def active(self) -> bool:
        """True when any model changes the measurement."""
        return bool(self.delay) or any(
            x is not None and np.any(x) for x in (self.noise_q, self.noise_qd,
                                                   self.resolution_q, self.resolution_qd))

    def delay_steps(self, step: float) -> int:
        """The delay in integration steps.

        Raises:
            InputError: a delay that is not a whole number of steps (to 1e-9 relative).
        """
        ratio = self.delay / step
        if abs(ratio - round(ratio)) > 1e-9 * max(1.0, ratio):
            raise InputError(f"sensor delay = {self.delay:g} s is not a multiple of the "
                             f"integration step {step:g} s ({ratio:.6g} steps): give a "
                             "whole number of steps", name="delay")
        return int(round(ratio))

    def noise(self, n_ctrl: int) -> tuple[np.ndarray, np.ndarray]:
        """``(n_ctrl, 9)`` noise of q and of q̇, drawn from ``seed`` (q's rows first)."""
        rng = np.random.default_rng(self.seed)
        sq = np.zeros(9) if self.noise_q is None else self.noise_q
        sqd = np.zeros(9) if self.noise_qd is None else self.noise_qd
        return rng.normal(size=(n_ctrl, 9)) * sq, rng.normal(size=(n_ctrl, 9)) * sqd

    @staticmethod
    def quantised(x: np.ndarray, resolution: np.ndarray | None) -> np.ndarray:
        """``round(x / r) r`` where ``r`` > 0, ``x`` elsewhere."""
        if resolution is None or not np.any(resolution):
            return x
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(resolution > 0.0, np.round(x / resolution) * resolution, x)


@dataclass(frozen=True)
class Actuators:
    """Actuator models between the law's command and the plant (module docstring).

    Attributes:
        rate_limit: ``(9,)`` or one number [N·m/s, N/s] > 0; None: none.
        lag: First-order time constant τ [s] > 0, one number or ``(9,)``; None: none.

    One number applies to every force the law commands, a commanded winch's line pull
    too; 9 numbers to the robot's actuators (the winch's pull then unmodelled); 10 to
    them and the winch's pull (:meth:`for_forces`).
    """

    rate_limit: object = None
    lag: object = None

    def __post_init__(self):
        one = {k: np.ndim(getattr(self, k)) == 0 for k in ("rate_limit", "lag")}
        object.__setattr__(self, "rate_limit", _nine("rate_limit", self.rate_limit,
                                                     "N·m/s, N/s", positive=True, winch=True))
        object.__setattr__(self, "lag", _nine("lag", self.lag, "s", positive=True,
                                              winch=True))
        object.__setattr__(self, "_one", one)

    def for_forces(self, nx: int) -> tuple[np.ndarray, np.ndarray]:
        """``(lag, rate_limit)`` for a law commanding ``nx`` forces (9, or 10 with a
        commanded winch): each ``(nx,)``, or ``(9,)`` when 9 numbers were given (the
        winch's pull unmodelled), or ``(0,)`` when not given.

        Raises:
            InputError: 10 numbers given for 9 forces (no commanded winch).
        """
        out = []
        for name in ("lag", "rate_limit"):
            a = getattr(self, name)
            if a is None:
                out.append(np.zeros(0))
                continue
            if len(a) > nx:
                raise InputError(f"actuators {name}: 10 numbers given, but the plant has no "
                                 "commanded winch (actuators.winch.reflected_mass): give 9",
                                 name=name)
            out.append(np.full(nx, a[0]) if self._one[name] else a)
        return out[0], out[1]

    @property
    def active(self) -> bool:
        return self.rate_limit is not None or self.lag is not None

    def limited(self, X_cmd: np.ndarray, X_last: np.ndarray | None,
                period: float) -> np.ndarray:
        """The command after the rate limit over one control ``period`` [s]."""
        if self.rate_limit is None or X_last is None:
            return X_cmd
        r = self.rate_limit * period
        return X_last + np.clip(X_cmd - X_last, -r, r)
