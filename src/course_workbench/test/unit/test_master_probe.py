"""roslab's getPid over a plain socket (master_probe) answers as xmlrpc.client would: the master's
pid from a real master, and None for anything that is not a master's answer, whatever the bytes,
the delay or the size; its request is XML-RPC that xmlrpc.client reads back."""
from __future__ import annotations

import contextlib
import socket
import subprocess
import sys
import threading
import time
import xmlrpc.client
from typing import Callable, Iterator

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from course_testkit import xmlrpc_fake
from course_testkit.master import PrivateMaster
from course_workbench import master_probe

CALLER = "/workbench_roslab"
TIMEOUT_S = 2.0


def test_a_real_master_answers_its_pid_as_xmlrpc_client_gets_it():
    with PrivateMaster() as master:
        _code, _message, pid = xmlrpc.client.ServerProxy(master.uri).getPid(CALLER)
        assert master_probe.master_pid(master.uri, CALLER, TIMEOUT_S) == pid
        assert master_probe.master_pid(master.uri + "/", CALLER, TIMEOUT_S) == pid
    assert master_probe.master_pid(master.uri, CALLER, TIMEOUT_S) is None  # stopped: refused


@pytest.fixture
def server() -> Iterator[Callable[[Callable], str]]:
    """A Python XML-RPC server whose getPid is the function given; its URI."""
    with contextlib.ExitStack() as servers:
        yield lambda get_pid: servers.enter_context(xmlrpc_fake.serving({"getPid": get_pid})).rstrip("/")


@pytest.mark.parametrize("answer, expected", [
    ((1, "", 4321), 4321),
    ((1, "a <message> & more", 7), 7),
    ((0, "not now", 4321), None),        # not a success code
    ((-1, "error", 4321), None),
    ((1, "", "4321"), None),             # a string, not an int
    ((1, "", 4321, 5), None),            # four values
    ([1, ""], None),
    ("4321", None),
    ((1, "", 4321.0), None),             # a double
])
def test_only_a_master_s_answer_is_a_pid(server, answer, expected):
    uri = server(lambda caller: answer)
    assert master_probe.master_pid(uri, CALLER, TIMEOUT_S) == expected


def test_a_fault_is_no_master(server):
    def fault(caller):
        raise ValueError("no")
    assert master_probe.master_pid(server(fault), CALLER, TIMEOUT_S) is None


def test_a_reply_over_the_size_limit_is_no_master(server):
    uri = server(lambda caller: (1, "x" * (master_probe.MAX_REPLY_BYTES + 1), 4321))
    assert master_probe.master_pid(uri, CALLER, TIMEOUT_S) is None


@pytest.fixture
def raw_server() -> Iterator[Callable[[bytes, float], str]]:
    """A TCP server that reads the request, waits, answers these bytes and closes; its URI."""
    listeners = []

    def serve(reply: bytes, delay: float = 0.0) -> str:
        listener = socket.create_server(("127.0.0.1", 0))
        listeners.append(listener)

        def answer() -> None:
            try:
                connection, _ = listener.accept()
            except OSError:
                return
            with connection:
                connection.recv(65536)
                time.sleep(delay)
                try:
                    connection.sendall(reply)
                except OSError:
                    pass
        threading.Thread(target=answer, daemon=True).start()
        return "http://127.0.0.1:%d" % listener.getsockname()[1]
    yield serve
    for listener in listeners:
        listener.close()


def test_a_server_slower_than_the_time_limit_is_no_master(raw_server):
    reply = b"HTTP/1.0 200 OK\r\n\r\n" + xmlrpc.client.dumps(((1, "", 9),), methodresponse=True).encode()
    uri = raw_server(reply, delay=3.0)
    assert master_probe.master_pid(uri, CALLER, 0.5) is None  # a master's answer, but after the limit


@pytest.mark.parametrize("reply", [
    b"",
    b"SSH-2.0-OpenSSH_9.2\r\n",
    b"HTTP/1.0 500 Internal Server Error\r\n\r\n",
    b"HTTP/1.0 200 OK\r\n\r\n<html>a web page</html>",
    b"HTTP/1.0 200 OK\r\n\r\n\xff\xfe<methodResponse>",
])
def test_something_else_listening_is_no_master(raw_server, reply):
    assert master_probe.master_pid(raw_server(reply), CALLER, TIMEOUT_S) is None


@pytest.mark.parametrize("uri", ["", "localhost:11311", "https://localhost:11311", "http://localhost",
                                 "http://localhost:0", "http://localhost:99999", "http://:11311", "http://a b:1"])
def test_a_uri_that_is_not_http_host_port_is_no_master(uri):
    assert master_probe.master_pid(uri, CALLER, TIMEOUT_S) is None


RESPONSE = st.tuples(st.integers(-3, 3), st.text(max_size=40),
                     st.integers(-2 ** 31, 2 ** 31 - 1))


@settings(max_examples=300, deadline=None)
@given(RESPONSE)
def test_any_well_formed_answer_reads_as_xmlrpc_client_reads_it(answer):
    code, _message, pid = answer
    body = xmlrpc.client.dumps((answer,), methodresponse=True).encode("utf-8")
    reply = b"HTTP/1.0 200 OK\r\nContent-Type: text/xml\r\n\r\n" + body
    assert master_probe.parse_reply(reply) == (pid if code == 1 else None)


@settings(max_examples=500, deadline=None)
@given(st.binary(max_size=600) | st.builds(lambda tail: b"HTTP/1.0 200 OK\r\n\r\n" + tail, st.binary(max_size=600)))
def test_any_bytes_read_as_none_or_a_pid_never_an_error(reply):
    found = master_probe.parse_reply(reply)
    assert found is None or isinstance(found, int)


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=80))
def test_any_uri_and_caller_id_give_none_or_a_request_never_an_error(text):
    assert master_probe.split_uri(text) is None or isinstance(master_probe.split_uri(text)[1], int)
    body = (master_probe.REQUEST_BODY % master_probe.escape(text)).encode("utf-8")
    try:
        params, method = xmlrpc.client.loads(body)
    except Exception:  # XML cannot carry this character (control characters): neither can xmlrpc.client
        assert any(ord(c) < 32 and c not in "\t\n\r" or 0xD800 <= ord(c) < 0xE000 or ord(c) in (0xFFFE, 0xFFFF)
                   for c in text)
        return
    assert method == "getPid" and params == (text.replace("\r\n", "\n").replace("\r", "\n"),)


def test_roslab_polls_without_xmlrpc_client_and_its_http_stack():
    code = ("import json, sys; import course_workbench.roslab; "
            "print(json.dumps([m for m in ('xmlrpc.client', 'http.client', 'email', 'ssl', 'pyexpat') "
            "if m in sys.modules]))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.strip().splitlines()[-1] == "[]"
