"""The env-token kill: a child that leaves its session, forks and ignores SIGINT/SIGTERM dies."""
import os
import socket
import subprocess
import sys

import pytest

from course_checks import isolation
from course_checks.waiting import wait_for

# A grandchild in a new session that ignores the polite signals, whose parent exits at once.
ESCAPER = r'''
import os, signal, sys, time
if os.fork() == 0:
    os.setsid()
    if os.fork() == 0:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        print(os.getpid(), flush=True)
        time.sleep(600)
    os._exit(0)
os.wait()
'''


def test_free_port_is_bindable():
    port = isolation.free_port()
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", port))


def test_a_port_below_the_ephemeral_range_is_free_and_out_of_the_kernels_picks(tmp_path):
    ranges = tmp_path / "ip_local_port_range"
    ranges.write_text("40000\t60999\n")
    ports = {isolation.port_below_ephemeral_range(ranges=str(ranges), lowest=39990) for _ in range(20)}
    assert ports <= set(range(39990, 40000))
    # A port someone holds is never given. The held one is the kernel's pick, not a fixed number:
    # on this machine 39990-39999 lie inside the real ephemeral range, where any process may hold one.
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        port = taken.getsockname()[1]
        ranges.write_text("%d 60999\n" % (port + 1))
        assert isolation.port_below_ephemeral_range(ranges=str(ranges), lowest=port) != port


def test_token_kill_reaches_a_setsid_double_forked_process():
    token = isolation.new_token()
    proc = subprocess.Popen([sys.executable, "-c", ESCAPER], env=isolation.token_env(dict(os.environ), token),
                            stdout=subprocess.PIPE, text=True)
    escaped = int(proc.stdout.readline())
    proc.wait(10)
    proc.stdout.close()
    assert escaped in isolation.pids_with_token(token)
    killed = isolation.kill_run(token)
    assert escaped in killed
    assert wait_for(lambda: not isolation.pids_with_token(token), 5)


def test_descendants_follow_the_parent_tree():
    proc = subprocess.Popen(["sh", "-c", "sleep 60 & sleep 60 & wait"])
    try:
        found = wait_for(lambda: len(isolation.descendants(proc.pid)) >= 2, 5)
        assert found
    finally:
        isolation.kill_run(isolation.new_token(), proc.pid)
        proc.wait(5)
    assert not isolation.descendants(proc.pid)


def test_file_size_cap_stops_an_endless_writer(tmp_path):
    target = tmp_path / "big.log"
    proc = subprocess.Popen(["sh", "-c", "sleep 0.2; yes 0123456789 > %s" % target])
    isolation.limit_file_size(proc.pid, 1024 * 1024)
    proc.wait(30)
    assert target.stat().st_size <= 1024 * 1024


def test_isolated_command_without_own_network_is_unchanged():
    assert isolation.isolated_command(["rostest", "a", "b.test"], False) == ["rostest", "a", "b.test"]


LISTENER = r'''
import socket, sys, time
server = socket.socket()
server.bind(("0.0.0.0", int(sys.argv[1])))
server.listen()
client = socket.create_connection(("127.0.0.1", int(sys.argv[1])))  # loopback works inside
print("up", flush=True)
time.sleep(60)
'''


@pytest.mark.skipif(not isolation.network_namespace_works(), reason="unshare --net is not allowed here (needs root)")
def test_own_network_hides_a_port_listening_on_every_interface():
    port = isolation.free_port()
    command = isolation.isolated_command([sys.executable, "-c", LISTENER, str(port)], own_network=True)
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, text=True, start_new_session=True)
    try:
        assert proc.stdout.readline().strip() == "up"
        with socket.socket() as probe:
            assert probe.connect_ex(("127.0.0.1", port)) != 0, "the run's port is reachable from outside"
    finally:
        isolation.kill_run(isolation.new_token(), proc.pid)
        proc.kill()
        proc.wait(5)
        proc.stdout.close()
