"""The one way to run a rostest, with one pass rule, for `make test`, the grader and benchmarks.

rostest (without --text) starts its own master on a free port, writes JUnit XML under
$ROS_HOME/test_results/<pkg>/ and exits non-zero when a test fails. A run passes when rostest
exits 0 AND its JUnit XML exists, counts at least one test, and holds no failure or error.
Each run has its own ROS_HOME and ROS_LOG_DIR under `results_dir`, loopback-only ROS
networking, unbuffered Python, a file-size cap and an environment token: after the run (or at
its time limit) every process carrying the token is killed, so nothing is left running.
"""
from __future__ import annotations

import glob
import importlib.util
import os
import shutil
import subprocess
import tempfile
import threading
import time
from typing import IO, List, NamedTuple, Optional, Sequence, Tuple

from course_checks import isolation, junit
from course_checks.core_params import etc_dir_for_run

DEFAULT_TIMEOUT_S = 300.0
ROSTEST_MAIN = "course_rospy.rostest_main"  # rostest with course_rospy.quick_exit
# What we keep of rostest's combined output: its start and its end.
OUTPUT_HEAD_CHARS = 20_000
OUTPUT_TAIL_CHARS = 60_000
# Lines of rostest's output quoted when it failed without any test result.
SUMMARY_OUTPUT_LINES = 5


class RostestResult(NamedTuple):
    passed: bool
    tests: int
    failures: List[Tuple[str, str]]  # (test name, the check's message)
    junit_path: Optional[str]  # the check node's rosunit XML if any, else rostest's own
    output: str  # combined stdout/stderr, capped
    elapsed: float
    timed_out: bool
    returncode: Optional[int]
    results_dir: str

    def summary(self) -> str:
        """The reasons in words: one line per failed check (its message alone: the name of a check's
        test method, `test_steps`, means nothing to a student; the name when there is no message),
        or why there is no verdict."""
        if self.timed_out:
            lines = ["the milestone did not finish within its time limit of %.0f s" % self.elapsed]
        else:
            lines = []
        lines += [message or name for name, message in self.failures]
        if not lines and not self.passed:
            said = [line for line in self.output.splitlines() if line.strip()][-SUMMARY_OUTPUT_LINES:]
            lines.append("rostest %s (exit code %s)%s" % (
                "reported no test result" if self.tests == 0 else "failed", self.returncode,
                ", it said:\n" + "\n".join(said) if said else ""))
        return "\n".join(lines)


class CappedText:
    """Collects a stream's text, keeping only its first `head` and last `tail` characters."""

    def __init__(self, head: int = OUTPUT_HEAD_CHARS, tail: int = OUTPUT_TAIL_CHARS) -> None:
        self._head_max, self._tail_max = head, tail
        self._head: List[str] = []
        self._head_len = 0
        self._tail = ""
        self.dropped = 0

    def add(self, text: str) -> None:
        if self._head_len < self._head_max:
            take = text[:self._head_max - self._head_len]
            self._head.append(take)
            self._head_len += len(take)
            text = text[len(take):]
        if text:
            joined = self._tail + text
            self.dropped += max(0, len(joined) - self._tail_max)
            self._tail = joined[-self._tail_max:]

    def text(self) -> str:
        middle = "\n[... %d characters left out ...]\n" % self.dropped if self.dropped else ""
        return "".join(self._head) + middle + self._tail


def _pump(stream: IO[bytes], sink: CappedText) -> None:
    for chunk in iter(lambda: stream.read1(65536), b""):
        sink.add(chunk.decode("utf-8", errors="replace"))


def run_etc_dir(results_dir: str) -> str:
    """The run's own etc/ros (core_params.etc_dir_for_run): roslaunch reads it in every process
    of the run, the student's sandboxed ones too (the grader shows it to them read-only)."""
    return os.path.join(results_dir, "etc_ros")


def rostest_env(base: Optional[dict], results_dir: str, token: str) -> dict:
    """The environment of one run: own ROS_HOME/ROS_LOG_DIR, loopback, no display, unbuffered,
    and two start-up costs cut: roscore.xml's rosversion commands answered from a file
    (core_params), and Python's own distutils instead of the copy setuptools' import hook
    loads (roslaunch, rostest and rosclean import distutils: 0.30 s -> 0.17 s per roslaunch)."""
    env = dict(os.environ if base is None else base)
    env.pop("DISPLAY", None)
    env.pop("ROS_MASTER_URI", None)
    env.pop("ROS_IP", None)
    env.update(ROS_HOME=os.path.join(results_dir, "ros_home"), ROS_LOG_DIR=os.path.join(results_dir, "log"),
               ROS_HOSTNAME="localhost", QT_QPA_PLATFORM="offscreen", PYTHONUNBUFFERED="1")
    env.setdefault("SETUPTOOLS_USE_DISTUTILS", "stdlib")
    etc = etc_dir_for_run(env, run_etc_dir(results_dir))
    if etc is not None:
        env["ROS_ETC_DIR"] = etc
    return isolation.token_env(env, token)


def read_results(results_dir: str) -> Tuple[int, List[Tuple[str, str]], Optional[str]]:
    """Test count, failures and the most telling JUnit file of the run in `results_dir`."""
    base = os.path.join(results_dir, "ros_home", "test_results")
    launchers = sorted(glob.glob(os.path.join(base, "*", "rostest-*.xml")))
    check_files = sorted(glob.glob(os.path.join(base, "*", "rosunit-*.xml")))
    launcher = None
    for path in launchers:
        suite = junit.parse_file(path)
        if suite is not None:
            launcher = suite if launcher is None else junit.Suite(launcher.tests + suite.tests,
                                                                  launcher.cases + suite.cases)
    checks = [s for s in (junit.parse_file(p) for p in check_files) if s is not None]
    tests, failures = junit.combine(launcher, checks)
    path = (check_files or launchers or [None])[0]
    return tests, failures, path


def rostest_command() -> List[str]:
    """How to start rostest: its script under its own interpreter (its #! line) through
    course_rospy.rostest_main, which stops its servers' loops before they can spin at the end.
    Plain `rostest` when the script is not found or names no interpreter, or without course_rospy
    (which needs nothing of this package: a declared dependency would make a cycle with its tests)."""
    script = shutil.which("rostest")
    try:
        with open(script or "", "rb") as f:
            first = f.readline(256).decode("ascii")
    except (OSError, UnicodeDecodeError):
        return ["rostest"]
    interpreter = first[2:].split() if first.startswith("#!") else []
    if len(interpreter) != 1 or not os.path.isabs(interpreter[0]) or importlib.util.find_spec(ROSTEST_MAIN) is None:
        return ["rostest"]
    return [interpreter[0], "-P", "-m", ROSTEST_MAIN, script]  # -P: not the working folder on sys.path


def run_rostest(pkg: str, test_file: str, args: Sequence[str] = (), env: Optional[dict] = None,
                results_dir: Optional[str] = None, timeout: float = DEFAULT_TIMEOUT_S,
                own_network: bool = True) -> RostestResult:
    """Run `rostest pkg test_file args...` isolated (see the module docstring) and judge it; with
    `pkg` empty, `test_file` is the rostest file's path."""
    results_dir = results_dir or tempfile.mkdtemp(prefix="rostest-")
    os.makedirs(results_dir, exist_ok=True)
    token = isolation.new_token()
    command = isolation.isolated_command(rostest_command() + ([pkg] if pkg else []) + [test_file] + list(args),
                                         own_network)
    output = CappedText()
    started = time.monotonic()
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                            env=rostest_env(env, results_dir, token), cwd=results_dir, start_new_session=True)
    isolation.limit_file_size(proc.pid)
    reader = threading.Thread(target=_pump, args=(proc.stdout, output), daemon=True)
    reader.start()
    timed_out = False
    try:
        proc.wait(timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
    finally:
        isolation.kill_run(token, proc.pid)
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        reader.join(10)
        proc.stdout.close()
    elapsed = time.monotonic() - started
    tests, failures, junit_path = read_results(results_dir)
    passed = (not timed_out and proc.returncode == 0 and junit_path is not None and tests >= 1
              and not failures)
    return RostestResult(passed, tests, failures, junit_path, output.text(), elapsed, timed_out,
                         None if timed_out else proc.returncode, results_dir)
