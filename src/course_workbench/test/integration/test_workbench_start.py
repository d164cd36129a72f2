"""`make jupyter`'s start-up refuses what it cannot do, in one sentence and a non-zero exit code,
before anything starts: a port already taken (which one, and how to pick another), a port that is
no port number."""
from __future__ import annotations

import os
import socket
import subprocess
import tempfile

from course_checks.isolation import free_port
from course_checks.nodes import find_executable
from course_workbench import startup


def start(env_changes: dict) -> subprocess.CompletedProcess:
    with tempfile.TemporaryDirectory() as home:
        env = dict(os.environ, HOME=home, **env_changes)
        return subprocess.run([find_executable("course_workbench", "workbench")], env=env, stdin=subprocess.DEVNULL,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60, check=False)


def test_a_busy_port_says_which_and_how_to_pick_another():
    # Where the workbench listens here: $JUPYTER_ADDRESS as it reads it (0.0.0.0 in the course image),
    # else its default 127.0.0.1. The port is taken on that address and the message names it.
    address = startup.parse([], os.environ).address
    with socket.socket(socket.AF_INET6 if ":" in address else socket.AF_INET) as taken:
        taken.bind((address, 0))
        taken.listen(1)
        port = taken.getsockname()[1]
        done = start({"JUPYTER_PORT": str(port)})
    assert done.returncode == 2, done.stdout + done.stderr
    assert "port %d is already in use on %s" % (port, address) in done.stderr
    assert "JUPYTER_PORT=%d make jupyter" % (port + 1) in done.stderr
    assert "Traceback" not in done.stderr + done.stdout


def test_a_port_that_is_no_number_is_refused():
    for wrong in ("eighty", "0", "70000"):
        done = start({"JUPYTER_PORT": wrong})
        assert done.returncode == 2
        assert "the port must be a number from 1 to 65535 (JUPYTER_PORT=%s)" % wrong in done.stderr
        assert "Traceback" not in done.stderr


def test_an_address_of_no_interface_here_is_refused():
    done = start({"JUPYTER_PORT": str(free_port()), "JUPYTER_ADDRESS": "192.0.2.1"})  # TEST-NET-1
    assert done.returncode == 2
    assert "cannot listen on 192.0.2.1 port" in done.stderr and "Traceback" not in done.stderr
