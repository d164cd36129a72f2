"""Run every package's rostest files (src/*/test/*.test), each with its own roscore.

rostest starts a master on a free port, so these never touch a roscore the user
may have running on 11311. A failing rostest shows its output in the pytest report.
"""
from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TEST_FILES = sorted(ROOT.glob("src/*/test/*.test"))
TIMEOUT_S = 240


@pytest.mark.parametrize("test_file", TEST_FILES, ids=lambda p: "%s/%s" % (p.parts[-3], p.name))
def test_rostest(test_file: Path, tmp_path: Path) -> None:
    env = dict(os.environ, ROS_HOME=str(tmp_path / "ros_home"), ROS_LOG_DIR=str(tmp_path / "log"),
               ROS_HOSTNAME="localhost", QT_QPA_PLATFORM="offscreen")
    env.pop("DISPLAY", None)
    proc = subprocess.run(["rostest", test_file.parts[-3], test_file.name],
                          cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=TIMEOUT_S)
    tail = "\n".join(proc.stdout.splitlines()[-80:])
    assert proc.returncode == 0 and "RESULT: SUCCESS" in proc.stdout, \
        "rostest %s failed:\n%s" % (test_file.name, tail)
