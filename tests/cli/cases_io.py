"""The sweep, store and I/O family of the bad-input catalogue (issue 36): scheduler
addresses of every malformed form, results directories whose lock cannot be taken,
outputs that are sockets or devices rather than files, memory limits that are no limit.
Other instances than the ones the issue quotes (``tcp://[::1``, a read-only directory, a
FIFO, ``nan``, ``0`` and negative limits); the FIFO, the peer on the scheduler's port
and the read-only directory need a reader, a server or another user, and are tested in
tests/test_io_special.py and tests/studies/test_sweep_hostile.py.
"""

from __future__ import annotations

import os
import socket
from pathlib import Path

import offshore_crane as oc
from offshore_crane.errors import ResultsDirectoryError
from offshore_crane.studies.sweep.scheduler import check_scheduler
from offshore_crane.validation import check_memory

from test_bad_inputs import _SCENES, Case, _bytes

_SWEEP = str(_SCENES / "sweep_crane.toml")


def _sweep(tmp: Path, *extra: str) -> list:
    """``sweep`` of the shipped crane scene over one sea state, with ``extra``."""
    return ["sweep", "--scene", _SWEEP, "--grid", str(_bytes(tmp, "grid.toml", b"hs = [1.0]\n")),
            "--record", "scene", *extra]


def _scheduler(case_id: str, address: str, match: str, description: str) -> Case:
    """A malformed ``--scheduler`` address: refused by the library's check and by the
    command line before anything is written (``--out`` is never made)."""
    return Case(case_id, description, oc.InputError, match,
                lib=lambda tmp: check_scheduler(address),
                cli=lambda tmp: _sweep(tmp, "--scheduler", address, "--out",
                                       str(tmp / "out" / "res")))


def _socket_file(tmp: Path, name: str) -> Path:
    """A Unix socket's file in ``tmp`` (it stays when the socket is closed)."""
    path = tmp / name
    with socket.socket(socket.AF_UNIX) as s:
        s.bind(str(path))
    return path


def _results_with_lock(tmp: Path, make) -> Path:
    """A results directory (outside ``tmp/out``, so that what a run would write there is
    checked as an input) whose ``_lock`` is what ``make(path)`` puts there."""
    res = tmp / "res"
    res.mkdir(exist_ok=True)
    make(res / "_lock")
    return res


def _limit(value: str):
    """``check_memory`` of a small record under ``OFFSHORE_CRANE_MEMORY_LIMIT=value``."""
    def run(tmp: Path):
        before = os.environ.get("OFFSHORE_CRANE_MEMORY_LIMIT")
        os.environ["OFFSHORE_CRANE_MEMORY_LIMIT"] = value
        try:
            check_memory(8.0, "one number", "nothing")
        finally:
            if before is None:
                del os.environ["OFFSHORE_CRANE_MEMORY_LIMIT"]
            else:
                os.environ["OFFSHORE_CRANE_MEMORY_LIMIT"] = before
    return run


_LIMIT = r"OFFSHORE_CRANE_MEMORY_LIMIT = '{}': give a number of bytes, finite and > 0"

CASES = [
    # ---- scheduler addresses (a ValueError traceback from urlsplit, or accepted)
    _scheduler("scheduler-ipv6-unclosed-with-port", "tcp://[fe80::2:8786",
               r"tcp://\[fe80::2:8786: '\[' opens an IPv6 address that no '\]' closes",
               "an IPv6 address whose bracket is never closed (once a ValueError "
               "traceback)"),
    _scheduler("scheduler-ipv6-unbracketed", "tcp://fe80::2:8786",
               r"an IPv6 address goes in brackets \(tcp://\[::1\]:8786\)",
               "an IPv6 address without brackets (once blamed on the port)"),
    _scheduler("scheduler-name-in-brackets", "tcp://[scheduler]:8786",
               r"\[scheduler\] is not an IPv6 address",
               "a host name in IPv6 brackets (once a ValueError traceback)"),
    _scheduler("scheduler-two-ports", "tcp://node3:8786:8787",
               r"one ':' only, between the host and the port",
               "two ports (once blamed on the port's range)"),
    _scheduler("scheduler-user-name", "tcp://ops@node3:8786", r"no user name",
               "a user name before the host (once silently dropped, node3 dialled)"),
    _scheduler("scheduler-newline", "tcp://node3\n:8786",
               r"--scheduler 'tcp://node3\\n:8786': '\\n' \(character 12\) has no place",
               "a newline inside the address (once dropped by urlsplit, and the message "
               "two lines)"),
    _scheduler("scheduler-empty-label", "tcp://node3..lab:8786",
               r"'node3\.\.lab' is not a host name",
               "a host name with an empty label (once a UnicodeError traceback from the "
               "connection)"),
    _scheduler("scheduler-trailing-slash", "tcp://node3:8786/", r"nothing may follow the port",
               "a slash after the port (once accepted and given to Dask as it was)"),
    _scheduler("scheduler-port-in-letters", "tcp://node3:http",
               r"the port must be 1\.\.65535", "a service name for the port"),
    # ---- results directories whose lock cannot be taken (a traceback from filelock)
    Case("sweep-lock-is-a-directory", "sweep --out a directory whose _lock is a directory "
         "(once an IsADirectoryError traceback)", ResultsDirectoryError,
         r"--out .*/res: its lock file _lock cannot be opened: remove _lock if it is not "
         r"a sweep's lock, or give another --out \(Is a directory\)",
         cli=lambda tmp: _sweep(tmp, "--out", str(_results_with_lock(tmp, Path.mkdir)))),
    Case("sweep-lock-is-a-symlink", "sweep --out a directory whose _lock is a symbolic "
         "link to another file (once a traceback; never followed)", ResultsDirectoryError,
         r"its lock file _lock cannot be opened: .*\(Too many levels of symbolic links\)",
         cli=lambda tmp: _sweep(tmp, "--out", str(_results_with_lock(
             tmp, lambda p: p.symlink_to(_bytes(tmp, "elsewhere.txt", b"keep\n")))))),
    Case("sweep-out-a-device", "sweep --out /dev/null (a results directory that is a "
         "device)", ResultsDirectoryError,
         r"--out /dev/null: exists and is not a directory \(a character device\)",
         cli=lambda tmp: _sweep(tmp, "--out", "/dev/null")),
    # ---- outputs that are sockets (once replaced by a regular file)
    Case("id-out-socket", "id --out onto a Unix socket (once replaced by the CSV)",
         oc.OutputError,
         r"--out: cannot write .*/sock\.csv: is a socket, not a file: write to a regular "
         r"file", cli=lambda tmp: ["id", "--duration", "0.5", "--out",
                                   str(_socket_file(tmp, "sock.csv"))]),
    Case("simulate-plot-socket", "simulate --plot onto a Unix socket named .png",
         oc.OutputError, r"--plot: cannot write .*/sock\.png: is a socket",
         cli=lambda tmp: ["simulate", "--duration", "0.1", "--plot",
                          str(_socket_file(tmp, "sock.png"))]),
    Case("export-mjcf-socket", "export --mjcf onto a Unix socket", oc.OutputError,
         r"--mjcf: cannot write .*/sock\.xml: is a socket",
         cli=lambda tmp: ["export", "--mjcf", str(_socket_file(tmp, "sock.xml"))]),
    Case("describe-out-socket", "describe --out onto a Unix socket", oc.OutputError,
         r"--out: cannot write .*/sock\.yaml: is a socket",
         cli=lambda tmp: ["describe", "--out", str(_socket_file(tmp, "sock.yaml"))]),
    Case("sweep-csv-socket", "sweep --csv onto a Unix socket", oc.OutputError,
         r"--csv: cannot write .*/sock\.csv: is a socket",
         cli=lambda tmp: _sweep(tmp, "--csv", str(_socket_file(tmp, "sock.csv")))),
    Case("sweep-plot-socket", "sweep --plot DIR onto a Unix socket", oc.OutputError,
         r"--plot .*/sock: exists and is not a directory \(a socket\)",
         cli=lambda tmp: _sweep(tmp, "--plot", str(_socket_file(tmp, "sock")))),
    Case("sweep-out-socket", "sweep --out RESULTS_DIR onto a Unix socket",
         ResultsDirectoryError, r"--out .*/sock: exists and is not a directory \(a socket\)",
         cli=lambda tmp: _sweep(tmp, "--out", str(_socket_file(tmp, "sock")))),
    # ---- memory limits that are no limit (nan turned the guard off; 0 refused all)
    Case("memory-limit-inf", "OFFSHORE_CRANE_MEMORY_LIMIT=inf (the guard off)",
         oc.InputError, _LIMIT.format("inf"), lib=_limit("inf")),
    Case("memory-limit-overflow", "OFFSHORE_CRANE_MEMORY_LIMIT=1e999 (read as inf)",
         oc.InputError, _LIMIT.format("1e999"), lib=_limit("1e999")),
    Case("memory-limit-upper-nan", "OFFSHORE_CRANE_MEMORY_LIMIT=NAN", oc.InputError,
         _LIMIT.format("NAN"), lib=_limit("NAN")),
    Case("memory-limit-minus-zero", "OFFSHORE_CRANE_MEMORY_LIMIT=-0.0", oc.InputError,
         _LIMIT.format("-0.0"), lib=_limit("-0.0")),
    Case("memory-limit-hex", "OFFSHORE_CRANE_MEMORY_LIMIT=0x40000000", oc.InputError,
         _LIMIT.format("0x40000000"), lib=_limit("0x40000000")),
    Case("memory-limit-with-unit", "OFFSHORE_CRANE_MEMORY_LIMIT=8GB (units are not read)",
         oc.InputError, _LIMIT.format("8GB"), lib=_limit("8GB")),
]
