"""`catkin_make install && source install/setup.bash` gives a working course, as the devel space does.

The workspace is built and installed into a temporary folder (its own build, devel and install
spaces; the sources are this checkout's). A shell that starts from this machine's PATH, where the
first `python3` cannot import rospy, sources only install/setup.bash. Then:
- `python3` sees rospy, PyQt5 and the venv's mujoco, and our modules come from the install space;
- roscd, rosls and roswtf's ROS_ROOT work, as in the devel space;
- `rosrun turtlesim turtlesim_node` publishes the turtle's pose;
- `roslaunch rrbot_gazebo rrbot_world.launch` runs the MuJoCo simulator from the install space:
  the world file and the RRBot come from share/, and a coke can spawns from the model database.
The master is course_testkit's private one, started from the install space's environment: it
stops every process of the test at the end, whatever happens.
"""
from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import Dict, List

import pytest

from course_checks.isolation import pids_with_token, sourced_env
from course_testkit.master import PrivateMaster
from course_checks.waiting import wait_for

ROOT = Path(__file__).resolve().parents[1]
BUILD_TIMEOUT_S = 900.0
START_TIMEOUT_S = 90.0  # a loaded 2-core machine; a quiet one needs a few seconds


def plain_env(**extra: str) -> Dict[str, str]:
    """What a new terminal has: this machine's PATH without any ROS workspace in it, and no
    ROS variables (a workspace built from a sourced shell would chain to that one)."""
    dirs = os.environ.get("PATH", "").split(os.pathsep)
    path = os.pathsep.join(d for d in dirs if "catkin_ws" not in d and ".venv" not in d
                           and "course_env" not in d)
    return dict({"HOME": os.environ.get("HOME", "/root"), "PATH": path, "LANG": "C.UTF-8"}, **extra)


@pytest.fixture(scope="module")
def install_space(tmp_path_factory) -> Path:
    ws = tmp_path_factory.mktemp("install_ws")
    (ws / "src").symlink_to(ROOT / "src")
    result = subprocess.run(["catkin_make", "-DPYTHON_EXECUTABLE=/usr/bin/python3", "install"], cwd=str(ws),
                            env=plain_env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            universal_newlines=True, timeout=BUILD_TIMEOUT_S)
    assert result.returncode == 0, result.stdout[-4000:]
    return ws / "install"


@pytest.fixture(scope="module")
def install_env(install_space, tmp_path_factory) -> Dict[str, str]:
    """The environment of a new shell after `source install/setup.bash`."""
    home = tmp_path_factory.mktemp("ros_home")
    start = plain_env(ROS_HOME=str(home))
    env = sourced_env(install_space / "setup.bash", start)
    env.update(QT_QPA_PLATFORM="offscreen", PYTHONUNBUFFERED="1")
    return env


def run(env: Dict[str, str], *command: str, timeout: float = 60.0) -> subprocess.CompletedProcess:
    return subprocess.run(list(command), env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=timeout)


def test_python_sees_rospy_qt_mujoco_and_the_installed_modules(install_space, install_env):
    probe = ("import rospy, PyQt5, mujoco, turtlesim.turtle, mujoco_gazebo.engine.database as d;"
             "print(turtlesim.turtle.__file__); print(d.shipped_models())")
    result = run(install_env, "python3", "-c", probe)
    assert result.returncode == 0, result.stdout
    module_file, models = result.stdout.split()
    assert module_file.startswith(str(install_space)), module_file
    assert (Path(models) / "coke_can").is_dir() and models.startswith(str(install_space)), models


def test_shell_tools_work(install_space, install_env):
    result = run(install_env, "bash", "-c", 'source "$1/setup.bash" && roscd turtlesim && pwd && rosls turtlesim',
                 "bash", str(install_space))
    assert result.returncode == 0, result.stdout
    assert str(install_space / "share" / "turtlesim") in result.stdout and "launch" in result.stdout
    assert Path(install_env["ROS_ROOT"]).is_dir(), install_env.get("ROS_ROOT")


def command_line(pid: int) -> str:
    try:
        with open("/proc/%d/cmdline" % pid, "rb") as f:
            return f.read().replace(b"\0", b" ").decode(errors="replace")
    except OSError:
        return ""


def answers(env: Dict[str, str], command: List[str], expected: str) -> bool:
    try:
        return expected in run(env, *command, timeout=30).stdout
    except subprocess.TimeoutExpired:
        return False


def test_nodes_and_the_simulator_run_from_the_install_space(install_space, install_env):
    with PrivateMaster(env=install_env, timeout=START_TIMEOUT_S) as master:
        env = master.env
        turtlesim = master.start(["rosrun", "turtlesim", "turtlesim_node"], "turtlesim")
        pose = run(env, "rostopic", "echo", "-n1", "/turtle1/pose", timeout=START_TIMEOUT_S)
        assert "x: 5.544" in pose.stdout, pose.stdout + turtlesim.output()

        world = master.start(["roslaunch", "rrbot_gazebo", "rrbot_world.launch", "gui:=false"], "rrbot")
        get_rrbot = ["rosservice", "call", "/gazebo/get_model_state", "rrbot", ""]
        wait_for(lambda: answers(env, get_rrbot, "success: True") or not world.running(),
                 timeout=START_TIMEOUT_S, interval=0.5)
        assert world.running(), "rrbot_world.launch ended:\n" + world.output()[-3000:]
        servers = [command_line(pid) for pid in pids_with_token(master.token)
                   if "mujoco_gazebo/gzserver" in command_line(pid)]
        assert servers and all(str(install_space / "lib" / "mujoco_gazebo" / "gzserver") in c
                               for c in servers), servers

        spawn = run(env, "rosrun", "gazebo_ros", "spawn_model", "-database", "coke_can", "-sdf",
                    "-model", "coke_can", "-x", "1", timeout=START_TIMEOUT_S)
        assert spawn.returncode == 0, spawn.stdout
        assert answers(env, ["rosservice", "call", "/gazebo/get_model_state", "coke_can", ""], "success: True")
