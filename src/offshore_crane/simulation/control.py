"""A controller: a law of the registry by name (:mod:`offshore_crane.simulation.laws`)
and its options.

The laws (``docs/simulation.md``; with a hanging load ``docs/cable.md``):

- ``"computed-torque"``: ``X = ID_model(q, q̇, q̈_ref + Kd (q̇_ref − q̇) + Kp (q_ref − q))``
  at the *measured* state, with the controller's own robot model. With an exact model the
  closed-loop error obeys ``ë + Kd ė + Kp e = 0`` in each coordinate. Gains per coordinate
  q1..q9: ``kp`` [1/s²], ``kd`` [1/s].
- ``"pd-gravity"``: ``X = ID_model(q, 0, 0) + Kp (s_ref − s) + Kd (ṡ_ref − ṡ)`` on the
  actuator coordinates ``s`` (arm joints q7..q9 and the six leg lengths, in the order of X):
  gravity compensation plus a joint-space PD. Gains per actuator: ``kp`` [N·m/rad, N/m],
  ``kd`` [N·m·s/rad, N·s/m].
- ``"pd"``: the same PD without gravity compensation.
- ``"none"``: X = 0 (a free, unactuated motion; for energy checks).
- ``"pid"``: PD with gravity compensation plus an integral term with anti-windup
  (:mod:`offshore_crane.simulation.laws.pid`; gains ``ki``, tracking time ``windup``).
- ``"anti-sway"``: computed torque with a reference shift that damps a hanging load's
  swing (``anti_sway=ζ`` selects it).
- ``"arm-compensation"``: computed torque whose arm reference is solved on line from the
  measured platform, holding the tip over its still-ship aim (or a moving ``target``;
  :mod:`offshore_crane.simulation.laws.arm_compensation`).
- ``"arm-winch-compensation"``: the same, and a commanded winch's pull holding the
  payload's height (:mod:`offshore_crane.simulation.laws.arm_winch_compensation`).

Options: actuator saturation (each X_k clipped to ``[lower_k, upper_k]``, push and pull
apart: the actuators' capacities; the time spent saturated is reported, never silent), a
model mismatch (``model``: the robot the controller believes in, e.g. a heavier payload),
measurement noise (Gaussian, standard deviations per coordinate for q and q̇, seeded) and a
control rate (sample-and-hold of X between control instants; ``None``: the law is
evaluated at every integrator stage, a continuous controller).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from offshore_crane.conventions import ACTUATORS
from offshore_crane.errors import InputError

from offshore_crane.simulation.laws import law_class, names

#: The registered laws' names (:mod:`offshore_crane.simulation.laws`).
LAWS = names()
#: Default computed-torque gains: critically damped, natural frequency 20 rad/s (3.2 Hz,
#: well above Table 1's 0.5 rad/s and a ship's 0.3-1.5 rad/s motions at model scale).
CT_OMEGA = 20.0
#: Default PD gains on the actuator coordinates, for the lab-scale placeholder robot:
#: stiffness [N·m/rad for the arm joints, N/m for the slider and legs] and damping.
PD_KP = np.array([400.0, 200.0, 2.0e3, 2.0e5, 2.0e5, 2.0e5, 2.0e5, 2.0e5, 2.0e5])
PD_KD = np.array([40.0, 20.0, 100.0, 4.0e3, 4.0e3, 4.0e3, 4.0e3, 4.0e3, 4.0e3])


def _gains(name: str, value, default: np.ndarray) -> np.ndarray:
    if value is None:
        return default.copy()
    try:
        g = np.broadcast_to(np.asarray(value, dtype=float), (9,)).copy()
    except (TypeError, ValueError):
        raise InputError(f"{name} must be one number or 9 numbers, got {value!r}",
                         name=name) from None
    bad = ~(np.isfinite(g) & (g >= 0.0))
    if bad.any():
        k = int(np.argmax(bad))
        raise InputError(f"{name}[{k}] = {float(g[k])!r}: gains must be finite and ≥ 0",
                         name=name)
    return g


@dataclass(frozen=True)
class Controller:
    """A control law and its options (module docstring).

    Attributes:
        law: One of :data:`LAWS`.
        kp, kd: ``(9,)`` gains (or one number for all); defaults: computed torque
            ``Kp = ω²``, ``Kd = 2ω`` with ω = :data:`CT_OMEGA`; PD :data:`PD_KP`,
            :data:`PD_KD`.
        rate: Control rate [Hz] (sample-and-hold), or None for a continuous law.
        lower, upper: ``(9,)`` actuator limits [N·m, N] (push and pull apart; −inf/inf
            for none); None (the default): the robot's capacities
            (:meth:`bounds`).
        saturation: False: no limits at all (lower/upper must then be None).
        model: The robot the controller uses (None: the simulated robot itself).
        noise_q, noise_qd: ``(9,)`` standard deviations of the measurement noise [m, rad]
            and [m/s, rad/s] (zeros: none); ``seed`` seeds it.
        anti_sway: With a payload on a cable: the damping ratio ζ ≥ 0 the anti-sway law
            adds to the swing (suspension-point velocity feedback through the platform's
            horizontal reference, :mod:`offshore_crane.simulation.laws.anti_sway`); None:
            none. Given, the law is ``"anti-sway"``.
        ki: ``(9,)`` integral gains of ``"pid"`` (or one number) [N·m/(rad·s), N/(m·s)];
            None: ``Kp / T_i`` with ``T_i = 4 Kd / Kp``.
        windup: The anti-windup's tracking time constant T_t [s] > 0 of ``"pid"``;
            None: ``√(T_i T_d)``.
        function: A Python law ``function(t, q, qd, q_ref, qd_ref, qdd_ref) -> X``
            (:mod:`offshore_crane.simulation.laws.python`) run with these options (a
            control rate, saturation); ``law`` is then ``"python"``.
        target: A moving aim for ``"arm-compensation"``: ``target(t (n,)) -> (x, v, a)``
            each ``(n, 3)``, the displacement of a point on a second vessel's deck [m,
            m/s, m/s²], base axes (:class:`~offshore_crane.motion.sea.DeckMotion`); None:
            the still-ship point.
    """

    law: str = "computed-torque"
    kp: object = None
    kd: object = None
    rate: float | None = None
    lower: object = None
    upper: object = None
    saturation: bool = True
    model: object = None
    noise_q: object = None
    noise_qd: object = None
    seed: int = 0
    anti_sway: float | None = None
    ki: object = None
    windup: float | None = None
    function: object = None
    target: object = None
    _arrays: dict = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self):
        if self.function is not None:
            if not callable(self.function):
                raise InputError(f"function = {self.function!r}: a Python law must be "
                                 "callable as function(t, q, qd, q_ref, qd_ref, qdd_ref)",
                                 name="function")
            object.__setattr__(self, "law", "python")
        else:
            law_class(self.law)                # a registered law ("did you mean")
        ct = law_class(self.law).ct_gains if self.law != "python" else False
        kp = _gains("kp", self.kp, np.full(9, CT_OMEGA ** 2) if ct else PD_KP)
        kd = _gains("kd", self.kd, np.full(9, 2.0 * CT_OMEGA) if ct else PD_KD)
        if self.rate is not None:
            r = float(self.rate) if isinstance(self.rate, (int, float)) else math.nan
            if not (math.isfinite(r) and r > 0.0):
                raise InputError(f"control rate = {self.rate!r} Hz: must be positive and "
                                 "finite (or None for a continuous controller)", name="rate")
        lower = np.full(9, -np.inf) if self.lower is None else np.asarray(self.lower, float)
        upper = np.full(9, np.inf) if self.upper is None else np.asarray(self.upper, float)
        if lower.shape != (9,) or upper.shape != (9,) or np.isnan(lower).any() or \
                np.isnan(upper).any() or (lower > upper).any():
            raise InputError("actuator limits lower/upper must be 9 numbers each with lower "
                             f"≤ upper, in the order {', '.join(ACTUATORS)}", name="lower")
        if not isinstance(self.saturation, bool):
            raise InputError(f"saturation = {self.saturation!r}: must be true or false",
                             name="saturation")
        if not self.saturation and (self.lower is not None or self.upper is not None):
            raise InputError("saturation = false with actuator limits lower/upper given: "
                             "drop one of them", name="saturation")
        if self.anti_sway is not None:
            z = self.anti_sway
            if isinstance(z, bool) or not isinstance(z, (int, float)) or not (
                    math.isfinite(z) and z >= 0.0):
                raise InputError(f"anti_sway = {z!r}: the damping ratio it adds to the swing "
                                 "must be a finite number ≥ 0", name="anti_sway")
            if self.law not in ("computed-torque", "anti-sway"):
                raise InputError(f"anti_sway works through the computed-torque law, not "
                                 f"{self.law!r}", name="anti_sway")
        elif self.law == "anti-sway":
            raise InputError("law 'anti-sway' needs the damping ratio it adds to the swing: "
                             "give anti_sway = ζ", name="anti_sway")
        if self.target is not None and (self.law not in ("arm-compensation",
                                                         "arm-winch-compensation")
                                        or not callable(self.target)):
            raise InputError(f"target = {self.target!r}: a moving aim is the "
                             "'arm-compensation' law's (and 'arm-winch-compensation''s), a "
                             "callable target(t) -> (x, v, a)", name="target")
        if self.ki is not None and self.law != "pid":
            raise InputError(f"ki: integral gains are the 'pid' law's, not {self.law!r}",
                             name="ki")
        if self.windup is not None:
            w = self.windup
            if self.law != "pid" or isinstance(w, bool) or not isinstance(w, (int, float)) \
                    or not (math.isfinite(w) and w > 0.0):
                raise InputError(f"windup = {w!r} s: the 'pid' law's anti-windup time "
                                 "constant, a finite number > 0", name="windup")
        noise = []
        for name, value in (("noise_q", self.noise_q), ("noise_qd", self.noise_qd)):
            n = np.zeros(9) if value is None else _gains(name, value, np.zeros(9))
            noise.append(n)
        ki = None if self.ki is None else _gains("ki", self.ki, np.zeros(9))
        self._arrays.update(kp=kp, kd=kd, lower=lower, upper=upper, noise_q=noise[0],
                            noise_qd=noise[1], ki=ki)

    @property
    def law_name(self) -> str:
        """The registry's law this controller runs: ``"anti-sway"`` when ``anti_sway``
        is given, else :attr:`law`."""
        if self.function is not None:
            return "python"
        return "anti-sway" if self.anti_sway or self.law == "anti-sway" else self.law

    @property
    def integral_gains(self) -> np.ndarray | None:
        """``ki`` ``(9,)`` as given, or None (the PID's default)."""
        return self._arrays["ki"]

    @property
    def gains(self) -> tuple[np.ndarray, np.ndarray]:
        """``(kp, kd)`` as ``(9,)`` arrays."""
        return self._arrays["kp"], self._arrays["kd"]

    @property
    def limits(self) -> tuple[np.ndarray, np.ndarray]:
        """``(lower, upper)`` actuator limits ``(9,)`` as given (±inf where not)."""
        return self._arrays["lower"], self._arrays["upper"]

    def bounds(self, robot) -> tuple[np.ndarray, np.ndarray]:
        """``(lower, upper)`` ``(9,)`` [N·m, N] the applied forces are clipped to on
        ``robot`` (the plant): ``lower``/``upper`` where given, else the robot
        description's capacities ``(−pull_max, push_max)`` (``inf`` where the description
        gives none); ±inf everywhere with ``saturation=False``."""
        lower, upper = self.limits
        if not self.saturation:
            return lower, upper
        caps = robot.capacities
        lo = -np.asarray(caps.pull_max, float) if self.lower is None else lower
        hi = np.asarray(caps.push_max, float) if self.upper is None else upper
        if (lo > hi).any():
            k = int(np.argmax(lo > hi))
            raise InputError(f"actuator {ACTUATORS[k]}: lower limit {lo[k]:g} > upper limit "
                             f"{hi[k]:g} (given limits against the robot's capacities)",
                             name="lower")
        return lo, hi

    @property
    def noise(self) -> tuple[np.ndarray, np.ndarray]:
        """Standard deviations ``(noise_q, noise_qd)`` ``(9,)``."""
        return self._arrays["noise_q"], self._arrays["noise_qd"]
