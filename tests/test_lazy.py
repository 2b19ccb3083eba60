"""Sub-modules resolve as attributes from ``import offshore_crane as oc`` alone
(``oc.dynamics.cable``, ``oc.studies.sizing``, ``oc.outputs.export.mjcf``), imported on
first use, so that ``import offshore_crane`` still imports NumPy and nothing heavier."""

from __future__ import annotations

import importlib
import subprocess
import sys
from pathlib import Path

import pytest

import offshore_crane

PACKAGE = Path(offshore_crane.__file__).resolve().parent

#: What ``import offshore_crane`` must not import (README: NumPy only).
HEAVY = ("numba", "llvmlite", "scipy", "pinocchio", "matplotlib", "pandas", "pyarrow",
         "joblib", "dask", "xacro", "yourdfpy", "mpmath", "PIL", "imageio", "viser",
         "mujoco")


def _run(code: str) -> str:
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def test_import_is_numpy_only_and_sub_modules_resolve_on_use():
    """In a fresh process: the import loads none of :data:`HEAVY`; ``oc.dynamics.cable``
    (the README's example) is then the module, without importing it first."""
    out = _run("import sys; import offshore_crane as oc; "
               f"heavy = {HEAVY!r}; "
               "print(sorted(m for m in heavy if m in sys.modules)); "
               "print('offshore_crane.dynamics.cable' in sys.modules); "
               "c = oc.dynamics.cable; "
               "print(c is sys.modules['offshore_crane.dynamics.cable'], "
               "callable(c.inverse_dynamics))")
    assert out.split("\n")[:3] == ["[]", "False", "True True"], out


def _packages() -> list[str]:
    return sorted(".".join(p.parent.relative_to(PACKAGE.parent).parts)
                  for p in PACKAGE.rglob("__init__.py") if "__pycache__" not in p.parts)


@pytest.mark.parametrize("package", _packages())
def test_every_sub_module_is_an_attribute_of_its_package(package):
    """Each child module or package of each package is reachable as an attribute, and
    is the module itself (not a copy, not a name shadowing it)."""
    pkg = importlib.import_module(package)
    folder = Path(pkg.__file__).parent
    names = [p.stem for p in folder.glob("*.py") if not p.stem.startswith("__")]
    names += [p.name for p in folder.iterdir() if (p / "__init__.py").is_file()]
    for name in names:
        assert getattr(pkg, name) is importlib.import_module(f"{package}.{name}"), name


def test_a_missing_name_is_an_attribute_error_naming_it():
    import offshore_crane as oc

    with pytest.raises(AttributeError, match="'offshore_crane.dynamics' has no attribute "
                                             "'no_such_module'"):
        oc.dynamics.no_such_module
    with pytest.raises(AttributeError, match="no_such_thing"):
        oc.no_such_thing
    assert not hasattr(oc.studies, "__wrapped__")    # dunders are never looked up
    assert oc.CableResult is oc.dynamics.cable.CableResult        # the old names stay
    assert oc.SlackCableError is oc.errors.SlackCableError
