"""The measured figures in README.md and docs/ are those of the benchmarks' last saved run
(``benchmarks/results/*.json``, and ``docs/bench/summary.md`` of ``benchmarks/bench.py``,
rendered by ``scripts/figures.py``): a figure edited by hand, or a saved run not carried
into the documents, fails here; and so does a measured figure typed outside what
``scripts/figures.py`` writes.

**The coverage rule** (:func:`unrendered_figures`). In README.md and docs/*.md (but the
pages of :data:`EXCLUDED`), after removing what ``scripts/figures.py`` writes (the table
rows it renders, found by their first cell, and the text between ``<!-- figure KEY -->``
and ``<!-- /figure -->`` for a KEY it renders), fenced code blocks and inline code (the
commands and their arguments are inputs), a *measured figure* is a number (``12``,
``0.71``, ``1.75–2.50``, ``~1000``) that is

- a duration below a millisecond: followed by ``µs`` or ``ns`` (no input of this project
  is that short);
- a duration (``ms``, ``s``, ``min``) introduced as a time taken: after ``in``,
  ``takes``/``took``, ``about``/``~``, ``spends``, ``costs``, or followed by ``of CPU``,
  or followed by ``a``/``per`` + ``sample``, ``call``, ``case``, ``frame``, ``row``;
- a speed-up: followed by ``×`` (or ``x``) and then by a comparison: ``faster``,
  ``slower``, ``one`` or ``1`` (thread, worker, call), ``on N cores``, ``against``,
  ``floor``, ``Table 1's``, ``the rigid``;
- a rate: followed by ``GFLOP/s``, ``GB/s``, or after ``real-time factor``;
- a size of what was written: followed by ``kB``, ``KB``, ``MB``, ``GB``, or ``B a row``;

and is not a bound: a number right after ``≤``, ``≥``, ``<``, ``>``, ``±`` or ``target``
is a limit, not a measurement. Inputs (``Hs 2.5 m``, ``Tp 8 s``, ``60 s at 30 fps``, a
``20 ms`` delay, a ``1 ms`` step) and the model's own results (a tension ``11.1 × static``,
an RMS reduction ``186×``) are thereby left alone; a rule that aims at timings, speed-ups,
rates and sizes misses a measured figure phrased otherwise, and prefers that to false
alarms. A figure marker whose KEY no renderer writes is an error too.
"""

import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: Pages left out of the coverage rule, with the reason (the rendered-figure check above
#: still covers whatever they hold of ``scripts/figures.py``'s figures).
EXCLUDED: dict = {}

_NUMBER = r"(?<![\w.·^/-])~?\d[\d,.]*(?:\s?[–-]\s?\d[\d,.]*)?"
_BOUND = r"(?:[≤≥<>±]|target|targets:?)\s*$"
#: (kind, pattern): a match is a figure unless a bound precedes it.
KINDS = [
    ("sub-millisecond time", re.compile(_NUMBER + r"\s?(?:µs|ns)\b")),
    ("time taken", re.compile(r"(?:\b(?i:in|takes?|took|taking|about|spends?|costs?)\s+|~)"
                              + _NUMBER + r"\s?(?:ms|s|min)\b")),
    ("time taken", re.compile(_NUMBER + r"\s?(?:ms|s|min)\s(?:of CPU|against|(?:a|per) "
                              r"(?:sample|call|case|frame|row|step)s?\b)")),
    ("speed-up", re.compile(_NUMBER + r"\s?[×x]\s(?:faster|slower|one\b|1\b|on \d+ cores|"
                            r"against|(?:the )?floor|Table 1's|the rigid)")),
    ("rate", re.compile(_NUMBER + r"\s?(?:GFLOP/s|GB/s)|real-time factor\s+" + _NUMBER)),
    ("size", re.compile(_NUMBER + r"\s?(?:(?:kB|KB|MB|GB)\b|B a row)")),
]


def _figures():
    spec = importlib.util.spec_from_file_location("figures", ROOT / "scripts" / "figures.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _strip(text: str, labels: list[str], keys: set[str]) -> tuple[str, list[str]]:
    """The page without rendered figures, code and markers; and the unknown markers."""
    unknown = [m.group(1) for m in re.finditer(r"<!-- figure (\S+) -->", text)
               if m.group(1) not in keys]
    text = re.sub(r"<!-- figure (\S+) -->(.*?)<!-- /figure -->",
                  lambda m: "" if m.group(1) in keys else m.group(2), text, flags=re.S)
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    lines = [ln for ln in text.splitlines()
             if not any(ln.startswith(f"| {label}") for label in labels)]
    return re.sub(r"`[^`\n]*`", "`…`", "\n".join(lines)), unknown


def unrendered_figures(name: str, text: str, rendered: dict) -> list[str]:
    """``["page: kind 'context'", ...]``: the measured figures of one page that
    ``scripts/figures.py`` does not write (the rule of this module's docstring).

    Args:
        name: The page's path from the repository's root (``docs/sea.md``).
        text: Its Markdown.
        rendered: ``scripts/figures.py``'s ``rows()``: ``{(page, label): text}``.
    """
    labels = [label for page, label in rendered if page == name
              and not label.startswith("figure ")]
    keys = {label.split(" ", 1)[1] for page, label in rendered if page == name
            and label.startswith("figure ")}
    prose, unknown = _strip(text, labels, keys)
    out = [f"{name}: marker 'figure {k}' that no renderer writes" for k in unknown]
    for kind, pattern in KINDS:
        for m in pattern.finditer(prose):
            if re.search(_BOUND, prose[max(0, m.start() - 12):m.start()]):
                continue
            line = prose[prose.rfind("\n", 0, m.start()) + 1:]
            out.append(f"{name}: {kind} {m.group(0)!r} in {line[:100]!r}")
    return out


def test_saved_results_exist_and_render_rows():
    figures = _figures()
    for name in figures.RENDERERS:
        assert figures.source(name).is_file(), name
    assert len(figures.rows()) >= 75          # 75 figures from 11 benchmarks


def test_the_documents_say_what_the_benchmarks_measured():
    assert _figures().apply(write=False) == []


@pytest.mark.parametrize("text, found", [
    ("compiles in about 65 s on 2 cores", ["time taken 'about 65 s'"]),
    ("12.3 µs a sample, and ≤ 15 µs is the target", ["sub-millisecond time '12.3 µs'"]),
    ("2.04 × one thread; 1.7 × on 2 cores", ["speed-up '2.04 × one'",
                                            "speed-up '1.7 × on 2 cores'"]),
    ("a 7.2 MB GIF, ~0.8 kB a row; 53.7 GFLOP/s", ["rate '53.7 GFLOP/s'",
                                                  "size '7.2 MB'", "size '~0.8 kB'"]),
    ("About 15 s. It took 0.24–0.27 s; 3.05 s against 2.10 s", ["time taken 'About 15 s'",
                                                                "time taken 'took 0.24–0.27 s'",
                                                                "time taken '3.05 s against'"]),
    ("real-time factor 46", ["rate 'real-time factor 46'"]),
    # inputs, limits and the model's own results are not measured figures
    ("Hs 2.5 m, Tp 8 s, 60 s at 30 fps, a 20 ms delay, RK4 at 1 ms over 10 s", []),
    ("target ≤ 10 s; within 3 s; ≤ 1 KB a row; after 2 s; 640 × 480", []),
    ("a tension 11.1 × static, the RMS motion cut 186× (x); `--duration 20` in `60 s`", []),
])
def test_the_rule_finds_timings_speed_ups_rates_and_sizes_only(text, found):
    """The rule on sentences of the kinds the documents hold: what it flags, and the
    inputs, bounds and results it must leave alone."""
    got = unrendered_figures("x.md", text, {})
    assert [g.split(": ", 1)[1].split(" in ")[0] for g in got] == found


def test_no_measured_figure_is_typed_by_hand():
    """Every measured figure of README.md and docs/*.md (but :data:`EXCLUDED`) is written
    by ``scripts/figures.py`` from a saved benchmark run."""
    rendered = _figures().rows()
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    found = []
    for page in pages:
        name = str(page.relative_to(ROOT))
        if name not in EXCLUDED:
            found += unrendered_figures(name, page.read_text(encoding="utf-8"), rendered)
    assert not found, "\n".join(found)
