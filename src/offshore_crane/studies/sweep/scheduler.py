"""A Dask scheduler's address and the check that Dask answers there, before a client
connects: the address parsed strictly (every malformed form one line), and the first
message read from the peer bounded in size and time (a peer that is not Dask is refused;
nothing it sends is allocated beyond :data:`MAX_HANDSHAKE` bytes).
"""

from __future__ import annotations

import re
import struct

from offshore_crane.errors import InputError, SchedulerError


#: Seconds to wait for a Dask scheduler (its connection and its handshake, in all) before
#: calling it unreachable.
CONNECT_TIMEOUT = 3.0
#: The largest first message accepted from a scheduler [bytes]. Dask's handshake (its
#: compression, Python version and pickle protocol, msgpack-encoded in one frame) is
#: ~60 bytes; a length prefix beyond this is not Dask (an SSH banner read as a length
#: announces 3e18 bytes), and is refused before anything is allocated.
MAX_HANDSHAKE = 4096
#: Dask's frame lengths: unsigned 64-bit in the machine's byte order
#: (``distributed.comm.tcp``).
_LENGTH = struct.Struct("Q")
_HINT = "give 'local' (a Dask LocalCluster here) or a scheduler's tcp://HOST:PORT"
_LABEL = re.compile(r"(?!-)[A-Za-z0-9_-]{1,63}(?<!-)")


def check_scheduler(scheduler) -> str | None:
    """``None``, ``"local"`` or a checked Dask address ``tcp://HOST:PORT`` (the scheme,
    a host and a port 1..65535), before anything runs.

    Raises:
        InputError: anything else, naming what to give.
    """
    if scheduler is None or scheduler == "local":
        return scheduler
    scheduler_address(scheduler)
    return scheduler


def scheduler_address(scheduler) -> tuple[str, int]:
    """``(host, port)`` of a Dask scheduler address ``tcp://HOST:PORT``: HOST a host name
    (labels of letters, digits, ``-`` and ``_``), an IPv4 address or an IPv6 address in
    brackets (``tcp://[::1]:8786``), PORT 1..65535 in decimal digits, nothing else.

    Raises:
        InputError: not such an address, naming the part that is wrong.
    """
    if not isinstance(scheduler, str) or "://" not in scheduler:
        raise InputError(f"--scheduler {scheduler!r}: {_HINT}", name="scheduler")
    shown = scheduler if scheduler.isprintable() else repr(scheduler)

    def refuse(what: str):
        raise InputError(f"--scheduler {shown}: {what}: {_HINT}", name="scheduler")

    scheme, rest = scheduler.split("://", 1)
    if scheme != "tcp":
        refuse("the scheme must be tcp")
    odd = next((i for i, c in enumerate(rest) if not (c.isascii() and c.isprintable())
                or c == " "), None)
    if odd is not None:
        refuse(f"{rest[odd]!r} (character {len(scheme) + 4 + odd}) has no place in an "
               "address" + ("" if rest[odd].isascii() else
                            " (an international host name: its xn-- form)"))
    if "@" in rest:
        refuse("no user name: give the host alone")
    end = min((rest.index(c) for c in "/?#" if c in rest), default=len(rest))
    if end < len(rest):
        refuse("nothing may follow the port")
    host, port = _host_port(rest, refuse)
    if not re.fullmatch(r"[0-9]{1,5}", port) or not 0 < int(port) < 65536:
        refuse("the port must be 1..65535" + ("" if port else " (none given)"))
    return host, int(port)


def _host_port(rest: str, refuse) -> tuple[str, str]:
    """``(host, port text)`` of ``HOST:PORT`` (``refuse(what)`` raises)."""
    import ipaddress

    if rest.startswith("["):                                  # an IPv6 address
        close = rest.find("]")
        if close < 0:
            refuse("'[' opens an IPv6 address that no ']' closes (e.g. tcp://[::1]:8786)")
        inside, after = rest[1:close], rest[close + 1:]
        try:
            ipaddress.IPv6Address(inside)
        except ValueError:
            refuse(f"[{inside}] is not an IPv6 address (brackets hold IPv6 only)")
        if not after.startswith(":"):
            refuse("the port must follow ']' as :PORT" if after else
                   "the port must be 1..65535 (none given)")
        return inside, after[1:]
    if "]" in rest:
        refuse("']' without '[': an IPv6 address goes in brackets (tcp://[::1]:8786)")
    host, colon, port = rest.rpartition(":")
    if not colon:
        host, port = rest, ""
    if ":" in host:
        try:
            ipaddress.IPv6Address(rest)
            ipv6 = True
        except ValueError:
            ipv6 = False
        refuse("an IPv6 address goes in brackets (tcp://[::1]:8786)" if ipv6 or "::" in rest
               else "one ':' only, between the host and the port")
    if not host:
        refuse("no host")
    labels = host[:-1].split(".") if host.endswith(".") else host.split(".")
    if len(host) > 253 or not all(_LABEL.fullmatch(label) for label in labels):
        refuse(f"{host!r} is not a host name (labels of ≤ 63 letters, digits, '-', '_' "
               "joined by '.')")
    return host, port


def handshake(scheduler: str, timeout: float = CONNECT_TIMEOUT) -> None:
    """Connect to the address and read the scheduler's handshake (a Dask scheduler writes
    its own at once: a length, a frame count, frame lengths and a msgpack map), all
    within ``timeout`` [s]. Every length is checked before anything is read into memory
    (at most :data:`MAX_HANDSHAKE` bytes); a closed port, a listener that is not Dask (a
    web server waits for a request forever; an SSH server sends its banner) and a peer
    that trickles bytes all end here, before Dask's client reads from it.

    Raises:
        InputError: a malformed address. SchedulerError: anything else, one line.
    """
    import socket
    import time

    host, port = scheduler_address(scheduler)
    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except OSError as exc:
        reason = exc.strerror or str(exc) or type(exc).__name__
        raise SchedulerError(f"--scheduler {scheduler}: cannot reach the Dask scheduler "
                             f"within {timeout:g} s ({reason}): start it (dask scheduler) "
                             "or check the address; nothing was run or written",
                             address=scheduler, reason=reason) from None
    with sock:
        reason = _not_a_handshake(sock, deadline)
    if reason is not None:
        raise SchedulerError(f"--scheduler {scheduler}: something listens there but sent no "
                             f"Dask handshake within {timeout:g} s ({reason}): is it a Dask "
                             "scheduler? nothing was run or written",
                             address=scheduler, reason=reason)


def _not_a_handshake(sock, deadline: float) -> str | None:
    """Why what ``sock`` sends before ``deadline`` (``time.monotonic()``) is not a Dask
    handshake, or None when it is one."""
    from offshore_crane.studies.sweep.grid import install_hint

    head = _receive(sock, _LENGTH.size, deadline)
    if isinstance(head, str):
        return head
    (total,) = _LENGTH.unpack(head)
    if not 2 * _LENGTH.size <= total <= MAX_HANDSHAKE:
        return (f"its first message announces {total} bytes; a Dask handshake has at most "
                f"{MAX_HANDSHAKE}")
    body = _receive(sock, total, deadline)
    if isinstance(body, str):
        return body
    (frames,) = _LENGTH.unpack_from(body)
    if not 1 <= frames <= total // _LENGTH.size - 1:
        return f"its first message announces {frames} frames"
    lengths = struct.unpack_from(f"{frames}Q", body, _LENGTH.size)
    start = _LENGTH.size * (1 + frames)
    if sum(lengths) != total - start:
        return "its first message's frames do not add up to its length"
    msgpack = install_hint("msgpack", "--scheduler (Dask)")
    try:
        info = msgpack.unpackb(body[start:start + lengths[0]], raw=False)
    except (ValueError, msgpack.UnpackException):
        info = None
    if not isinstance(info, dict) or not {"python", "pickle-protocol"} <= set(info):
        return "its first message is not a Dask handshake"
    return None


def _receive(sock, n: int, deadline: float) -> bytes | str:
    """Exactly ``n`` bytes from ``sock`` by ``deadline``, or why not (text)."""
    import time

    got = bytearray()
    while len(got) < n:
        left = deadline - time.monotonic()
        if left <= 0:
            return "no Dask handshake" if not got else "an incomplete message"
        sock.settimeout(left)
        try:
            chunk = sock.recv(n - len(got))
        except TimeoutError:
            continue
        except OSError as exc:
            return exc.strerror or type(exc).__name__
        if not chunk:
            return "connection closed"
        got += chunk
    return bytes(got)
