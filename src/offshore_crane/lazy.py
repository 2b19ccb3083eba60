"""Sub-modules as attributes, imported on first use: ``oc.dynamics.cable`` works after
``import offshore_crane as oc`` alone, as ``from offshore_crane.dynamics import cable``
does, while ``import offshore_crane`` still imports only NumPy.

Each package of ``offshore_crane`` sets ``__getattr__ = submodule_getattr(__name__)``
(PEP 562: Python calls it only for a name the package does not hold yet). The name is
imported when the package has a sub-module or sub-package of that name; otherwise the
usual ``AttributeError``. Names of the form ``__x__`` are never looked up as sub-modules
(tools probe ``__wrapped__``, ``__path__`` and the like).
"""

from __future__ import annotations

import importlib
import importlib.util
from types import ModuleType
from typing import Callable


def find_submodule(package: str, name: str) -> ModuleType | None:
    """The sub-module ``package.name``, imported, or None when there is none."""
    if name.startswith("__") and name.endswith("__"):
        return None
    full = f"{package}.{name}"
    if importlib.util.find_spec(full) is None:
        return None
    return importlib.import_module(full)


def submodule_getattr(package: str) -> Callable[[str], ModuleType]:
    """A module ``__getattr__`` for ``package`` that imports its sub-modules on use.

    Args:
        package: The package's dotted name (its ``__name__``).

    Returns:
        ``__getattr__(name)``: the sub-module, or ``AttributeError`` naming the package.
    """

    def __getattr__(name: str) -> ModuleType:
        module = find_submodule(package, name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return module

    return __getattr__
