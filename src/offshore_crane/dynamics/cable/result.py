"""What the hanging load's inverse dynamics returns (:class:`CableResult`)."""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np


@dataclass
class CableResult:
    """Inverse dynamics of the robot with its hanging payload, sampled like the input.

    Attributes:
        t: ``(N,)`` [s].
        q, qd, qdd: ``(N, 9)`` the robot's prescribed motion [m, rad], rates, accelerations.
        X: ``(N, 9)`` actuator forces ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]``, the cable's
            pull included.
        sway: ``(N, 2)`` φ1, φ2 [rad] (``arm_tip`` frame, see the module docstring).
        sway_rate: ``(N, 2)`` [rad/s]; sway_accel: ``(N, 2)`` [rad/s²].
        tension: ``(N,)`` the cable's tension [N] (> 0 taut): the pull's part along it.
        force_tip: ``(N, 3)`` the cable's pull on the robot [N], base frame,
            ``m (g − a_p) + f`` (``f`` the payload's drag), acting at the payload's place
            (the sway damping's moment about the tip leaves it off the cable's line).
        residual: ``(N, 2)`` Kane's rows of the sway speeds at the result [N·m], the sway
            damping's and the drag's generalized forces included (zero up to round-off:
            the sway accelerations solve them).
        slack: ``(N,)`` True where the tension is ≤ 0 (only with ``slack="warn"``).
        condition: ``(N,)`` the Stewart system's condition number (NaN without checks).
        sway_condition: worst ``1 / cos²φ2`` met (the sway inertia's condition).
        length, mass: The cable length [m] and payload mass [kg] (from the URDF).
        method, step: The path and the RK4 step [s].
        hoist: ``(N, 3)`` the cable's length [m], rate [m/s] and acceleration [m/s²]
            when a winch hoists it (``inverse_dynamics(hoist=...)``), else None; the
            winch then holds the line pull ``tension`` (:attr:`winch_force`).
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    X: np.ndarray
    sway: np.ndarray
    sway_rate: np.ndarray
    sway_accel: np.ndarray
    tension: np.ndarray
    force_tip: np.ndarray
    residual: np.ndarray
    slack: np.ndarray
    condition: np.ndarray
    sway_condition: float
    length: float
    mass: float
    method: str = "kane"
    step: float = 0.0
    info: dict = field(default_factory=dict)
    hoist: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.t)

    @property
    def winch_force(self) -> np.ndarray | None:
        """``(N,)`` the winch's line pull Fw [N] (the cable's tension at the drum, > 0
        holding the load), or None without a winch."""
        return None if self.hoist is None else self.tension

    @property
    def winch_power(self) -> np.ndarray | None:
        """``(N,)`` the power the winch delivers to the line [W]: ``−Fw L̇`` (positive
        while hauling in a taut line), or None without a winch."""
        return None if self.hoist is None else -self.tension * self.hoist[:, 1]

    @property
    def sway_angle(self) -> np.ndarray:
        """``(N,)`` angle between the cable and the tip frame's downward axis [rad]:
        ``arccos(cos φ1 cos φ2)``."""
        return np.arccos(np.clip(np.cos(self.sway[:, 0]) * np.cos(self.sway[:, 1]), -1, 1))

    def truncated(self, n: int) -> "CableResult":
        """The first ``n`` samples."""
        out = {}
        for f in fields(self):
            v = getattr(self, f.name)
            out[f.name] = v[:n] if isinstance(v, np.ndarray) else v
        return CableResult(**out)
