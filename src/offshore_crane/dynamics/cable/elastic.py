"""An elastic cable that can go slack and snap: the payload as a free point mass.

Model (docs/cable.md): the payload (mass m, the robot description's ``payload.mass``) at
``ρ`` from the tip (base axes), pulled towards it by a cable of unstretched length ``L``
(``payload.cable_length``, or a winch's ``L(t)``), axial stiffness ``EA`` [N] (a spring
``EA / L``) and damping ``c`` [N·s/m]: ``T = EA s / L + c ṡ`` for a stretch
``s = |ρ| − L > 0`` when that is positive, else 0 (a cable does not push). Relative to
the tip, ``ρ̈ = g − a_tip − (T / m) u + (F_s + F_d) / m``, ``u = ρ / |ρ|``, with the
rigid cable's sway damping as a force on the payload ``F_s``
(:func:`~offshore_crane.dynamics.sway.sway_damping_force`, ``payload.sway_damping``,
while the cable pulls) and the air's drag ``F_d = −½ ρ C_d A |v| v`` at the payload's
velocity v (``payload.drag_area``, ``payload.air_density``): the robot's motion is
prescribed, the payload's three coordinates free, slack phases simulated (the payload
flies) and the snap on re-tension resolved by the integrator:

- **step**: RK4 with ``substeps`` steps a sample interval, by default enough for
  :data:`STEPS_PER_PERIOD` steps in the shortest axial period ``2π √(m L_min / EA)``;
- **slack ↔ taut**: a step across which the cable changes state (the force's derivative
  jumps there and RK4 drops to low order) is done again in :data:`REFINE` steps;
- **checked**: the snap of a load released with slack against its closed form, the free
  fall while slack, the energy balance, the rigid cable as ``EA → ∞``
  (tests/dynamics/test_elastic_cable.py), and with sway damping and drag
  (tests/dynamics/test_cable_damping.py).

X takes the pull ``T u − F_s`` as a force on the robot at the payload's place
(``formulas.kane_sample_pull``: the damping's moment about the tip is the robot's), the
same Kane pass the winch uses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from offshore_crane import progress
from offshore_crane.conventions import AIR_DENSITY, GRAVITY
from offshore_crane.errors import InputError, NumericalError
from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.validation import as_gravity, as_samples

#: RK4 steps in the shortest axial period by default: the axial oscillation's amplitude
#: then drifts by ~1e-8 of itself a period (RK4's (ωh)⁶/144 per step at ωh = 2π/50).
STEPS_PER_PERIOD = 50
#: The smallest static strain ``m g₀ / EA`` of a cable under its payload (g₀ standard
#: gravity), which bounds EA by ``m g₀ / STRAIN_MIN``: a steel wire rope (E ≈ 100 GPa on its
#: metal, breaking near 1.8 GPa) rated at a fifth to a tenth of its breaking load works at
#: 2-4e-3, so 1e-7 is some 10⁴ times stiffer than any rope rigged for its load (and below
#: the 2e-7 that the tests of the rigid limit EA → ∞ reach). A stiffer cable stretches
#: less than 0.1 µm a metre: the rigid cable (no ``ea``) is its model, and the step rule's
#: period ``∝ 1/√EA`` would make RK4's steps vanish.
STRAIN_MIN = 1e-7
#: RK4 steps a sample interval at most (the step rule's bound): the axial period must be
#: at least ``STEPS_PER_PERIOD / MAX_SUBSTEPS`` = 1/20 of the sample interval (a ringing
#: faster than that shows in the samples at random phases only), and a sample's work stays
#: bounded (a few hundred µs: a run stops within that of a signal).
MAX_SUBSTEPS = 1000
#: Steps a slack ↔ taut step is redone in: the kink's local error, O(h²) of the step,
#: falls by REFINE² (measured: the analytic snap load to ~1e-6 at 50 steps a period).
REFINE = 64


@dataclass
class ElasticResult:
    """The robot's inverse dynamics with its payload on an elastic cable.

    Attributes:
        t: ``(N,)`` [s]. q, qd, qdd: ``(N, 9)`` the robot's prescribed motion.
        X: ``(N, 9)`` actuator forces [N·m, N], the cable's pull included.
        position, velocity: ``(N, 3)`` the payload from the tip [m] and relative to it
            [m/s], base axes.
        payload, payload_velocity: ``(N, 3)`` the payload in the base frame [m, m/s].
        tension: ``(N,)`` [N] (0 while slack); stretch: ``(N,)`` ``|ρ| − L`` [m].
        force_tip: ``(N, 3)`` the cable's pull on the robot [N], base axes: ``T u − F_s``,
            acting at the payload's place (``F_s`` the sway damping's force on the
            payload, whose reaction the tip takes with the moment ``−ρ × F_s``).
        hoist: ``(N, 3)`` the winch's L [m], L̇, L̈, or None (fixed length).
        mass [kg], length [m] (unstretched, fixed), ea [N], damping [N·s/m].
        static_tension: ``m |g|`` [N], what the ratios are taken against.
        step: RK4's step [s]; substeps: steps a sample interval; refined: steps redone
        at a slack ↔ taut change; axial_period: the shortest ``2π √(m L / EA)`` [s].
        sway_force: ``(N, 3)`` the sway damping's force on the payload ``F_s`` [N] (base
            axes; 0 while slack, or resting on a deck).
        drag: ``(N, 3)`` the air's drag on the payload [N] (base axes; 0 on a deck).
        sway_damping: [N·m·s/rad]; drag_area: C_d·A [m²]; air_density: [kg/m³].
        airborne: ``(first, stop)`` the samples with the load off the deck,
            ``first ≤ k < stop`` (a lift-off's record rests on it before, a set-down's
            after; its cable is neither slack nor judged there).
        event: The lift's critical instant (:class:`~.liftoff.LiftOff`,
            :class:`~.liftoff.SetDown`), or None.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    X: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    payload: np.ndarray
    payload_velocity: np.ndarray
    tension: np.ndarray
    stretch: np.ndarray
    force_tip: np.ndarray
    hoist: np.ndarray | None
    mass: float
    length: float
    ea: float
    damping: float
    static_tension: float
    step: float
    substeps: int
    refined: int
    axial_period: float
    sway_force: np.ndarray | None = None
    drag: np.ndarray | None = None
    sway_damping: float = 0.0
    drag_area: float = 0.0
    air_density: float = AIR_DENSITY
    airborne: tuple = (0, None)
    event: object = None

    def __len__(self) -> int:
        return len(self.t)

    @property
    def plumb_angle(self) -> np.ndarray:
        """``(N,)`` the cable's angle from the base's vertical (−z), the plumb line [rad].
        Not the sway, which every report measures from the tip's vertical
        (:func:`~offshore_crane.dynamics.cable.tip.sway_angle`: the crane's side-lead
        and off-lead, the ship's roll included)."""
        rho = self.position
        return np.arccos(np.clip(-rho[:, 2] / np.linalg.norm(rho, axis=1), -1.0, 1.0))

    @property
    def slack(self) -> np.ndarray:
        """``(N,)`` True where the cable does not pull."""
        return ~(self.tension > 0.0)

    @property
    def tension_ratio(self) -> np.ndarray:
        """``(N,)`` ``T / (m |g|)``: the slack criterion reads its minimum, the snap
        load its maximum."""
        return self.tension / self.static_tension

    def time_slack(self) -> float:
        """Time the cable spent slack [s] (:func:`~.lift.time_slack`)."""
        from offshore_crane.dynamics.cable.lift import time_slack

        return time_slack(self.t, self.tension)

    def peak_tension(self) -> float:
        """The largest tension [N], refined between samples by the parabola through the
        largest sample and its neighbours (the snap's peak falls between samples), once
        the load is airborne."""
        T = self.tension[slice(*self.airborne)]
        k = int(np.argmax(T))
        if 0 < k < len(T) - 1:
            a, b, c = T[k - 1], T[k], T[k + 1]
            den = a - 2.0 * b + c
            if den < 0.0:
                return float(b - 0.125 * (c - a) ** 2 / den)
        return float(T[k])


def check_cable(ea, damping, mass: float | None = None) -> None:
    """An elastic cable's EA [N] (finite, > 0; with the payload's ``mass`` [kg], at most
    ``mass g₀ /`` :data:`STRAIN_MIN`) and axial damping [N·s/m] (finite, ≥ 0).

    Raises:
        InputError: naming the value, its unit and its bound.
    """
    for name, value, low, unit in (("ea", ea, "> 0", "N"), ("damping", damping, ">= 0",
                                                            "N·s/m")):
        ok = (isinstance(value, (int, float, np.floating)) and not isinstance(value, bool)
              and math.isfinite(value) and (value > 0 if low == "> 0" else value >= 0))
        if not ok:
            raise InputError(f"cable {name} = {value!r} {unit}: give a finite number {low}",
                             name=name)
    g0 = float(np.linalg.norm(GRAVITY))
    if mass is not None and ea * STRAIN_MIN > mass * g0:
        raise InputError(
            f"cable ea = {ea:.4g} N: stiffer than any rope for a {mass:.4g} kg payload "
            f"(static strain m·g/EA = {mass * g0 / ea:.2g} < {STRAIN_MIN:g}): give ea <= "
            f"{mass * g0 / STRAIN_MIN:.4g} N, or no ea (the rigid cable)", name="ea")


def check_steps(ea: float, mass: float, length: float, dt: float, substeps=None) -> int:
    """RK4's steps a sample interval ``dt`` [s] for a cable of EA [N] carrying ``mass``
    [kg] at its shortest length ``length`` [m]: ``substeps``, or by the step rule
    :data:`STEPS_PER_PERIOD` steps in the axial period ``2π √(m L / EA)``; at most
    :data:`MAX_SUBSTEPS` (the step may not vanish).

    Raises:
        InputError: ``substeps`` not an integer ≥ 1, or more steps than the bound (names
            the axial period, the sample interval and what to change).
    """
    if substeps is not None:
        if (isinstance(substeps, bool) or not isinstance(substeps, (int, np.integer))
                or not 1 <= substeps <= MAX_SUBSTEPS):
            raise InputError(f"substeps = {substeps!r} must be an integer >= 1 and <= "
                             f"{MAX_SUBSTEPS} (RK4 steps a sample interval)", name="substeps")
        return int(substeps)
    period = 2.0 * math.pi * math.sqrt(mass * length / ea)
    need = dt * STEPS_PER_PERIOD / period
    if not need <= MAX_SUBSTEPS:
        ea_max = mass * length * (2.0 * math.pi * MAX_SUBSTEPS / (STEPS_PER_PERIOD * dt)) ** 2
        raise InputError(
            f"cable ea = {ea:.4g} N: axial period {period:.3g} s (m {mass:.4g} kg, L "
            f"{length:.4g} m) under 1/{MAX_SUBSTEPS // STEPS_PER_PERIOD} of the sample "
            f"interval {dt:.3g} s (> {MAX_SUBSTEPS} RK4 steps a sample): give ea <= "
            f"{ea_max:.4g} N or sample faster", name="ea")
    return max(1, math.ceil(need))


def elastic_inverse_dynamics(robot, q, qd, qdd, *, t, ea: float, damping: float = 0.0,
                             reference=None, gravity=GRAVITY, hoist=None, initial=None,
                             initial_velocity=(0.0, 0.0, 0.0), substeps: int | None = None,
                             limits: bool = True, checks: bool = True,
                             thresholds: ws.Thresholds = ws.Thresholds()) -> ElasticResult:
    """Actuator forces of the prescribed motion with the payload on an elastic cable.

    Args:
        robot: With a payload on a cable (``payload.cable_length > 0``: the unstretched
            length, ``payload.mass``; ``payload.sway_damping``, ``payload.drag_area`` and
            ``payload.air_density`` damp its flight).
        q, qd, qdd: ``(N, 9)`` the robot's motion [m, rad], rates, accelerations.
        t: ``(N,)`` uniform times [s], N ≥ 2.
        ea: Axial stiffness EA [N], finite and > 0.
        damping: Axial damping c [N·s/m], ≥ 0.
        reference: ``reference(t) -> (q, qd, qdd)`` at the midpoints (analytic motions);
            None: quintic Hermite interpolation of the samples.
        gravity: ``(3,)`` [m/s²], base frame.
        hoist: A winch ``hoist(t) -> (L, L̇, L̈)`` (:func:`~.hoist.hoist_profile`), or
            None: the fixed ``payload.cable_length``.
        initial: ``(3,)`` the payload from the tip at ``t[0]`` [m], base axes; None:
            hanging along g at the static stretch.
        initial_velocity: ``(3,)`` relative to the tip [m/s].
        substeps: RK4 steps a sample interval, at most :data:`MAX_SUBSTEPS`; None:
            :data:`STEPS_PER_PERIOD` a period (:func:`check_steps`).
        limits, checks, thresholds: As :func:`offshore_crane.inverse_dynamics`.

    Raises:
        InputError: EA or c out of range (EA above the payload's bound
            :data:`STRAIN_MIN`, or an axial period the samples' step rule cannot resolve
            in :data:`MAX_SUBSTEPS` steps), bad shapes, an initial position at the tip.
        NumericalError: the payload reaches the tip (a non-finite state).
        WorkspaceError, SingularConfigurationError: as the inverse dynamics.
    """
    from offshore_crane.dynamics.cable.tip import tip_positions
    from offshore_crane.dynamics.cable.forces import kane_forces
    from offshore_crane.dynamics.cable.grid import cable_robot, motion_samples, stage_grid
    from offshore_crane.dynamics.cable import elastic_kernels as ek
    from offshore_crane.dynamics.cable.hoist import hoist_grid
    from offshore_crane.dynamics.constants import cable_arrays
    from offshore_crane.dynamics.runtime import compiled_kernels

    check_cable(ea, damping)
    robot = cable_robot(robot)
    q, qd, qdd, t, dt = motion_samples(q, qd, qdd, t)
    N = q.shape[0]
    g = as_gravity(gravity)
    m = float(robot.hybrid.cable.mass[-1])
    check_cable(ea, damping, m)
    L0 = float(robot.hybrid.cable_length)
    tt, Q, Qd, Qdd = stage_grid(t, q, qd, qdd, reference, 1)
    Lh = np.array([[L0, 0.0, 0.0]]) if hoist is None else hoist_grid(hoist, tt)
    L_min = float(Lh[:, 0].min())
    period = 2.0 * math.pi * math.sqrt(m * L_min / float(ea))
    substeps = check_steps(float(ea), m, L_min, dt, substeps)
    gn = float(np.linalg.norm(g))
    if initial is None:
        down = g / gn if gn > 0 else np.array([0.0, 0.0, -1.0])
        initial = down * Lh[0, 0] * (1.0 + m * gn / float(ea))
    rho0 = as_samples("initial", initial, width=3)[0].reshape(3)
    rate0 = as_samples("initial_velocity", initial_velocity, width=3)[0].reshape(3)
    if not np.linalg.norm(rho0) > 0:
        raise InputError("initial = (0, 0, 0) m puts the payload at the tip: give its "
                         "position from the tip", name="initial")
    compiled_kernels()
    arrays = cable_arrays(robot)
    Y = np.full((N, 11), np.nan)
    status = np.zeros(3)
    y0 = np.concatenate([rho0, rate0])
    sway, drag = np.array(robot.hybrid.sway_damping, dtype=float), float(robot.hybrid.drag)
    stop = progress.stop_flag()
    progress.run_polled(
        lambda: ek.integrate(arrays.flat, arrays.layout, arrays.prismatic, Q, Qd, Qdd, Lh,
                             g, int(substeps), REFINE, dt, float(ea), float(damping), sway,
                             drag, m, y0, Y, status, stop),
        lambda: progress.filled_rows(Y), N, "sample", "elastic cable", stop)
    if int(status[0]) != ek.OK:
        k = int(status[1])
        raise NumericalError(f"elastic cable: the payload's state is not finite at sample {k} "
                             f"(t = {t[k]:.6g} s; it reached the tip?): check the motion "
                             "and the cable", index=k, name="elastic")
    rho = np.ascontiguousarray(Y[:, 0:3])
    sway_force = Y[:, 8:11].copy()
    pull = Y[:, 6:7] * rho / np.linalg.norm(rho, axis=1)[:, None] - sway_force
    zeros = np.zeros((N, 6))
    X, F, kappa = kane_forces(robot, t, q, qd, qdd, zeros, g, limits, checks, thresholds,
                               P=pull, at=rho)
    p_tip, v_tip = tip_positions(robot, q, qd)
    L = None if hoist is None else np.ascontiguousarray(Lh[::2])
    velocity = v_tip + Y[:, 3:6]
    return ElasticResult(
        t=t, q=q, qd=qd, qdd=qdd, X=X, position=rho.copy(), velocity=Y[:, 3:6].copy(),
        payload=p_tip + rho, payload_velocity=velocity, tension=Y[:, 6].copy(),
        stretch=Y[:, 7].copy(), force_tip=pull, hoist=L, mass=m, length=L0, ea=float(ea),
        damping=float(damping), static_tension=m * gn, step=dt / substeps,
        substeps=int(substeps), refined=int(status[2]), axial_period=period,
        sway_force=sway_force, drag=drag_forces(velocity, drag), sway_damping=float(sway[0]),
        drag_area=float(robot.hybrid.drag_area), air_density=float(robot.hybrid.air_density))


def drag_forces(v: np.ndarray, drag: float) -> np.ndarray:
    """``(N, 3)`` the air's drag on the payload [N] at its velocities ``v`` ``(N, 3)``
    [m/s] relative to still air, ``drag`` = ``½ ρ C_d A`` [kg/m]
    (:func:`offshore_crane.dynamics.sway.drag_force` on NumPy arrays)."""
    from offshore_crane.dynamics import backends

    if drag == 0.0:
        return np.zeros_like(v)
    return np.stack(backends.NUMPY.drag_force(tuple(v.T), drag), axis=-1)
