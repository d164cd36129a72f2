"""The process id of the ROS master at a URI: one XML-RPC `getPid` over a plain socket.

roslab asks this every 0.5-2 s for as long as the lab page is open, in every student's container.
xmlrpc.client would do it in one line, but it brings http.client, email's parsers and pyexpat:
1.9 MiB of roslab's resident memory for one call whose request is a fixed document and whose answer
is three values. So the request is written here and the answer read strictly: anything but an
HTTP 200 whose body is a methodResponse of [int code, string, int pid], read within the time limit
and the size limit, is no master.
"""
from __future__ import annotations

import re
import socket
import time
from typing import Optional, Tuple

MAX_REPLY_BYTES = 64 * 1024
REQUEST_BODY = ("<?xml version='1.0'?>\n<methodCall>\n<methodName>getPid</methodName>\n<params>\n"
                "<param>\n<value><string>%s</string></value>\n</param>\n</params>\n</methodCall>\n")
_INT = r"<value>\s*<(?:int|i4)>\s*([+-]?\d{1,10})\s*</(?:int|i4)>\s*</value>"
_STRING = r"<value>(?:[^<]*|\s*<string>[^<]*</string>\s*|\s*<string/>\s*)</value>"
REPLY = re.compile(r"\A\s*(?:<\?xml[^>]*\?>)?\s*<methodResponse>\s*<params>\s*<param>\s*<value>\s*<array>\s*"
                   r"<data>\s*%s\s*%s\s*%s\s*</data>\s*</array>\s*</value>\s*</param>\s*</params>\s*"
                   r"</methodResponse>\s*\Z" % (_INT, _STRING, _INT))
_URI = re.compile(r"\Ahttp://(\[[0-9A-Fa-f:.]+\]|[^/:\[\]]+):(\d{1,5})(/[^\s]*)?\Z")


def escape(text: str) -> str:
    """`text` as XML character data (xml.sax.saxutils' would import urllib.request and ssl)."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def split_uri(uri: str) -> Optional[Tuple[str, int, str]]:
    """(host, port, path) of an http://host:port[/path] URI, or None for anything else."""
    found = _URI.match(uri.strip())
    if found is None or not 0 < int(found.group(2)) < 65536:
        return None
    return found.group(1).strip("[]"), int(found.group(2)), found.group(3) or "/"


def read_reply(sock: socket.socket, deadline: float) -> Optional[bytes]:
    """All the server sends until it closes, or None past `deadline` or MAX_REPLY_BYTES."""
    chunks, size = [], 0
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return None
        sock.settimeout(left)
        chunk = sock.recv(16384)
        if not chunk:
            return b"".join(chunks)
        size += len(chunk)
        if size > MAX_REPLY_BYTES:
            return None
        chunks.append(chunk)


def parse_reply(reply: bytes) -> Optional[int]:
    """The pid in an HTTP reply to getPid, or None unless it is a 200 carrying [1, msg, pid]."""
    head, separator, body = reply.partition(b"\r\n\r\n")
    status = head.split(b"\r\n", 1)[0].split()
    if not separator or len(status) < 2 or not status[0].startswith(b"HTTP/1.") or status[1] != b"200":
        return None
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError:
        return None
    found = REPLY.match(text)
    if found is None or int(found.group(1)) != 1:
        return None
    return int(found.group(2))


def master_pid(uri: str, caller_id: str, timeout: float) -> Optional[int]:
    """The process id of the master at `uri`, or None when nothing answers as a master there
    within `timeout` seconds."""
    where = split_uri(uri)
    if where is None:
        return None
    host, port, path = where
    body = (REQUEST_BODY % escape(caller_id)).encode("utf-8")
    request = ("POST %s HTTP/1.0\r\nHost: %s:%d\r\nUser-Agent: roslab\r\nContent-Type: text/xml\r\n"
               "Content-Length: %d\r\n\r\n" % (path, host, port, len(body))).encode("ascii") + body
    deadline = time.monotonic() + timeout
    try:
        with socket.create_connection((host, port), timeout=timeout) as sock:
            sock.sendall(request)
            reply = read_reply(sock, deadline)
    except (OSError, UnicodeError, ValueError):
        return None
    return None if reply is None else parse_reply(reply)
