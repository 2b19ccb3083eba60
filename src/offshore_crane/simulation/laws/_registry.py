"""The registry of control laws: a law is a :class:`Law` subclass in a file of its own,
registered by name with :func:`register`; :func:`law_class` finds it (with "did you mean"
for a misspelt name)."""

from __future__ import annotations

import difflib
from typing import ClassVar

import numpy as np

from offshore_crane.errors import InputError

#: The plants a law may run on (:mod:`offshore_crane.simulation.plants`).
PLANTS = ("rigid", "hanging", "elastic")
_LAWS: dict[str, type["Law"]] = {}


class Law:
    """A control law bound to one run: the controller's options on one plant.

    A subclass sets :attr:`name` (its registry key), :attr:`plants` (where it makes
    sense; :attr:`refusal` says in one line why not elsewhere), :attr:`state_size` (its
    own slot in the integrated state, e.g. an integral term; 0: none) and implements
    :meth:`params` and :meth:`templates` (functions written for Numba). :attr:`code` is
    the law's code in the rigid robot's compiled law, which the DOP853 reference path runs
    (:mod:`offshore_crane.simulation.laws.codes`), or None; every law runs on the RK4
    driver (:mod:`offshore_crane.simulation.loop`) with every plant it names.

    Attributes (of a bound law):
        controller: The :class:`~offshore_crane.simulation.control.Controller`.
        plant: The :class:`~offshore_crane.simulation.plants.Plant` it drives (its
            ``model`` side is the controller's robot).
    """

    name: ClassVar[str] = ""
    plants: ClassVar[tuple[str, ...]] = PLANTS
    refusal: ClassVar[str] = ""
    state_size: ClassVar[int] = 0
    code: ClassVar[int | None] = None
    #: Shown in ``offshore-crane simulate --controller``'s choices (a Python law is not).
    selectable: ClassVar[bool] = True

    def __init__(self, controller, plant):
        self.controller = controller
        self.plant = plant
        self.kp, self.kd = controller.gains

    #: False for a Python law: the driver's loop then runs as Python.
    compiled: ClassVar[bool] = True
    #: True for a law on computed torque: its default gains are ``Kp = ω²``, ``Kd = 2ω``
    #: per coordinate (:data:`~offshore_crane.simulation.control.CT_OMEGA`), not a PD's.
    ct_gains: ClassVar[bool] = False
    #: The run's reference at every stage time ``(tt, q, qd, qdd)`` (set by
    #: :func:`offshore_crane.simulation.runs.prepare` before :meth:`params`), for a law
    #: that forms something from it once (an aim).
    grid: tuple | None = None
    #: True for a law that forms something from :attr:`grid` once (an aim): it cannot
    #: take a reference given as it goes (a stepper's ``action="reference"``).
    reference_once: ClassVar[bool] = False

    def initial_state(self) -> np.ndarray:
        """The law's state at the start ``(state_size,)``."""
        return np.zeros(self.state_size)

    def start(self, q0: np.ndarray, qd0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The robot's state ``(q0, q̇0)`` ``(9,)`` each at the start when the caller
        gave none (the reference's at ``t0`` by default; a law may start the robot where
        it would put it, not where the reference is)."""
        return q0, qd0

    def winch_start(self, q0: np.ndarray, qd0: np.ndarray):
        """A commanded winch's ``(L [m], L̇ [m/s])`` at the start, given the robot's
        ``(q0, q̇0)``: None (the default) starts it on its profile; a law that commands
        the winch starts it where it would put it."""
        return None

    def params(self) -> tuple:
        """``L``: what the law's templates read (gains, scratch arrays)."""
        raise NotImplementedError

    def templates(self) -> dict:
        """``{name: function}``: the law's templates, instantiated with the plant's
        kernels in the driver's namespace (:func:`offshore_crane.simulation.loop.
        instantiate`): ``command(L, P, i, t, y, n_p, qr, qdr, qddr, X)`` writes X (9,)
        [N·m, N] at stage point ``i`` (time ``t`` [s]) from the measured state ``y``
        (the plant's ``n_p`` entries, then the law's own) and the reference;
        ``law_rate(L, P, i, t, y, n_p, qr, qdr, qddr, X_cmd, X, dy)`` writes the law's
        state's rate into ``dy[n_p:n_p + state_size]`` from the command and the applied
        forces (what an anti-windup reads); and what they call. They call the plant's
        ``inverse``, ``gravity``, ``coords``, ``payload``, ``arm_tip`` and read ``IQ``,
        ``IQD``
        (:class:`~offshore_crane.simulation.plants.Plant`)."""
        raise NotImplementedError


def no_state(L, P, i, t, y, n_p, qr, qdr, qddr, Xc, X, dy):
    """The ``law_rate`` template of a law without a state (nothing to write)."""


def register(cls: type[Law]) -> type[Law]:
    """Register a law class under ``cls.name`` (a class decorator); a name taken twice
    is an error, never a silent replacement."""
    if not cls.name or cls.name in _LAWS:
        raise ValueError(f"law name {cls.name!r} is empty or registered already")
    _LAWS[cls.name] = cls
    return cls


def names(selectable: bool = True) -> tuple[str, ...]:
    """The registered laws' names, in registration order (only the selectable ones by
    default)."""
    return tuple(n for n, c in _LAWS.items() if c.selectable or not selectable)


def law_class(name: str) -> type[Law]:
    """The law registered as ``name``.

    Raises:
        InputError: no such law (naming the closest, "did you mean").
    """
    if name in _LAWS and _LAWS[name].selectable:
        return _LAWS[name]
    close = difflib.get_close_matches(str(name), names(), n=1)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    raise InputError(f"unknown control law {name!r}{hint} (laws: {', '.join(names())})",
                     name="law")


def check_plant(cls: type[Law], plant: str) -> None:
    """Raise :class:`InputError` in one line when ``cls`` does not run on ``plant``."""
    if plant not in cls.plants:
        raise InputError(f"control law {cls.name!r} does not run on the {plant} plant: "
                         f"{cls.refusal or 'it is written for ' + ', '.join(cls.plants)}",
                         name="law")
