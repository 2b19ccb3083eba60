"""Every ```` ```python ```` snippet of README.md and docs/*.md runs, as written, on the
installed package: one test per page, its snippets in the page's order in one namespace
(a later snippet uses the names of an earlier one, as a reader would).

How a page runs: in a temporary folder holding a link to each top-level entry of the
repository (``scenes/``, ``models/``, ``docs/``, ...), made the working directory, so a
snippet's relative paths read as from the repository root while a file it writes
(``out="results"``) lands in the temporary folder, which is removed. A snippet that would
write through a link into the repository fails the test: the repository's files are
listed before and after the page.

A snippet that is deliberately not run says so on its first line, visibly in the page:
``# not run: <reason>`` (rare: at most :data:`MAX_NOT_RUN` in all the documents). A
snippet needing a user's file uses a shipped one instead (a description of
``models/descriptions/``, a scene of ``scenes/``).

The snippets are kept light (short records, a few cases), so that this module adds a few
seconds to the suite.
"""

from __future__ import annotations

import os
import re
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: A fenced Python block: its info string starts with ``python``.
SNIPPET = re.compile(r"^```python[^\n]*\n(.*?)^```[ \t]*$", re.M | re.S)
#: The first line of a snippet that is deliberately not run, followed by the reason.
NOT_RUN = "# not run:"
#: The most snippets that may be marked not run, over README.md and docs/*.md together.
MAX_NOT_RUN = 2
#: Files the pages may leave behind in the repository: none; caches are not files of it.
IGNORED = ("__pycache__", ".git", ".pytest_cache", ".venv", ".hypothesis")


def pages() -> list[Path]:
    """README.md and docs/*.md."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def snippets(page: Path) -> list[tuple[int, str]]:
    """``[(line of the code's first line, code), ...]`` of a page's Python blocks."""
    text = page.read_text(encoding="utf-8")
    return [(text.count("\n", 0, m.start(1)) + 1, m.group(1)) for m in SNIPPET.finditer(text)]


def _runnable(page: Path) -> list[tuple[int, str]]:
    return [(line, code) for line, code in snippets(page)
            if not code.lstrip().startswith(NOT_RUN)]


def _repository_files() -> set[str]:
    out = set()
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d not in IGNORED]
        out.update(os.path.relpath(os.path.join(folder, f), ROOT) for f in files)
    return out


PAGES = [p for p in pages() if snippets(p)]


def test_every_page_with_python_is_collected_and_few_are_not_run():
    """The pages are found (the README's library example at least) and the snippets not
    run are rare and give a reason."""
    assert ROOT / "README.md" in PAGES
    marked = [(p.name, line, code.lstrip().splitlines()[0]) for p in PAGES
              for line, code in snippets(p) if code.lstrip().startswith(NOT_RUN)]
    assert len(marked) <= MAX_NOT_RUN, marked
    assert all(len(first) > len(NOT_RUN) + 3 for *_, first in marked), marked


@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(ROOT)) for p in PAGES])
def test_page_snippets_run_in_order(page, tmp_path, monkeypatch):
    for entry in ROOT.iterdir():
        if not entry.name.startswith("."):
            (tmp_path / entry.name).symlink_to(entry)
    monkeypatch.chdir(tmp_path)
    before = _repository_files()
    namespace: dict = {"__name__": "__snippet__"}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")          # a page's example may well warn
        for line, code in _runnable(page):
            # padded so that a traceback names the page's own line numbers
            exec(compile("\n" * (line - 1) + code, str(page), "exec"), namespace)
    added = sorted(_repository_files() - before)
    assert not added, f"{page.name}'s snippets wrote into the repository: {added}"
