"""A user's Python law: any callable ``law(t, q, qd, q_ref, qd_ref, qdd_ref) -> X (9,)``
[s, m, rad, /s, /s² → N·m, N], on every plant. A law that also takes keyword arguments
receives the plant's other measured channels by name (those its signature names, or all
with ``**measured``): with a rigid hanging load ``sway``, ``sway_rate`` (2,) [rad,
rad/s]; on an elastic cable ``payload``, ``payload_velocity`` (3,) [m, m/s, base frame],
``tension`` [N], ``length`` [m], ``length_rate`` [m/s], and the load cell's ``pull`` on
the tip [N] with ``pull_at``, where it acts from the tip [m] (base axes)
(:meth:`~offshore_crane.simulation.plants.Plant.channels`). With a commanded winch a law
may return 10 forces, the winch's line pull [N] last; 9 leave the pull to the winch's
drive.
"""

from __future__ import annotations

import inspect

import numpy as np

from offshore_crane.errors import InputError
from offshore_crane.simulation.laws._registry import Law, no_state, register


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    """The user's law, called from the driver's loop run as Python (``L``: the law)."""
    x = L.evaluate(i, t, y[:n_p], qr, qdr, qddr)
    X[:x.shape[0]] = x



@register
class PythonLaw(Law):
    name = "python"
    selectable = False
    compiled = False

    def __init__(self, controller, plant, function):
        super().__init__(controller, plant)
        self.function = function
        self.wants = _keywords(function)

    def params(self):
        return self

    def templates(self) -> dict:
        return {"command": command, "law_rate": no_state}

    def evaluate(self, i, t, y, qr, qdr, qddr):
        """X (9,) of the user's law at the measured plant state ``y``; (10,) where the
        plant has a commanded winch and the law commands its line pull too (else the
        winch's drive does)."""
        from offshore_crane.validation import as_samples

        p = self.plant
        extra = {}
        if self.wants:
            extra = p.channels(i, y)
            if self.wants is not True:
                extra = {k: v for k, v in extra.items() if k in self.wants}
        X = self.function(t, p.q(y).copy(), p.qd(y).copy(), qr.copy(), qdr.copy(),
                          qddr.copy(), **extra)
        if p.nx > 9 and np.shape(X) == (p.nx,):
            x = np.asarray(X, dtype=float)
            if not np.isfinite(x).all():
                raise InputError(f"X returned by the controller at t = {t:.6g} s is not "
                                 f"finite: {x.tolist()}", name="controller")
            return x
        if p.nx > 9 and np.shape(X) != (9,):
            raise InputError(f"X returned by the controller must be 9 numbers (10 with the "
                             f"commanded winch's line pull last), got {np.shape(X)}",
                             name="controller")
        try:
            return as_samples("X returned by the controller", X)[0][0]
        except InputError:
            raise
        except Exception:       # noqa: BLE001 - a shape as_samples cannot read
            raise InputError(f"X returned by the controller must be 9 numbers, got "
                             f"{np.shape(X)}", name="controller") from None


def _keywords(function):
    """True when ``function`` takes ``**kwargs``; else the names of its parameters after
    the six positional ones (an empty set: none)."""
    try:
        params = list(inspect.signature(function).parameters.values())
    except (TypeError, ValueError):
        return set()
    if any(p.kind is p.VAR_KEYWORD for p in params):
        return True
    return {p.name for p in params[6:] if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)}
