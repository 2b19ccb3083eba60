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
    :meth:`command` (and :meth:`state_rate` when it has a state). :attr:`code` is the law's
    code in the compiled rigid-robot loop (:mod:`offshore_crane.simulation.laws.codes`), or
    None: it then runs on the RK4 driver (:mod:`offshore_crane.simulation.driver`).

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

    def initial_state(self) -> np.ndarray:
        """The law's state at the start ``(state_size,)``."""
        return np.zeros(self.state_size)

    def command(self, i: int, t: float, y: np.ndarray, z: np.ndarray, ref) -> np.ndarray:
        """The commanded actuator forces ``X_cmd (9,)`` [N·m, N].

        Args:
            i: Index of the stage time on the reference grid (2 per step).
            t: Time [s].
            y: The plant's state as measured ``(plant.size,)``.
            z: The law's own state ``(state_size,)``.
            ref: ``(q_ref, qd_ref, qdd_ref)`` ``(9,)`` each at ``t``.
        """
        raise NotImplementedError

    def state_rate(self, i: int, t: float, y: np.ndarray, z: np.ndarray, ref,
                   X_cmd: np.ndarray, X: np.ndarray) -> np.ndarray:
        """``ż (state_size,)`` at a stage, from the command ``X_cmd`` and the forces the
        actuators apply ``X`` (saturated: what an anti-windup reads)."""
        return np.zeros(0)


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
