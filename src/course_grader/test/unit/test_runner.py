"""The grader's scheduling and outputs, with rostest and catkin_make replaced by fakes: every
submission gets one verdict per selected milestone, a results.json and one progress line,
whatever goes wrong with another submission."""
import json
import os
import sys
import threading
import time

from course_format.milestone import Milestone
from course_checks.rostest_runner import RostestResult

from course_grader import runner, workspace
from course_grader.submissions import Submission
from course_grader.workspace import BuildResult

CHATTER = Milestone("chatter", "Example pub/sub", "002 section 2", "chatter.test", ("chatter",))
CP1 = Milestone("checkpoint1", "TimestampString", "002 checkpoint 1", "checkpoint1.test", ("my_chatter",))
PACKAGE_XML = '<package format="2"><name>%s</name></package>'


def _fake_rostest(pkg, test_file, env=None, results_dir=None, timeout=None, **_):
    passed = test_file == "chatter.test"
    failures = [] if passed else [("test_cp1", "nothing on /user_messages")]
    return RostestResult(passed, 1, failures, None, "rostest output", 1.5, False, 0 if passed else 1, results_dir)


def _folder(tmp_path, name, packages):
    for pkg in packages:
        (tmp_path / name / "src" / pkg).mkdir(parents=True)
        (tmp_path / name / "src" / pkg / "package.xml").write_text(PACKAGE_XML % pkg)
    (tmp_path / name).mkdir(exist_ok=True)
    return Submission(name, str(tmp_path / name))


def test_each_submission_gets_its_verdicts_and_one_progress_line(tmp_path, monkeypatch):
    monkeypatch.setattr(runner, "run_rostest", _fake_rostest)
    monkeypatch.setenv("COURSE_SANDBOX_LEVEL", "none")  # fakes run nothing; tmp_path is in a 0700 folder
    monkeypatch.setattr(workspace, "course_packages", lambda: {"turtlesim", "course_testkit"})
    monkeypatch.setattr(workspace, "course_setup", lambda: "/nowhere/setup.bash")
    monkeypatch.setattr(workspace, "course_site", lambda setup: "")
    monkeypatch.setattr(workspace, "build",
                        lambda ws, setup, plan, home, log: BuildResult(True, "", "", {"PATH": "/usr/bin"}))
    (tmp_path / "broken.zip").write_bytes(b"not a zip")
    subs = [_folder(tmp_path, "alice", ["chatter", "my_chatter", "turtlesim"]),
            _folder(tmp_path, "bob", ["mychatter"]),
            Submission("broken", str(tmp_path / "broken.zip"))]
    lines = []
    out = tmp_path / "out"
    grader = runner.Grader([CHATTER, CP1], runner.Options(str(out), jobs=2), say=lines.append)
    verdicts = grader.grade(subs)
    assert len(lines) == 3 and all("points" in line for line in lines)
    by = {(v.student, v.milestone.name): v for v in verdicts}
    assert by["alice", "chatter"].passed and not by["alice", "checkpoint1"].passed
    assert "nothing on /user_messages" in by["alice", "checkpoint1"].reason
    assert "rename 'mychatter' to 'my_chatter'" in by["bob", "checkpoint1"].reason
    assert "cannot be unpacked" in by["broken", "chatter"].reason
    alice = json.loads((out / "alice" / "results.json").read_text())
    assert alice["score"] == 10.0 and [t["status"] for t in alice["tests"]] == ["passed", "failed"]
    assert "left out (the course provides them): turtlesim" in alice["output"]
    assert (out / "bob" / "checkpoint1" / "junit.xml").is_file()
    assert json.loads((out / "_work" / "durations.json").read_text())["chatter"] == 1.5
    assert "isolation: " in alice["output"]


def test_a_ros2_package_fails_before_anything_is_built(tmp_path, monkeypatch):
    monkeypatch.setattr(runner, "run_rostest", _fake_rostest)
    monkeypatch.setenv("COURSE_SANDBOX_LEVEL", "none")  # fakes run nothing; tmp_path is in a 0700 folder
    monkeypatch.setattr(workspace, "course_packages", lambda: set())
    monkeypatch.setattr(workspace, "course_setup", lambda: "/nowhere/setup.bash")
    built = []
    monkeypatch.setattr(workspace, "build", lambda *args: built.append(args))
    sub = _folder(tmp_path, "carol", ["chatter", "my_chatter"])
    (tmp_path / "carol" / "src" / "my_chatter" / "package.xml").write_text(
        '<package format="3"><name>my_chatter</name><version>1.0.0</version><description>d</description>'
        '<maintainer email="c@example.edu">c</maintainer><license>MIT</license>\n'
        '<export><build_type>ament_python</build_type></export></package>')
    verdicts = runner.Grader([CHATTER, CP1], runner.Options(str(tmp_path / "out"), jobs=1),
                             say=lambda line: None).grade([sub])
    by = {v.milestone.name: v for v in verdicts}
    assert not built and not by["chatter"].passed and not by["checkpoint1"].passed
    assert {v.cause for v in verdicts} == {"ros2_package"}
    assert by["checkpoint1"].reason.startswith("my_chatter is a ROS 2 (ament_python) package (src/my_chatter/"
                                               "package.xml line 2: <build_type>ament_python</build_type>)")
    assert by["chatter"].reason.startswith("the submission does not build: catkin_make cannot build a workspace")


def test_autograder_files_without_git_follow_the_gitignore(tmp_path):
    """The course image has no .git: the zip's files then come from a walk that honours .gitignore."""
    from course_grader.autograder import repo_files
    from course_checks.gitignore import ignored
    patterns = ["/.venv/", "/catkin_ws/build/", "__pycache__/", "*.pyc", "/autograder.zip"]
    assert ignored(".venv/", patterns) and ignored("catkin_ws/build/", patterns)
    assert ignored("src/a/__pycache__/", patterns) and ignored("src/a/x.pyc", patterns)
    assert ignored("autograder.zip", patterns) and not ignored("src/autograder.zip", patterns)
    assert not ignored("src/a/x.py", patterns) and not ignored("catkin_ws/buildx/", patterns)
    (tmp_path / ".gitignore").write_text("# built\n/.venv/\n*.pyc\n")
    for rel in ("src/pkg/a.py", "src/pkg/a.pyc", ".venv/bin/python3", "setup.sh", "courses/robotics_labs/samples/x/y.py"):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text("x")
    assert repo_files(str(tmp_path)) == [".gitignore", "setup.sh", "src/pkg/a.py"]


def test_every_milestone_of_the_builtin_course_has_a_typical_duration():
    from course_format import course_file
    course = course_file.load(course_file.builtin_course_dir())
    assert sorted(course_file.typical_durations(course)) == sorted(m.name for m in course.milestones)


def test_a_first_grading_into_a_fresh_out_starts_the_longest_runs_first(tmp_path, monkeypatch):
    """Without a _work/durations.json the order comes from the course's typical durations."""
    typical = {"chatter": 3.0, "checkpoint1": 5.6}
    started = []

    def recording_rostest(pkg, test_file, **kwargs):
        started.append(test_file)
        return _fake_rostest(pkg, test_file, **kwargs)
    built = []
    monkeypatch.setattr(runner, "run_rostest", recording_rostest)
    monkeypatch.setenv("COURSE_SANDBOX_LEVEL", "none")
    monkeypatch.setattr(workspace, "course_setup", lambda: "/nowhere/setup.bash")
    monkeypatch.setattr(workspace, "course_packages", lambda: {"turtlesim"})
    monkeypatch.setattr(workspace, "course_site", lambda setup: "")
    monkeypatch.setattr(workspace, "build", lambda ws, *args: built.append(sorted(os.listdir(os.path.join(ws, "src"))))
                        or BuildResult(True, "", "", {"PATH": "/usr/bin"}))
    grader = runner.Grader([CHATTER, CP1], runner.Options(str(tmp_path / "out"), jobs=1, typical=typical),
                           say=lambda line: None)
    reference = _folder(tmp_path, "solutions", ["chatter", "my_chatter"])
    grader.grade([Submission(runner.REFERENCE, reference.path)], reference=True)
    assert started == ["checkpoint1.test", "chatter.test"]
    assert built == [["chatter", "my_chatter"]]  # the reference is an overlay, built as a student's is


def test_default_jobs_are_three_per_core_within_the_memory(tmp_path):
    from course_grader.cli import available_mib, default_jobs
    assert default_jobs(2, 24 * 1024) == 6
    assert default_jobs(1, 768) == 1 and default_jobs(4, 1200) == 3 and default_jobs(2, 0) == 1
    (tmp_path / "meminfo").write_text("MemTotal: 8000000 kB\nMemAvailable:    4096000 kB\n")
    (tmp_path / "cg").mkdir()
    assert available_mib(str(tmp_path / "meminfo"), str(tmp_path / "cg")) == 4000
    (tmp_path / "cg" / "memory.max").write_text("1073741824\n")
    (tmp_path / "cg" / "memory.current").write_text("%d\n" % (200 * 2 ** 20))
    assert available_mib(str(tmp_path / "meminfo"), str(tmp_path / "cg")) == 824


def test_a_submission_s_runs_go_on_while_the_next_one_builds(tmp_path, monkeypatch):
    """Builds have a lane of their own: bob's build waits until one of alice's runs has started,
    which only works if her runs are not queued behind bob's build (one run at once, one build)."""
    import threading
    alice_ran = threading.Event()
    builds_at_once, most = [], [0]

    def rostest(pkg, test_file, env=None, results_dir=None, **kwargs):
        if "/alice/" in (results_dir or ""):
            alice_ran.set()
        return _fake_rostest(pkg, test_file, env=env, results_dir=results_dir, **kwargs)

    def build(ws, setup, plan, home, log):
        builds_at_once.append(ws)
        most[0] = max(most[0], len(builds_at_once))
        try:
            if "/bob/" in ws:
                assert alice_ran.wait(20), "alice's runs waited for bob's build"
            return BuildResult(True, "", "", {"PATH": "/usr/bin"})
        finally:
            builds_at_once.remove(ws)
    monkeypatch.setattr(runner, "run_rostest", rostest)
    monkeypatch.setenv("COURSE_SANDBOX_LEVEL", "none")
    monkeypatch.setattr(workspace, "course_packages", lambda: {"turtlesim"})
    monkeypatch.setattr(workspace, "course_setup", lambda: "/nowhere/setup.bash")
    monkeypatch.setattr(workspace, "course_site", lambda setup: "")
    monkeypatch.setattr(workspace, "build", build)
    subs = [_folder(tmp_path, name, ["chatter"]) for name in ("alice", "bob", "carol")]
    grader = runner.Grader([CHATTER], runner.Options(str(tmp_path / "out"), jobs=1, builds=1), say=lambda line: None)
    verdicts = grader.grade(subs)
    assert sorted((v.student, v.passed) for v in verdicts) == [("alice", True), ("bob", True), ("carol", True)]
    assert most[0] == 1, "one build at once"


def test_each_kind_of_milestone_is_run_by_its_rostest(tmp_path, monkeypatch):
    """A data milestone by the file written into its run folder (its world, then run_steps), and
    a course's own Python check (the built-in course's as any other) by its path, both as
    course_milestones' files (rostest finds no package for a file outside one)."""
    monkeypatch.setattr(workspace, "package_dir", lambda name: "/pkgs/" + name)
    data = Milestone("talk", "t", "x", "", ("beginner_tutorials",), world=("turtlesim",), course_file="/c/course.yaml")
    package, path, args = runner.rostest_of(data, str(tmp_path))
    assert (package, path) == ("", str(tmp_path / "talk.test"))
    assert args == ["--package=course_milestones", "--pkgdir=/pkgs/course_milestones", "--results-filename=talk.xml"]
    written = (tmp_path / "talk.test").read_text()
    assert 'type="turtlesim_node"' in written and 'type="run_steps"' in written and "/c/course.yaml" in written
    own = Milestone("mine", "t", "x", "/c/checks/mine.test", ("p",))
    assert runner.rostest_of(own, str(tmp_path)) == ("", "/c/checks/mine.test", [
        "--package=course_milestones", "--pkgdir=/pkgs/course_milestones", "--results-filename=mine.xml"])


class _SlowStdout:
    """A stdout whose write() lets other threads run whenever a piece does not end a line, as a
    pipe's writer may be interrupted between a line and its newline."""

    def __init__(self):
        self.pieces = []

    def write(self, text):
        self.pieces.append(text)
        if not text.endswith("\n"):
            time.sleep(0.001)
        return len(text)

    def flush(self):
        pass


def test_lines_said_from_many_threads_come_out_whole(monkeypatch):
    out = _SlowStdout()
    monkeypatch.setattr(sys, "stdout", out)
    per_thread = [["    student    milestone_%d_%d   pass   1.0s" % (t, i) for i in range(20)] for t in range(6)]
    threads = [threading.Thread(target=lambda mine=mine: [runner.say_line(line) for line in mine])
               for mine in per_thread]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert sorted("".join(out.pieces).splitlines()) == sorted(line for mine in per_thread for line in mine)
