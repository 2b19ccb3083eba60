"""The measured figures in README.md and docs/ are those of the benchmarks' last saved run
(``benchmarks/results/*.json``, rendered by ``scripts/figures.py``): a figure edited by
hand, or a saved run not carried into the documents, fails here."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _figures():
    spec = importlib.util.spec_from_file_location("figures", ROOT / "scripts" / "figures.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_saved_results_exist_and_render_rows():
    figures = _figures()
    for name in figures.RENDERERS:
        assert (figures.RESULTS / f"{name}.json").is_file(), name
    assert len(figures.rows()) >= 35          # 35 figures from 6 benchmarks


def test_the_documents_say_what_the_benchmarks_measured():
    assert _figures().apply(write=False) == []
