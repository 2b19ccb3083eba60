"""What a plant is to the RK4 driver (:mod:`offshore_crane.simulation.driver`): its state
layout, its right-hand side, what it records, its stop causes; and, on the controller's
side (its ``model``), the inverse dynamics a law asks of it."""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from offshore_crane.stops import StopCause


class Plant:
    """A plant: the robot and whatever moves with it, in one state vector ``y``.

    A subclass sets :attr:`name`, :attr:`size`, the slices :attr:`Q`, :attr:`QD` of the
    robot's coordinates and rates in ``y``, :attr:`RECORDED` and :attr:`KERNELS` (its
    compiled right-hand side, checks, record and, on the controller's model, the law's
    side) and implements :meth:`finish`.

    Attributes:
        robot: The simulated robot (the plant).
        model: The robot the controller believes in (the plant's own by default).
        g: ``(3,)`` gravity [m/s²].
    """

    name: ClassVar[str] = ""
    size: ClassVar[int] = 18
    #: The actuator forces the law commands: the robot's 9 (a commanded winch's line
    #: pull makes 10, :class:`~offshore_crane.simulation.plants.ElasticPlant`).
    nx: ClassVar[int] = 9
    Q: ClassVar[slice] = slice(0, 9)
    QD: ClassVar[slice] = slice(9, 18)
    #: Arrays the plant records beside the driver's, ``{name: width}`` (0: a scalar).
    RECORDED: ClassVar[dict] = {}
    #: The actuators' power is formed from the record (not recorded by the loop).
    POWER_FROM_RECORD: ClassVar[bool] = False

    #: The plant's compiled kernels for the driver (a module of
    #: :mod:`offshore_crane.simulation.plants`: ``prepare`` (what the plant makes at a
    #: stage's state before the law is evaluated there, for the law to share), ``rhs``,
    #: ``check``, ``keep``, ``inverse``, ``gravity``, ``coords``, ``payload``, ``arm_tip``
    #: and ``params(plant)``).
    KERNELS: ClassVar[str] = ""

    def __init__(self, robot, model, gravity):
        self.robot, self.model, self.g = robot, model, gravity
        self._P = None

    def kernels(self):
        """The compiled kernels' module (imports Numba)."""
        import importlib

        return importlib.import_module(self.KERNELS)

    @property
    def variant(self) -> str:
        """What tells kernels compiled apart for this plant from its default ones (a
        commanded winch), or ``""``: the driver's loop is compiled per variant."""
        return ""

    def params(self) -> tuple:
        """``P``: the arrays the kernels read (made once)."""
        if self._P is None:
            self._P = self.kernels().params(self)
        return self._P

    def extra_width(self) -> int:
        """Columns of the plant's own record (:attr:`RECORDED`)."""
        return sum(max(w, 1) for w in self.RECORDED.values())

    def recorded(self, EXTRA) -> dict:
        """The plant's own record by name (:attr:`RECORDED`), from its columns."""
        out, c = {}, 0
        for name, w in self.RECORDED.items():
            out[name] = EXTRA[:, c] if w == 0 else EXTRA[:, c:c + w]
            c += max(w, 1)
        return out

    # ----------------------------------------------------------- the state
    def state_names(self) -> tuple[str, ...]:
        """The names of ``y``'s entries, with their units (the CSV's ``q1_m``,
        ``qd4_rad_s``, ...): q1..q9 then their rates, and the plant's own between and
        after them (:attr:`Q`, :attr:`QD`, :meth:`own_names`)."""
        from offshore_crane.conventions import QD_COLUMNS, Q_COLUMNS

        names = [""] * self.size
        names[self.Q], names[self.QD] = Q_COLUMNS, QD_COLUMNS
        own = iter(self.own_names())
        return tuple(n or next(own) for n in names)

    def own_names(self) -> tuple[str, ...]:
        """The names of the plant's own entries of ``y`` beyond q and q̇, in order."""
        return ()

    def q(self, y: np.ndarray) -> np.ndarray:
        """The robot's coordinates q1..q9 ``(9,)`` [m, rad] in ``y``."""
        return y[self.Q]

    def qd(self, y: np.ndarray) -> np.ndarray:
        """Their rates ``(9,)`` [m/s, rad/s]."""
        return y[self.QD]

    def channels(self, i: int, y: np.ndarray) -> dict:
        """The plant's measured channels beyond q and q̇, by name (a Python law's
        keyword arguments)."""
        return {}

    def observed_names(self) -> tuple[str, ...]:
        """The names of what :meth:`observe` adds to the state a stepper observes
        (``()``: nothing; the CSV's names with their units)."""
        return ()

    def observe(self, i: int, y: np.ndarray, X: np.ndarray, out: np.ndarray) -> None:
        """The channels :meth:`observed_names` names, formed from the measured state
        ``y`` ``(size,)`` at stage point ``i`` under the forces ``X`` ``(nx,)`` [N·m, N]
        acting there, into ``out`` ``(len(observed_names),)`` (on the compiled kernels:
        a stepper calls it every control period)."""

    def words(self, cause: StopCause, res) -> str:
        """A stop's cause in words, from the samples kept (``res``)."""
        q5 = f", q5 = {res.q[-1, 4]:.4g} rad" if len(res) else ""
        return f"the mass matrix became singular (attitude singularity{q5})"

    def follower(self, limits: bool):
        """The :class:`~offshore_crane.simulation.record.Follower` the driver feeds with
        the record while the loop runs (the workspace with ``limits``; the power when
        :attr:`POWER_FROM_RECORD`)."""
        from offshore_crane.simulation.record import Follower

        return Follower(self.robot, limits, self.POWER_FROM_RECORD)

    def finish(self, res, rec: dict, limits: bool, follow=None):
        """Complete the result from the recorded samples (tension, power, ...) and
        return ``(sample, StopCause, words)`` of the first stop found on the record (a
        workspace violation, a slack cable), or None. ``follow``: the
        :meth:`follower` the driver fed with the record's first blocks while the loop
        ran (what is left of its work is done here), or None."""
        return None

    # ----------------------------------------------------------- the law's side
    def actuator_coordinates(self, q: np.ndarray, qd: np.ndarray):
        """The actuated joints' positions and rates ``(9,)`` each (arm joints, leg
        lengths, in the order of X) [rad, m, /s], on the model."""
        from offshore_crane.dynamics import compiled as c

        if not hasattr(self, "_legs"):
            from offshore_crane.dynamics.constants import robot_arrays

            self._legs = robot_arrays(self.model.without_hanging_payload()).kane
        s, sd = np.empty(9), np.empty(9)
        c.KE.actuator_coordinates(self._legs, np.ascontiguousarray(q),
                                  np.ascontiguousarray(qd), s, sd)
        return s, sd
