"""The command-line steps of the course texts, verbatim, against a live turtlesim.

Each row is a command a text tells students to type (001 2.1-2.2, 002 2-3, 003 Part I,
000) and a piece of what it must print. A private roscore (course_testkit.master) on a free
loopback port.
"""
from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

COMMANDS = [
    # 001 UPMC part 1, 2.1.1-2.1.5 and 2.2.3-2.2.6
    ("rosnode list", "/turtlesim"),
    ("rosnode info /turtlesim", "/turtle1/cmd_vel"),
    ("rostopic list", "/turtle1/pose"),
    ("rostopic info /turtle1/cmd_vel", "Type: geometry_msgs/Twist"),
    ("rosmsg info geometry_msgs/Twist", "geometry_msgs/Vector3 linear"),
    ("rosmsg show geometry_msgs/Twist", "float64 x"),
    ("rostopic info /turtle1/pose", "Type: turtlesim/Pose"),
    ("rosmsg info turtlesim/Pose", "float32 linear_velocity"),
    ("rosservice info /turtle1/set_pen", "Type: turtlesim/SetPen"),
    ("rossrv info turtlesim/SetPen", "uint8 width"),
    ("rosparam list", "/turtlesim/background_b"),
    # 002 Lab 2, sections 2-3
    ("rospack find chatter", "/src/chatter"),
    ("rosmsg show TimestampString", "float64"),
    # 003 Part I, tasks 2 and 4, and the ROS Parameters section
    ("rostopic pub -1 /turtle1/cmd_vel geometry_msgs/Twist '{linear: {x: 1.0}}'", ""),
    ("rosservice call /clear", ""),
    ("rosservice call /turtle1/set_pen 255 0 0 3 0", ""),
    ("rosservice call /turtle1/teleport_absolute 5.544445 5.544445 0", ""),
    ("rosservice call /reset", ""),
    ("rosparam set /turtlesim/background_r 150", ""),
    ("rosparam get /turtlesim/background_r", "150"),
    # 000, in ROS 1 form
    ("rostopic echo -n 1 /turtle1/pose", "linear_velocity"),
    ("rosnode ping -c 1 /turtlesim", "reply from"),
    # 003 Part I, task 1 (last: it ends the simulator)
    ("rosnode kill /turtlesim", "killed"),
]


@pytest.fixture(scope="module")
def ros_env(tmp_path_factory):
    """A roscore and a turtlesim_node of our own; both stopped (with their children) afterwards."""
    from course_testkit.master import PrivateMaster
    from course_checks.waiting import wait_for

    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    with PrivateMaster(rosout=True, home=tmp_path_factory.mktemp("ros_home"), env=env) as master:
        def services() -> str:
            proc = subprocess.run(["rosservice", "list"], env=master.env, capture_output=True, text=True)
            return proc.stdout if proc.returncode == 0 else ""

        master.start(["rosrun", "turtlesim", "turtlesim_node"], "turtlesim")
        assert wait_for(lambda: "/spawn" in services(), 30), "turtlesim did not start"
        yield master.env


@pytest.mark.parametrize("command, expected", COMMANDS, ids=[c for c, _ in COMMANDS])
def test_text_command(ros_env, command: str, expected: str) -> None:
    proc = subprocess.run(command, shell=True, env=ros_env, cwd=ROOT, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=60)
    assert proc.returncode == 0, "%s failed:\n%s" % (command, proc.stdout)
    assert expected in proc.stdout, "%s printed:\n%s" % (command, proc.stdout)
