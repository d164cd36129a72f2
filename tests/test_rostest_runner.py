"""course_checks.rostest_runner against real rostest runs of a throw-away package: the pass
rule, the check's own failure message, and the time limit that kills a process tree whose
members left their session and ignore SIGINT/SIGTERM."""
from __future__ import annotations

import os
import shutil
import subprocess
import textwrap
from pathlib import Path

import pytest

from course_checks.rostest_runner import rostest_command, run_rostest

PACKAGE = "runner_probe"
CHECK = '''\
#!/usr/bin/env python3
import sys, unittest
import rospy, rostest

class Probe(unittest.TestCase):
    def test_probe(self):
        self.assertTrue("pass" in sys.argv, "the probe was asked to fail")

if __name__ == "__main__":
    rospy.init_node("probe")
    rostest.rosrun("runner_probe", "probe", Probe)
'''
HANG = '''\
#!/usr/bin/env python3
import os, signal, time
for sig in (signal.SIGINT, signal.SIGTERM):
    signal.signal(sig, signal.SIG_IGN)
if os.fork() == 0:
    os.setsid()
    if os.fork() == 0:
        while True:
            time.sleep(1)
    os._exit(0)
while True:
    time.sleep(1)
'''


@pytest.fixture(scope="module")
def probe_env(tmp_path_factory) -> dict:
    root = tmp_path_factory.mktemp("pkgs")
    pkg = root / PACKAGE
    (pkg / "nodes").mkdir(parents=True)
    (pkg / "test").mkdir()
    (pkg / "package.xml").write_text(
        '<?xml version="1.0"?><package format="2"><name>%s</name><version>0.0.0</version>'
        '<description>probe</description><maintainer email="a@b.c">a</maintainer><license>BSD</license>'
        '<buildtool_depend>catkin</buildtool_depend></package>' % PACKAGE)
    for name, text in (("probe", CHECK), ("hang", HANG)):
        (pkg / "nodes" / name).write_text(text)
        os.chmod(pkg / "nodes" / name, 0o755)
    for verdict in ("pass", "fail"):
        (pkg / "test" / ("%s.test" % verdict)).write_text(textwrap.dedent('''\
            <launch><test test-name="probe" pkg="%s" type="probe" args="%s" time-limit="60"/></launch>
            ''' % (PACKAGE, verdict)))
    (pkg / "test" / "hang.test").write_text(
        '<launch><test test-name="hang" pkg="%s" type="hang" time-limit="600"/></launch>\n' % PACKAGE)
    return dict(os.environ, ROS_PACKAGE_PATH="%s:%s" % (root, os.environ.get("ROS_PACKAGE_PATH", "")))


def test_a_passing_check_passes(probe_env: dict, tmp_path: Path) -> None:
    result = run_rostest(PACKAGE, "pass.test", env=probe_env, results_dir=str(tmp_path), timeout=120)
    assert result.passed and result.tests == 1 and not result.failures, result.output[-2000:]
    assert result.junit_path and os.path.basename(result.junit_path) == "rosunit-probe.xml"


def test_a_failing_check_gives_its_message(probe_env: dict, tmp_path: Path) -> None:
    result = run_rostest(PACKAGE, "fail.test", env=probe_env, results_dir=str(tmp_path), timeout=120)
    assert not result.passed and result.returncode != 0
    assert result.failures == [("test_probe", "the probe was asked to fail")]


def test_the_time_limit_kills_the_whole_tree(probe_env: dict, tmp_path: Path) -> None:
    marker = "COURSE_PROBE_RUN=%s" % tmp_path.name
    env = dict(probe_env, COURSE_PROBE_RUN=tmp_path.name)
    result = run_rostest(PACKAGE, "hang.test", env=env, results_dir=str(tmp_path), timeout=8)
    assert result.timed_out and not result.passed and "time limit" in result.summary()
    assert result.elapsed < 30
    left = [pid for pid in os.listdir("/proc") if pid.isdigit() and _environ_has(pid, marker)]
    assert not left, "processes left after the time limit: %s" % left


def _environ_has(pid: str, marker: str) -> bool:
    try:
        return marker.encode() in Path("/proc", pid, "environ").read_bytes().split(b"\0")
    except OSError:
        return False


def test_rostest_runs_under_its_own_interpreter_through_the_quick_exit_wrapper() -> None:
    script = shutil.which("rostest")
    interpreter = Path(script).read_text().splitlines()[0][2:].strip()
    assert rostest_command() == [interpreter, "-P", "-m", "course_rospy.rostest_main", script]


def test_a_rostest_without_an_interpreter_line_is_run_as_it_is(tmp_path: Path, monkeypatch) -> None:
    fake = tmp_path / "rostest"
    fake.write_text("echo not python\n")
    fake.chmod(0o755)
    monkeypatch.setenv("PATH", "%s:%s" % (tmp_path, os.environ["PATH"]))
    assert rostest_command() == ["rostest"]
    fake.write_text("#!/usr/bin/env python3\n")  # two words: not a path we can run with -m
    assert rostest_command() == ["rostest"]


def test_the_wrapper_leaves_rostest_its_arguments_and_exit_code(probe_env: dict, tmp_path: Path) -> None:
    """rostest through the wrapper and rostest alone: the same exit code for a passing and a
    failing check (rostest's own rule), and the check's JUnit where rostest writes it."""
    for verdict in ("pass", "fail"):
        codes = []
        for name, command in (("wrapped", rostest_command()), ("plain", ["rostest"])):
            home = tmp_path / verdict / name
            home.mkdir(parents=True)
            run = subprocess.run(command + [PACKAGE, "%s.test" % verdict], env=dict(probe_env, ROS_HOME=str(home)),
                                 cwd=str(home), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                 timeout=120)
            assert list(home.glob("test_results/%s/rosunit-probe.xml" % PACKAGE)), run.stdout[-2000:]
            codes.append(run.returncode)
        assert codes[0] == codes[1] and (codes[0] == 0) == (verdict == "pass"), (verdict, codes)
