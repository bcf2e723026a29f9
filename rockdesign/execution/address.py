"""Dask values (``--dask`` / ``executor=``) checked before anything connects, and schedulers that must speak.

A dask value names a local cluster (``local`` or ``local:N``, N ≥ 1 worker processes) or a scheduler address
(``tcp://host:8786``, ``tls://``, ``ws://``, ``wss://``, or ``host:port``).  Three steps, each refusing with an
:class:`ExecutorError` keyed ``executor`` (the command line shows ``--dask``) that names the address:

1. :func:`check_address` — the text alone, whether or not dask is installed: the transport, a host, a port
   in 1–65535 (``tcp://127.0.0.1:70267`` would wrap to port 4731 in the socket layer), ``local:N`` with an
   integer N ≥ 1;
2. :func:`reach_scheduler` — a TCP connection within :data:`PROBE_TIMEOUT` (nobody listening, an unknown host);
3. :func:`probe_scheduler` — dask's own handshake (:func:`distributed.comm.connect`) within
   :data:`HANDSHAKE_TIMEOUT`: a port that accepts the connection and never speaks held ``check`` for minutes
   (dask bounds the connection but not the first message), and a port that answers something else had dask
   read its first bytes as a message length ("MemoryError: Unable to allocate 3.01 EiB").
"""
from __future__ import annotations

import asyncio
import concurrent.futures
import socket

from ..errors import RockdesignError

PROBE_TIMEOUT = 5.0
"""Seconds to wait for a TCP connection to a remote dask scheduler before refusing ``--dask``."""
HANDSHAKE_TIMEOUT = 10.0
"""Seconds a scheduler that accepted the connection has to complete dask's handshake before it is refused."""
SCHEMES = ("tcp", "tls", "ws", "wss")
"""dask.distributed's network transports a ``--dask`` address may name (``inproc://`` exists only inside one
process and cannot be reached from here)."""
MAX_PORT = 65535
EXPECTED = ("local:N (a local cluster of N ≥ 1 workers) or a scheduler address tcp://host:port, tls://, ws://, "
            "wss:// or host:port (port 1–65535)")


class ExecutorError(RockdesignError):
    """The execution backend cannot be used (bad ``--dask`` address, dask not installed...)."""


def _refuse(message: str, address, expected: str = EXPECTED) -> ExecutorError:
    return ExecutorError(message, key="executor", expected=expected, found=repr(str(address)))


def is_local(address: str) -> bool:
    """Whether a checked dask value starts a local cluster (``local`` or ``local:N``)."""
    return address == "local" or address.startswith("local:")


def check_address(address) -> str:
    """The dask value stripped, or :class:`ExecutorError` for one that names no cluster: not a string, empty or
    blank (it would silently run locally), ``local:N`` with N not an integer ≥ 1, a transport dask does not
    reach from another process, a scheduler address without a host or with a port outside 1–65535.
    ``localhost:8786`` is a scheduler address, not a local cluster: only ``local`` and ``local:N`` start one.
    Needs no dask."""
    if not isinstance(address, str):
        raise ExecutorError("a dask address is text", key="executor", expected=EXPECTED,
                            found=f"{address!r} ({type(address).__name__})")
    text = address.strip()
    if not text:
        raise _refuse("empty dask address", address, EXPECTED + " (or no dask executor, to run in this process)")
    if text == "local" or text.startswith("local:"):
        rest = text[len("local:"):] if text != "local" else ""
        if text != "local" and not (rest.isascii() and rest.isdigit() and int(rest) >= 1):
            raise _refuse("invalid local cluster: N must be a whole number of workers ≥ 1", address,
                          "local:N with N ≥ 1 workers (local:4), or a scheduler address (tcp://host:8786)")
        return text
    scheme, sep, target = text.rpartition("://")
    if sep and scheme not in SCHEMES:
        raise _refuse("unknown transport of the dask scheduler address", address)
    host, colon, port = target.rstrip("/").rpartition(":")
    if not colon or not host.strip("[]") or any(c.isspace() or c in "/?#@" for c in host):
        raise _refuse("invalid dask scheduler address: it needs a host and a port", address)
    if not (port.isascii() and port.isdigit()):
        raise _refuse(f"invalid port '{port}' of the dask scheduler address", address)
    if not 1 <= int(port) <= MAX_PORT:
        raise _refuse(f"port {int(port)} of the dask scheduler address is outside 1–{MAX_PORT}", address)
    return text


def _host_port(address: str) -> tuple[str, int]:
    target = address.strip().rpartition("://")[2].rstrip("/")
    host, _, port = target.rpartition(":")
    return host.strip("[]") or "localhost", int(port)


def reach_scheduler(address: str, timeout: float | None = None) -> None:
    """Open (and close) a TCP connection to the scheduler at ``address`` (``tcp://``, ``tls://``, ``ws://``,
    ``wss://host:port`` or ``host:port``: every transport runs over TCP), so an unreachable scheduler is
    refused at once, before any output is created."""
    check_address(address)
    timeout = PROBE_TIMEOUT if timeout is None else timeout
    try:
        with socket.create_connection(_host_port(address), timeout=timeout):
            pass
    except (OSError, ValueError, OverflowError) as exc:
        raise ExecutorError(f"cannot reach the dask scheduler ({getattr(exc, 'strerror', None) or exc})",
                            key="executor", expected="a running scheduler (dask scheduler; dask worker ADDRESS) "
                            "reachable within {:g} s".format(timeout), found=repr(address)) from None


def tls_hint(address: str) -> str:
    """What a ``tls://``/``wss://`` address also needs (dask's TLS configuration), or ''."""
    return "" if not address.startswith(("tls://", "wss://")) else \
        " with the TLS certificates of dask's configuration (distributed.comm.tls)"


async def _handshake(address: str, timeout: float) -> None:
    from distributed.comm import connect
    comm = await asyncio.wait_for(connect(address, timeout=timeout), timeout)
    comm.abort()


def probe_scheduler(address: str, timeout: float | None = None) -> None:
    """Complete dask's handshake with the scheduler at ``address`` within ``timeout`` seconds, then close the
    connection; :class:`ExecutorError` naming the address when it does not answer in time or answers something
    that is not dask (default timeout :data:`HANDSHAKE_TIMEOUT`).  Runs in a thread of its own, so it works
    inside a running event loop (a notebook)."""
    timeout = HANDSHAKE_TIMEOUT if timeout is None else timeout
    pool = concurrent.futures.ThreadPoolExecutor(1, thread_name_prefix="rockdesign-dask-probe")
    future = pool.submit(asyncio.run, _handshake(address, timeout))
    try:
        future.result(timeout + 1.0)
    except (asyncio.TimeoutError, concurrent.futures.TimeoutError, TimeoutError):
        raise ExecutorError(f"the dask scheduler accepted the connection but did not answer within {timeout:g} s",
                            key="executor", expected="a dask scheduler that completes dask's handshake "
                            f"within {timeout:g} s (is this port a dask scheduler?)", found=repr(address)) from None
    except TypeError:       # a tls:// address without dask's TLS configuration
        raise ExecutorError("cannot connect to the dask scheduler", key="executor",
                            expected="a running scheduler" + tls_hint(address), found=repr(address)) from None
    except OSError as exc:
        raise ExecutorError(f"cannot connect to the dask scheduler ({exc})", key="executor",
                            expected="a running scheduler (dask scheduler; dask worker ADDRESS)" + tls_hint(address),
                            found=repr(address)) from None
    except Exception as exc:  # noqa: BLE001 — whatever dask makes of bytes that are not its protocol
        raise ExecutorError("the port answered, but not as a dask scheduler "
                            f"({type(exc).__name__}: {str(exc)[:120]})", key="executor",
                            expected="the address of a dask scheduler (dask scheduler prints it)",
                            found=repr(address)) from None
    finally:
        pool.shutdown(wait=False, cancel_futures=True)


def require_dask(address) -> None:
    """:class:`ExecutorError` when dask.distributed cannot be imported (after the address was checked)."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise ExecutorError("dask.distributed is not installed", key="executor",
                            expected="pip install 'rockdesign[dask]' to use " + repr(str(address)),
                            found="no module 'distributed'") from None
