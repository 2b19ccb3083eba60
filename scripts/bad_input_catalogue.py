"""Print every bad input of tests/cli/test_bad_inputs.py (and its families,
tests/cli/cases_*.py) with the message it produces.

Usage: ``python scripts/bad_input_catalogue.py [--markdown]`` (from the repository, with
offshore-crane importable). Each case runs through the library and/or the command line
exactly as the tests run it (in a scratch directory); the output is what a user sees.
Cases marked GAP are known shortcomings (strict xfail in the tests).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import traceback
import warnings
from pathlib import Path

sys.path[:0] = [str(Path(__file__).resolve().parents[1] / "tests" / d) for d in ("cli", "")]

from test_bad_inputs import CASES, run_cli  # noqa: E402


def _library(case, tmp: Path) -> str:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            case.lib(tmp)
    except Exception as exc:  # noqa: BLE001 - we report whatever comes out
        return f"{type(exc).__name__}: {exc}"
    return "NO ERROR"


def _cli(case, tmp: Path) -> str:
    try:
        status, lines, left = run_cli(case, tmp)
    except Exception as exc:  # noqa: BLE001
        last = traceback.format_exception_only(type(exc), exc)[-1].strip()
        return f"UNCAUGHT (traceback) {last}"
    text = lines[-1] if lines else ""
    extra = f" [{len(lines)} lines; the last one]" if len(lines) != 1 else ""
    files = f" [left behind: {', '.join(left)}]" if left else ""
    return f"exit {status}{extra}{files}: {text}"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--markdown", action="store_true", help="a Markdown list")
    args = parser.parse_args(argv)
    for n, case in enumerate(CASES, 1):
        tag = " — GAP: " + case.gap if case.gap else ""
        print(f"{n}. **{case.description}** (`{case.id}`){tag}" if args.markdown
              else f"{n:2d}. {case.description} [{case.id}]{tag}")
        with tempfile.TemporaryDirectory() as d:
            if case.lib is not None:
                print(f"    - library: {_library(case, Path(d)).replace(d, 'DIR')}")
        if case.cli is not None:
            with tempfile.TemporaryDirectory() as d:      # the argv, its files made apart
                argv_shown = " ".join(case.cli(Path(d))).replace(d, "DIR")
            with tempfile.TemporaryDirectory() as d:      # the run makes its own
                shown = _cli(case, Path(d)).replace(d, "DIR")
            print(f"    - CLI `offshore-crane {argv_shown}`: {shown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
