"""The package's structure is enforced, not hoped for (docs/architecture.md).

- The import contract in ``pyproject.toml`` (columns run one way; the reference shares
  nothing with what it checks but the URDF) is kept: a wrong-way import fails here.
- No import cycle between modules, lazy (function-level) imports included.
- No private name imported across modules.
- No file in ``src/`` over 500 lines (split by concept).
- No undefined name (pyflakes): a name used on a path no test took is a NameError
  waiting for a user (``id --out -`` met one: ``sys`` in a lambda).
"""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import grimp
import pytest
from importlinter.cli import lint_imports

import offshore_crane

from conftest import package_sources

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = Path(offshore_crane.__file__).resolve().parent
#: The most lines a source file may have: beyond it a file holds more than one concept.
MAX_LINES = 500


def test_import_contract_is_kept(capsys, tmp_path):
    """``lint-imports`` with the project's configuration: every contract kept."""
    status = lint_imports(config_filename=str(ROOT / "pyproject.toml"), no_cache=True,
                          no_logo=True)
    out = capsys.readouterr().out
    assert status == 0, out


def _sccs(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    counter = 0
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            v, children = work[-1]
            for w in children:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    comp = []
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        comp.append(w)
                        if w == v:
                            break
                    if len(comp) > 1:
                        found.append(sorted(comp))
    return found


def test_sccs_finds_a_planted_cycle():
    """The cycle finder itself: a → b → c → a is found, a DAG is not."""
    assert _sccs({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _sccs({"a": {"b"}, "b": {"c"}, "c": set()}) == []


def test_no_import_cycle():
    graph = grimp.build_graph("offshore_crane", cache_dir=None)
    edges = {m: set(graph.find_modules_directly_imported_by(m)) for m in graph.modules}
    cycles = _sccs(edges)
    assert not cycles, "import cycles: " + "; ".join(" <-> ".join(c) for c in cycles)


def _modules() -> list[tuple[Path, str, bool]]:
    out = []
    for path in package_sources(PACKAGE):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        if is_package:
            parts = parts[:-1]
        out.append((path, ".".join(parts), is_package))
    return out


def _absolute(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if not node.level:
        return node.module or ""
    base = module.split(".") if is_package else module.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def test_no_private_name_is_imported_across_modules():
    """``from offshore_crane.x import _y`` anywhere in the package: a private name used
    by another module is not private; make it public (and document it) or keep it home."""
    bad = []
    for path, module, is_package in _modules():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                source = _absolute(module, is_package, node)
                if not source.startswith("offshore_crane") or source == module:
                    continue
                for alias in node.names:
                    if alias.name.startswith("_") and not alias.name.startswith("__"):
                        bad.append(f"{module} imports {alias.name} from {source} "
                                   f"(line {node.lineno})")
    assert not bad, "\n".join(bad)


def test_no_source_file_over_the_line_limit():
    long = [f"{p.relative_to(PACKAGE.parent)}: {n} lines"
            for p, _, _ in _modules()
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_LINES]
    assert not long, f"over {MAX_LINES} lines (split by concept):\n" + "\n".join(long)


@pytest.mark.parametrize("name", ["load_robot", "inverse_dynamics", "forward_dynamics",
                                  "mass_matrix", "bias_forces", "actuation_matrix",
                                  "simulate"])
def test_public_functions_are_typed(name):
    """Every parameter and the return of the top-level functions carry type hints."""
    import inspect

    fn = getattr(offshore_crane, name)
    sig = inspect.signature(fn)
    missing = [p.name for p in sig.parameters.values()
               if p.annotation is inspect.Parameter.empty
               and p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL)]
    assert not missing, f"{name}: parameters without a type hint: {missing}"
    assert sig.return_annotation is not inspect.Signature.empty, f"{name}: no return type"


def test_the_top_level_is_small_and_shadows_no_module():
    """About fifteen public names; none of them is also a sub-module's name."""
    assert len(offshore_crane.__all__) <= 16
    modules = {p.stem for p in PACKAGE.iterdir() if p.suffix == ".py"} | {
        p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    assert not set(offshore_crane.__all__) & modules
    for name in offshore_crane.__all__:
        assert getattr(offshore_crane, name) is not None


def test_no_name_shadows_a_sub_module():
    """A package's attribute named like one of its sub-modules is that sub-module: a
    function re-exported under a sub-module's name would hide it (``from pkg import x``
    then depends on import order)."""
    import importlib

    bad = []
    for path, module, is_package in _modules():
        if not is_package:
            continue
        package = importlib.import_module(module)
        for child in path.parent.iterdir():
            name = child.stem if child.suffix == ".py" else child.name
            if name.startswith("_") or not (child.suffix == ".py" or
                                            (child / "__init__.py").is_file()):
                continue
            value = getattr(package, name, None)
            if value is not None and not inspect.ismodule(value):
                bad.append(f"{module}.{name} is {type(value).__name__}, not the sub-module")
    assert not bad, "\n".join(bad)


def test_matplotlib_is_set_up_in_one_place_and_never_in_the_cli():
    """Figures belong to ``outputs``: one function sets matplotlib up
    (``outputs.report.pyplot``, Agg backend) and no CLI module draws."""
    setups = [str(p.relative_to(PACKAGE)) for p, _, _ in _modules()
              if "matplotlib.use(" in p.read_text(encoding="utf-8")]
    assert setups == ["outputs/report.py"], setups
    drawing = [str(p.relative_to(PACKAGE)) for p in (PACKAGE / "cli").glob("*.py")
               if "matplotlib" in p.read_text(encoding="utf-8")]
    assert not drawing, drawing


def test_no_undefined_name():
    """pyflakes finds no undefined name in the package (annotations included)."""
    from pyflakes import api, messages
    from pyflakes.reporter import Reporter
    import io

    class Collect(Reporter):
        def __init__(self):
            super().__init__(io.StringIO(), io.StringIO())
            self.found = []

        def flake(self, message):
            if isinstance(message, (messages.UndefinedName, messages.UndefinedLocal,
                                    messages.UndefinedExport)):
                self.found.append(str(message))

    reporter = Collect()
    for path in package_sources(PACKAGE):
        api.checkPath(str(path), reporter)
    assert reporter.found == []
