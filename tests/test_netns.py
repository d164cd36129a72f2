"""ROS 1 across two machines, emulated with two network namespaces joined by a veth pair.

Namespace M (10.200.0.1/30) runs roscore and turtlesim; namespace P (10.200.0.2/30) runs a
`rostopic pub` on /turtle1/cmd_vel against M's master. With the right ROS_IP the turtle moves;
with a ROS_IP that is not P's address the turtle stays still and `ros_net_check` says why.
Both namespaces are private to this test (unique names), and are deleted in all cases.
Needs root and `ip netns`; skipped with the reason otherwise.
"""
from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import uuid
from pathlib import Path
from typing import Dict, Iterator, List

import pytest

HERE = Path(__file__).resolve().parent
PROBE = [sys.executable, str(HERE / "netns_probe.py")]
MASTER_IP, PUB_IP, PREFIX = "10.200.0.1", "10.200.0.2", 30
WRONG_IP = "10.200.0.9"  # in no namespace at all
MASTER_URI = "http://%s:11311" % MASTER_IP  # port 11311 is free: the namespace is new
DRIVE = "{linear: {x: 1.0}, angular: {z: 0.5}}"


def run(cmd: List[str], **kw) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)


def skip_reason() -> str:
    if os.geteuid() != 0:
        return "needs root to create network namespaces"
    if shutil.which("ip") is None:
        return "the `ip` command (iproute2) is not installed"
    if shutil.which("roscore") is None or run(["rospack", "find", "course_graph"]).returncode != 0:
        return "the workspace is not sourced (source catkin_ws/devel/setup.bash)"
    return ""


class Namespaces:
    """Two namespaces joined by a veth pair, and the processes started in them."""

    def __init__(self, tmp: Path) -> None:
        tag = uuid.uuid4().hex[:6]
        self.master, self.pub = "rosm_" + tag, "rosp_" + tag
        self.veth_master, self.veth_pub = "vrm" + tag, "vrp" + tag
        self.tmp = tmp
        self.processes: List[subprocess.Popen] = []
        self.created: List[str] = []

    def create(self) -> None:
        for ns in (self.master, self.pub):
            out = run(["ip", "netns", "add", ns])
            if out.returncode != 0:
                pytest.skip("ip netns add is not permitted here: %s" % out.stdout.strip())
            self.created.append(ns)
        # `ip netns exec` remounts /sys for the namespace, which a chroot or an unprivileged
        # container does not allow: then the test cannot run here, and says why.
        probe = run(["ip", "netns", "exec", self.master, "true"])
        if probe.returncode != 0:
            pytest.skip("ip netns exec is not permitted here (a chroot or an unprivileged "
                        "container?): %s" % probe.stdout.strip())
        steps = [["ip", "link", "add", self.veth_master, "type", "veth", "peer", "name", self.veth_pub],
                 ["ip", "link", "set", self.veth_master, "netns", self.master],
                 ["ip", "link", "set", self.veth_pub, "netns", self.pub]]
        for ns, dev, ip in ((self.master, self.veth_master, MASTER_IP), (self.pub, self.veth_pub, PUB_IP)):
            steps += [["ip", "-n", ns, "link", "set", "lo", "up"],
                      ["ip", "-n", ns, "addr", "add", "%s/%d" % (ip, PREFIX), "dev", dev],
                      ["ip", "-n", ns, "link", "set", dev, "up"]]
        for step in steps:
            out = run(step)
            assert out.returncode == 0, "%s: %s" % (" ".join(step), out.stdout)

    def env(self, ros_ip: str) -> Dict[str, str]:
        env = dict(os.environ, ROS_MASTER_URI=MASTER_URI, ROS_IP=ros_ip, QT_QPA_PLATFORM="offscreen",
                   ROS_HOME=str(self.tmp / "ros_home"), ROS_LOG_DIR=str(self.tmp / "log"))
        env.pop("ROS_HOSTNAME", None)  # it would win over ROS_IP
        env.pop("DISPLAY", None)
        return env

    def start(self, ns: str, ros_ip: str, cmd: List[str], log: str) -> subprocess.Popen:
        with open(self.tmp / log, "w") as out:
            proc = subprocess.Popen(["ip", "netns", "exec", ns, *cmd], env=self.env(ros_ip), stdout=out,
                                    stderr=subprocess.STDOUT, start_new_session=True)
        self.processes.append(proc)
        return proc

    def call(self, ns: str, ros_ip: str, cmd: List[str], timeout_s: float = 60.0) -> subprocess.CompletedProcess:
        return run(["ip", "netns", "exec", ns, *cmd], env=self.env(ros_ip), timeout=timeout_s)

    @staticmethod
    def stop(proc: subprocess.Popen) -> None:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGINT)
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()

    def destroy(self) -> None:
        for proc in reversed(self.processes):
            self.stop(proc)
        for ns in self.created:  # deleting a namespace deletes its end of the veth pair too
            for pid in run(["ip", "netns", "pids", ns]).stdout.split():
                try:
                    os.kill(int(pid), signal.SIGKILL)
                except (ProcessLookupError, ValueError):
                    pass
            run(["ip", "netns", "del", ns])


@pytest.fixture
def machines(tmp_path: Path) -> Iterator[Namespaces]:
    reason = skip_reason()
    if reason:
        pytest.skip(reason)
    spaces = Namespaces(tmp_path)
    try:
        spaces.create()
        spaces.start(spaces.master, MASTER_IP, ["roscore", "-p", "11311"], "roscore.log")
        up = spaces.call(spaces.master, MASTER_IP, PROBE + ["master", "30"])
        assert up.returncode == 0, "roscore did not come up in %s: %s\n%s" % (
            spaces.master, up.stdout, (tmp_path / "roscore.log").read_text()[-2000:])
        spaces.start(spaces.master, MASTER_IP, ["rosrun", "turtlesim", "turtlesim_node"], "turtlesim.log")
        yield spaces
    finally:
        spaces.destroy()
        listed = run(["ip", "netns", "list"]).stdout
        assert spaces.master not in listed and spaces.pub not in listed, "namespaces left behind: " + listed


def test_publisher_on_another_host_drives_the_turtle(machines: Namespaces) -> None:
    machines.start(machines.pub, PUB_IP, ["rostopic", "pub", "-r", "10", "/turtle1/cmd_vel",
                                          "geometry_msgs/Twist", DRIVE, "__name:=remote_teleop"], "pub.log")
    moved = machines.call(machines.master, MASTER_IP, PROBE + ["moves", "30", "0.5"])
    assert moved.returncode == 0, "the turtle did not move: %s\npublisher log: %s" % (
        moved.stdout, (machines.tmp / "pub.log").read_text()[-2000:])
    # Both sides' settings are right, and every node is reachable from either host.
    for ns, ip in ((machines.pub, PUB_IP), (machines.master, MASTER_IP)):
        check = machines.call(ns, ip, ["rosrun", "course_netcheck", "ros_net_check"])
        assert check.returncode == 0, check.stdout
        assert "all" in check.stdout and "reachable at their registered URIs" in check.stdout


def test_wrong_ros_ip_is_diagnosed(machines: Namespaces) -> None:
    machines.start(machines.pub, WRONG_IP, ["rostopic", "pub", "-r", "10", "/turtle1/cmd_vel",
                                            "geometry_msgs/Twist", DRIVE, "__name:=remote_teleop"], "pub.log")
    registered = machines.call(machines.master, MASTER_IP, PROBE + ["registered", "/remote_teleop", "30"])
    assert registered.returncode == 0, registered.stdout
    # The publisher registered, but advertised an address nobody has: turtlesim cannot connect.
    still = machines.call(machines.master, MASTER_IP, PROBE + ["moves", "5", "0.2"])
    assert still.returncode == 1, "the turtle moved although ROS_IP was wrong: " + still.stdout

    on_publisher = machines.call(machines.pub, WRONG_IP, ["rosrun", "course_netcheck", "ros_net_check"])
    assert on_publisher.returncode == 1
    assert "ROS_IP=%s is not an address of this host" % WRONG_IP in on_publisher.stdout
    assert PUB_IP in on_publisher.stdout  # names the address that would work

    on_master = machines.call(machines.master, MASTER_IP, ["rosrun", "course_netcheck", "ros_net_check"])
    print("ros_net_check on the publisher's host:\n%s\non the master's host:\n%s" % (on_publisher.stdout,
                                                                                  on_master.stdout))
    assert on_master.returncode == 1
    assert "node /remote_teleop registered the URI http://%s:" % WRONG_IP in on_master.stdout
    assert "check ROS_IP / ROS_HOSTNAME there" in on_master.stdout
