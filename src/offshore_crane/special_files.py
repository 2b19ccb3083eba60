"""FIFOs and devices without a hang: written without ever blocking on their ``open``, read
with a timeout (what :mod:`offshore_crane.io` does with a path that is not a regular
file).

A plain ``open(fifo, "w")`` waits until a process opens the FIFO for reading: forever
when none does (an output named after computing minutes, then stuck). Here a FIFO is
opened non-blocking, which fails at once (``ENXIO``) while no process reads it; the open
is retried for a bounded time, then the caller refuses the output. A device is opened
non-blocking too (a terminal line would wait for a carrier). Only the standard library
and OS errors: the caller words the message.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat

#: How often a FIFO without a reader is tried again [s].
PIPE_POLL = 0.02


def is_fifo(path) -> bool:
    """Whether ``path`` (followed through symbolic links) is a FIFO."""
    try:
        return stat.S_ISFIFO(os.stat(path).st_mode)
    except OSError:
        return False


def pipe_writer(path, timeout: float) -> int | None:
    """A blocking write end of the FIFO ``path``, opened as soon as a process reads it,
    or None when none did within ``timeout`` [s].

    Raises:
        OSError: the FIFO cannot be opened (permissions, gone).
    """
    import time

    deadline = time.monotonic() + timeout
    while True:
        try:
            fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK | os.O_CLOEXEC)
        except OSError as exc:
            if exc.errno != errno.ENXIO:          # ENXIO: no reader (yet)
                raise
            if time.monotonic() >= deadline:
                return None
            time.sleep(PIPE_POLL)
            continue
        os.set_blocking(fd, True)
        return fd


def device_writer(path) -> int:
    """A blocking write descriptor of the character device ``path``, opened without
    waiting.

    Raises:
        OSError: it cannot be opened.
    """
    fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    os.set_blocking(fd, True)
    return fd


def read_pipe(path, timeout: float) -> bytes | None:
    """The whole content of the FIFO ``path``, or None when its writer did not connect and
    finish within ``timeout`` [s] (the read goes on in a daemon thread, which a plain
    ``open`` would block forever).

    Raises:
        OSError: it cannot be read.
    """
    import threading

    out: list = []

    def read() -> None:
        try:
            with open(path, "rb") as fh:        # blocks until a writer connects
                out.append(fh.read())
        except OSError as exc:
            out.append(exc)

    reader = threading.Thread(target=read, daemon=True, name=f"read {path}")
    reader.start()
    reader.join(timeout)
    if out and isinstance(out[0], OSError):
        raise out[0]
    return out[0] if out else None


class Held:
    """A descriptor held open until it is taken (a FIFO's write end from the planning of
    an output to its write: its reader keeps waiting for the data instead of seeing its
    end); closed when dropped untaken."""

    def __init__(self, fd: int):
        self.fd: int | None = fd

    def take(self) -> int | None:
        """The descriptor, once (None after)."""
        fd, self.fd = self.fd, None
        return fd

    def __del__(self):
        if self.fd is not None:
            with contextlib.suppress(OSError):
                os.close(self.fd)


def what_is(path) -> str:
    """What ``path`` is (followed through symbolic links), for a message: ``"a
    directory"``, ``"a FIFO (named pipe)"``, ``"a socket"``, ``"a character device"``,
    ``"a block device"``, ``"a file"``, or ``"nothing"`` (it does not exist)."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return "nothing"
    for test, name in ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISSOCK, "a socket"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device")):
        if test(mode):
            return name
    return "a file"
