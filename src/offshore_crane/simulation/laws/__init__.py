"""Control laws by name: each law is a :class:`Law` subclass in one file, registered by
its name (:func:`register`); :func:`law_class` finds one ("did you mean" for a misspelt
name). Adding a law is one file in this package (found and registered on import) and its
test (``docs/simulation.md``, the PID law as the worked example).

Built in: ``computed-torque`` (:mod:`.computed_torque`), ``pd-gravity`` and ``pd``
(:mod:`.pd`), ``none`` (:mod:`.none`), ``pid`` (:mod:`.pid`), ``anti-sway``
(:mod:`.anti_sway`), ``arm-compensation`` (:mod:`.arm_compensation`),
``arm-winch-compensation`` (:mod:`.arm_winch_compensation`), a user's Python callable
(:mod:`.python`) and the actions of a controller outside the simulation
(:mod:`.held_action`, bound by a :class:`~offshore_crane.simulation.stepper.Stepper`).
"""

from __future__ import annotations

from offshore_crane.simulation.laws._registry import (PLANTS, Law, check_plant, law_class,
                                                      names, no_state, register)
from offshore_crane.simulation.laws import computed_torque, pd, none  # noqa: F401 (register)


def _discover() -> None:
    """Import (and so register) every law module of this package: a law added as a file
    here is found without another edit (the first three above keep their order)."""
    import importlib
    import pkgutil

    for info in pkgutil.iter_modules(__path__):
        if not info.name.startswith("_") and info.name != "codes":
            importlib.import_module(f"{__name__}.{info.name}")


_discover()

__all__ = ["Law", "PLANTS", "check_plant", "law_class", "names", "no_state", "register"]
