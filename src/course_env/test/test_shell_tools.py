"""After `source devel/setup.bash`, rosbash's shell functions and roswtf work as on a ROS install.

Debian ships roscd/rosls/roscp only as a bash-completion file and sets no ROS_ROOT, which
roswtf reads; the course_env hooks fix both. Each check runs a fresh `bash -c` that sources the
workspace, the way a student's new terminal does.
"""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

SETUP = Path(__file__).resolve().parents[3] / "catkin_ws" / "devel" / "setup.bash"

pytestmark = pytest.mark.skipif(not SETUP.exists(), reason="workspace not built")


def _bash(script: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(["env", "-u", "ROS_ROOT", "bash", "-c", "source %s && %s" % (SETUP, script)], cwd=cwd,
                          capture_output=True, text=True, timeout=120)


def _package_dir(name: str) -> Path:
    return Path(_bash("rospack find %s" % name).stdout.strip())


def test_roscd_goes_to_the_package():
    done = _bash("roscd turtlesim && pwd")
    assert done.returncode == 0, done.stderr
    assert Path(done.stdout.strip()) == _package_dir("turtlesim")


def test_rosls_lists_the_package():
    done = _bash("rosls turtlesim")
    assert done.returncode == 0, done.stderr
    assert "package.xml" in done.stdout.split()


def test_roscp_copies_a_package_file(tmp_path):
    done = _bash("roscp turtlesim package.xml %s" % (tmp_path / "copy.xml"))
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "copy.xml").read_text() == (_package_dir("turtlesim") / "package.xml").read_text()


def test_roswtf_inside_a_package_folder():
    done = _bash("ROS_MASTER_URI=http://127.0.0.1:9 roswtf", cwd=_package_dir("turtlesim"))
    assert "Traceback" not in done.stdout + done.stderr, done.stdout + done.stderr
    assert "Static checks summary" in done.stdout
