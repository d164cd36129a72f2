"""The private master against real rosmaster/roscore: ready when the block starts, on loopback
at its own port, and nothing of it left when the block ends, however it ends."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from course_checks import isolation
from course_testkit.master import PrivateMaster, rosout_registered, system_state
from course_checks.waiting import wait_for

# A node whose child leaves the process group and ignores Ctrl+C: only the run token finds it.
STUBBORN = r'''
import os, signal, time
if os.fork() == 0:
    os.setsid()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    print(os.getpid(), flush=True)
    time.sleep(600)
time.sleep(600)
'''


def alive(pid: int) -> bool:
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def listening(port: int) -> list:
    """The local addresses listening on TCP `port`, as ss prints them."""
    table = subprocess.run(["ss", "-ltnH", "sport = :%d" % port], capture_output=True, text=True).stdout
    return [line.split()[3] for line in table.splitlines() if line.strip()]


def test_the_master_answers_on_loopback_and_is_gone_after_the_block():
    with PrivateMaster() as master:
        assert master.uri == "http://localhost:%d" % master.port
        assert master.port != 11311
        assert system_state(master.uri) is not None
        assert not rosout_registered(system_state(master.uri)), "rosmaster --core alone has no rosout"
        assert master.env["ROS_MASTER_URI"] == master.uri and master.env["ROS_HOSTNAME"] == "localhost"
        assert "ROS_IP" not in master.env
        addresses = listening(master.port)
        assert addresses and all(a.startswith("127.0.0.1:") for a in addresses), addresses
        home, token = master.home, master.token
        assert home.is_dir()
    assert system_state(master.uri) is None
    assert not listening(master.port)
    assert not isolation.pids_with_token(token)
    assert not home.exists(), "a clean run leaves no scratch folder"


def test_with_rosout_the_graph_has_rosout_and_nodes_see_the_master():
    with PrivateMaster(rosout=True) as master:
        assert rosout_registered(system_state(master.uri))
        node = master.start(["rosnode", "list"], "rosnode")
        assert wait_for(lambda: not node.running(), 30)
        assert "/rosout" in node.output()
        token = master.token
    assert system_state(master.uri) is None
    assert not isolation.pids_with_token(token)


def test_a_node_that_left_its_group_and_ignores_ctrl_c_is_killed(tmp_path: Path):
    with PrivateMaster(home=tmp_path) as master:
        node = master.start([sys.executable, "-c", STUBBORN], "stubborn")
        assert wait_for(lambda: node.output().strip(), 30)
        pid = int(node.output().split()[0])
        assert alive(pid)
    assert wait_for(lambda: not alive(pid), 10), "the node that escaped its group survived"
    assert tmp_path.is_dir(), "a home given by the caller is the caller's"


def test_an_error_in_the_block_stops_everything_and_keeps_the_logs():
    with pytest.raises(ValueError):
        with PrivateMaster() as master:
            pid = master.start(["sleep", "600"], "sleeper").proc.pid
            raise ValueError("the scene failed")
    assert not alive(pid)
    assert system_state(master.uri) is None
    assert (master.home / "rosmaster.out").exists(), "the logs of a failed run are kept"
    shutil.rmtree(master.home)


def test_inside_another_run_the_run_token_is_kept_and_the_run_s_others_are_left_alone():
    outer = isolation.new_token()
    sibling = subprocess.Popen(["sleep", "600"], env=isolation.token_env(dict(os.environ), outer))
    try:
        with PrivateMaster(env=isolation.token_env(dict(os.environ), outer)) as master:
            assert master.token == outer
            node = master.start(["sleep", "600"], "sleeper")
        assert not alive(node.proc.pid)
        assert sibling.poll() is None, "the master swept a process of the run it was started in"
    finally:
        sibling.kill()
        sibling.wait()


def test_export_points_this_process_at_the_master(monkeypatch):
    monkeypatch.setenv("ROS_IP", "10.0.0.1")
    for name in ("ROS_MASTER_URI", "ROS_HOSTNAME", "ROS_HOME", "ROS_LOG_DIR", isolation.TOKEN_VAR):
        monkeypatch.delenv(name, raising=False)
    master = PrivateMaster()
    try:
        master.export()
        assert os.environ["ROS_MASTER_URI"] == master.uri and os.environ["ROS_HOSTNAME"] == "localhost"
        assert os.environ["ROS_HOME"] == str(master.home) and "ROS_IP" not in os.environ
    finally:
        master.stop()


def test_a_master_that_cannot_start_says_so_and_leaves_nothing(monkeypatch):
    master = PrivateMaster(timeout=10)
    monkeypatch.setattr(master, "command", lambda: ["sh", "-c", "echo port taken; exit 1"])
    with pytest.raises(RuntimeError, match="port taken"):
        with master:
            pass
    assert master.home.is_dir(), "kept for its logs"
    shutil.rmtree(master.home)


def test_system_state_of_nobody_is_none():
    assert system_state("http://localhost:%d" % isolation.free_port()) is None
    assert not rosout_registered(None)
