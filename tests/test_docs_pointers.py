"""Every pointer in the docs leads somewhere: file paths quoted in README.md and docs/*.md
exist in the repository, and every dotted ``offshore_crane.…`` name written in the docs or
in the package's docstrings resolves (a module, or an attribute of one). A file moved or
renamed without its mentions fails here instead of misleading a reader."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

from conftest import package_sources

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "offshore_crane"
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
#: A quoted file name: `a/b/c.py`, `c.py`, `docs/x.md`, `models/….xacro`, `data.csv`.
FILE = re.compile(r"`([\w./-]*\w\.(?:py|md|toml|xacro|csv|png|gif|json))[`:]")
#: A quoted source folder: `robot/description/`, `src/offshore_crane/motion/sea/`.
FOLDER = re.compile(r"`((?:src/offshore_crane/)?(?:robot|motion|dynamics|reference|simulation|scenes|studies|outputs|cli|serial)/[\w/]*)`")
DOTTED = re.compile(r"\boffshore_crane(?:\.[A-Za-z_]\w*)+")
#: Endings that make a dotted name a file name (``offshore_crane.urdf.xacro``).
FILE_ENDINGS = {"xacro", "urdf", "toml", "py", "md", "json", "csv"}
#: Files a run writes (named in the docs as outputs, not part of the repository).
WRITTEN = {"bench.csv", "results.csv", "envelope.csv", "run.csv", "_manifest.json",
           "forces.csv", "forces.png", "sway.png", "scene.toml", "my_platform.toml",
           "lab.mjcf", "my_scene.toml", "my_grid.toml", "grid.toml", "motion.csv",
           "utilisation-worst-case.png", "_lock.json", "operability-no-slack.png",
           "operability-load.png", "operability-all.png", "pareto.csv", "front.png"}


def _repository_files() -> list[str]:
    skip = {".git", ".venv", "__pycache__", "build", "node_modules"}
    return [p.relative_to(ROOT).as_posix() for p in ROOT.rglob("*")
            if p.is_file() and not skip & set(p.relative_to(ROOT).parts)]


def _exists(name: str, files: list[str]) -> bool:
    """``name`` is a repository path, or the tail of one (``dynamics/forward.py`` names
    ``src/offshore_crane/dynamics/forward.py``; a bare ``forward.py`` any such file)."""
    name = name.lstrip("./")
    return any(f == name or f.endswith("/" + name) for f in files)


def test_quoted_files_exist():
    files = _repository_files()
    missing = []
    for doc in DOCS:
        for n, line in enumerate(doc.read_text(encoding="utf-8").splitlines(), 1):
            for folder in FOLDER.findall(line):
                path = folder.removeprefix("src/offshore_crane/").rstrip("/")
                if not (PACKAGE / path).exists():
                    missing.append(f"{doc.relative_to(ROOT)}:{n}: {folder}")
            for name in FILE.findall(line):
                if Path(name).name in WRITTEN or name.startswith(("/", "~")):
                    continue
                if not _exists(name, files):
                    missing.append(f"{doc.relative_to(ROOT)}:{n}: {name}")
    assert not missing, "files named in the docs that do not exist:\n" + "\n".join(missing)


def _resolves(dotted: str) -> bool:
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for attr in parts[cut:]:
            fields = getattr(obj, "__dataclass_fields__", {})
            if not hasattr(obj, attr) and attr not in fields:
                return False
            obj = getattr(obj, attr, None)
        return True
    return False


def _dotted_names() -> dict[str, str]:
    found = {}
    sources = DOCS + package_sources(PACKAGE)
    for path in sources:
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            for name in DOTTED.findall(line):
                if name.rsplit(".", 1)[-1] in FILE_ENDINGS:
                    continue
                found.setdefault(name.rstrip("."), f"{path.relative_to(ROOT)}:{n}")
    return found


def test_dotted_names_resolve():
    """Docstrings' ``:mod:`offshore_crane.x``` / ``:func:`offshore_crane.x.f``` and the
    docs' names (imports heavy modules: it is a docs check, run once)."""
    bad = [f"{where}: {name}" for name, where in sorted(_dotted_names().items())
           if not _resolves(name)]
    assert not bad, "names that do not resolve:\n" + "\n".join(bad)


def test_the_readme_library_example_runs():
    """The README's Python block (the library's first page) runs as written."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    block = text.split("## Library", 1)[1].split("```python", 1)[1].split("```", 1)[0]
    namespace: dict = {}
    exec(compile(block, "README.md (Library)", "exec"), namespace)
    assert namespace["X"].shape == namespace["q"].shape == (3142, 9)
    assert namespace["swing"].sway.shape == (3142, 2)


RELATIVE = re.compile(r":(?:mod|func|class|data|meth):`~?(\.+[A-Za-z_][\w.]*)`")


def test_relative_docstring_references_resolve():
    """``:mod:`.formulas``` in a docstring names a module beside it (or inside it, for a
    package's ``__init__``); ``..x`` one package up."""
    bad = []
    for path in package_sources(PACKAGE):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        module = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        package = module if parts[-1] == "__init__" else module.rsplit(".", 1)[0]
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            for ref in RELATIVE.findall(line):
                dots = len(ref) - len(ref.lstrip("."))
                base = package.rsplit(".", dots - 1)[0] if dots > 1 else package
                candidates = [f"{base}.{ref.lstrip('.')}", f"{module}.{ref.lstrip('.')}"]
                if not any(_resolves(c) for c in candidates):
                    bad.append(f"{path.relative_to(ROOT)}:{n}: {ref}")
    assert not bad, "relative references that do not resolve:\n" + "\n".join(bad)
