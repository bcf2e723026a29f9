"""``--dask`` / ``executor=``: addresses checked before any connection, schedulers that must speak (issue 49).

Every case ends in exit 2 naming ``--dask`` (the library: ``key == "executor"``) and the address, with and
without dask installed ("absent" is simulated by making ``import distributed`` fail), before any kernel is
compiled and with no output folder left behind.  The two servers a port may hide are real sockets in a thread:
one accepts the connection and never says a word (``check`` waited minutes), one answers HTTP, whose first 8
bytes dask read as a message length ("MemoryError: Unable to allocate 3.01 EiB").
"""
from __future__ import annotations

import socket
import sys
import threading
import time

import pytest
from typer.testing import CliRunner

import rockdesign as rd
from rockdesign import library
from rockdesign.cli import app
from rockdesign.execution import address as dask_address
from rockdesign.execution.executor import ExecutorError, make_executor
from rockdesign.paths import REPO_ROOT

runner = CliRunner()
PIER = str(REPO_ROOT / "examples" / "bridge_pier.toml")
CURVED = str(REPO_ROOT / "examples" / "podium_curved.toml")
HTTP_REPLY = b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n"


def assert_one_line_error(result, *fragments):
    assert result.exit_code == 2, (result.exit_code, result.output)
    assert "Traceback" not in result.output, result.output
    text = " ".join(result.stderr.split())
    assert text.count("error:") == 1, text
    for fragment in fragments:
        assert fragment in text, (fragment, text)
    return text


@pytest.fixture
def no_compiling(monkeypatch):
    def boom(*args, **kwargs):
        raise AssertionError("compiled kernels before the --dask value was refused")
    monkeypatch.setattr("rockdesign.execution.compilation.prepare", boom)


@pytest.fixture(params=["dask installed", "dask absent"])
def dask_presence(request, monkeypatch):
    """Both ways: dask.distributed importable, and not (``import distributed`` raises ImportError)."""
    if request.param == "dask absent":
        monkeypatch.setitem(sys.modules, "distributed", None)
    else:
        pytest.importorskip("distributed")
    return request.param


class Server:
    """A TCP server on 127.0.0.1 in a thread: ``reply`` None accepts and stays silent, else sends ``reply``."""

    def __init__(self, reply: bytes | None):
        self.reply = reply
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen()
        self.sock.settimeout(0.2)
        self.address = f"tcp://127.0.0.1:{self.sock.getsockname()[1]}"
        self.accepted = 0
        self._stop = threading.Event()
        self._held = []
        self._thread = threading.Thread(target=self._serve, daemon=True)
        self._thread.start()

    def _serve(self):
        while not self._stop.is_set():
            try:
                conn, _ = self.sock.accept()
            except OSError:
                continue
            self.accepted += 1
            self._held.append(conn)              # held open: a silent peer, not a closed one
            if self.reply is not None:
                try:
                    conn.sendall(self.reply)
                except OSError:
                    pass

    def close(self):
        self._stop.set()
        self._thread.join(5)
        for conn in self._held:
            conn.close()
        self.sock.close()


@pytest.fixture
def silent():
    server = Server(None)
    yield server
    server.close()


@pytest.fixture
def junk():
    server = Server(HTTP_REPLY)
    yield server
    server.close()


@pytest.fixture
def short_handshake(monkeypatch):
    monkeypatch.setattr(dask_address, "HANDSHAKE_TIMEOUT", 1.0)


# ------------------------------------------------------------------ the text alone, dask or not
BAD = [
    ("tcp://127.0.0.1:70267", "port 70267", "outside 1–65535"),
    ("tcp://127.0.0.1:0", "port 0", "outside 1–65535"),
    ("127.0.0.1:99999", "port 99999", "outside 1–65535"),
    ("local:0", "invalid local cluster", "N ≥ 1"),
    ("local:-1", "invalid local cluster", "N ≥ 1"),
    ("local:abc", "invalid local cluster", "N ≥ 1"),
    ("local:²", "invalid local cluster", "N ≥ 1"),
    ("tcp://127.0.0.1:port", "invalid port 'port'", "host:port"),
    ("tcp://:8786", "needs a host and a port", "tcp://host:port"),
    ("udp://127.0.0.1:8786", "unknown transport", "tcp://host:port"),
    ("   ", "empty dask address", "local:N"),
]


@pytest.mark.parametrize("value,problem,expected", BAD)
def test_bad_addresses_are_named_with_and_without_dask(value, problem, expected, dask_presence):
    for call in (lambda: make_executor(value), lambda: dask_address.check_address(value)):
        with pytest.raises(ExecutorError) as err:
            call()
        assert err.value.key == "executor" and problem in str(err.value) and expected in str(err.value)
        assert repr(value) in str(err.value)


@pytest.mark.parametrize("value,problem,expected", BAD[:4])
@pytest.mark.parametrize("command", ["check", "design", "spectrum"])
def test_bad_addresses_from_the_command_line(tmp_path, value, problem, expected, command, dask_presence,
                                             no_compiling):
    args = {"check": ["check", PIER, "--no-pdf"],
            "design": ["design", CURVED, "--vary", "podium.width=0.36m:0.44m:2", "--no-pdf"],
            "spectrum": ["spectrum", PIER, "--pulse", "sine", "--x", "omega_p/p:1:2:2", "--y", "ap/up:1:2:2"]}
    r = runner.invoke(app, [*args[command], "--dask", value, "-o", str(tmp_path / "out")])
    assert_one_line_error(r, "key '--dask'", problem, expected, repr(value))
    assert not (tmp_path / "out").exists()


def test_a_good_address_without_dask_says_how_to_install(monkeypatch, silent):
    monkeypatch.setitem(sys.modules, "distributed", None)
    for value in ("local:2", silent.address):
        with pytest.raises(ExecutorError, match=r"dask.distributed is not installed.*rockdesign\[dask\]"):
            make_executor(value)
    assert silent.accepted == 0          # nothing connects to a scheduler dask could not use anyway


# ------------------------------------------------------------------ ports that accept and then misbehave
def test_a_silent_scheduler_is_refused_after_the_stated_timeout(silent, short_handshake):
    pytest.importorskip("distributed")
    t0 = time.perf_counter()
    with pytest.raises(ExecutorError) as err:
        make_executor(silent.address)
    took = time.perf_counter() - t0
    assert err.value.key == "executor" and repr(silent.address) in str(err.value)
    assert "did not answer within 1 s" in str(err.value)
    assert 0.9 < took < 10, took
    assert silent.accepted >= 1


def test_a_port_answering_junk_is_refused(junk):
    pytest.importorskip("distributed")
    t0 = time.perf_counter()
    with pytest.raises(ExecutorError) as err:
        make_executor(junk.address)
    assert time.perf_counter() - t0 < dask_address.HANDSHAKE_TIMEOUT
    assert err.value.key == "executor" and repr(junk.address) in str(err.value)
    assert "not as a dask scheduler" in str(err.value)


@pytest.mark.parametrize("which", ["silent", "junk"])
@pytest.mark.parametrize("command", ["check", "design"])
def test_misbehaving_schedulers_from_the_command_line(tmp_path, which, command, request, short_handshake,
                                                      no_compiling):
    pytest.importorskip("distributed")
    server = request.getfixturevalue(which)
    args = {"check": ["check", PIER, "--no-pdf"],
            "design": ["design", CURVED, "--vary", "podium.width=0.36m:0.44m:2", "--no-pdf"]}[command]
    t0 = time.perf_counter()
    r = runner.invoke(app, [*args, "--dask", server.address, "-o", str(tmp_path / "out")])
    assert time.perf_counter() - t0 < 60
    what = "did not answer within 1 s" if which == "silent" else "not as a dask scheduler"
    assert_one_line_error(r, "key '--dask'", what, repr(server.address))
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("which", ["silent", "junk"])
def test_misbehaving_schedulers_from_the_library(which, request, short_handshake):
    pytest.importorskip("distributed")
    server = request.getfixturevalue(which)
    project = rd.load_project(PIER)
    for call in (lambda: rd.check(project, executor=server.address),
                 lambda: rd.design(project, ["pier.width=0.30m:0.40m:2"], executor=server.address)):
        with pytest.raises(ExecutorError) as err:
            call()
        assert err.value.key == "executor" and repr(server.address) in str(err.value)


def test_a_real_scheduler_passes_the_probe(dask_cluster):
    """The handshake probe is what dask itself does: a real scheduler answers it at once."""
    t0 = time.perf_counter()
    dask_address.probe_scheduler(dask_cluster.scheduler_address)
    library.check_options(rd.load_project(PIER), executor=dask_cluster.scheduler_address)
    assert time.perf_counter() - t0 < 5
