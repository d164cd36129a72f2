"""A free TCP port, the kernel's pick: for a server a test or tool starts and must name the port of.

No ROS in here, and nothing but the standard library: the podman suites (tests/e2e/test_image.py),
which run with Debian's /usr/bin/python3 possibly without ROS sourced, import it from its source
folder (the Makefile's PYTHONPATH).
"""
from __future__ import annotations

import socket

LOOPBACK = "127.0.0.1"


def free_port(host: str = LOOPBACK) -> int:
    """A TCP port nobody listens on at `host` right now (bound to port 0, then released)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind((host, 0))
        return sock.getsockname()[1]
