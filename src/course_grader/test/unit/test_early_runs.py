"""Runs started while their submission builds (course_grader.early_runs): whatever the build
does and whenever the run ends, each milestone gets exactly one verdict, from a run whose check
passed its gate only after the overlay was built and its sandbox policy written."""
import os
import threading

from hypothesis import given, settings, strategies as st

from course_format.milestone import Milestone
from course_checks import run_gate
from course_checks.rostest_runner import RostestResult

from course_grader import early_runs, runner, workspace
from course_grader.early_runs import ABANDONED, GO, RESTART, VOID, EarlyRun
from course_grader.submissions import Submission
from course_grader.workspace import BuildResult

ARCH = Milestone("arch", "Writing Our First Node", "003", "arch.test", ("my_pkg",))
CHATTER = Milestone("chatter", "Example pub/sub", "002 section 2", "chatter.test", ("chatter",))
OWN = Milestone("own", "A course's own check", "x", "/course/own.test", ("my_pkg",))
PACKAGE_XML = '<package format="2"><name>%s</name></package>'


# -- the hand-over alone ----------------------------------------------------------------------------

def test_an_opened_run_counts_and_its_gate_says_go(tmp_path):
    run = EarlyRun(str(tmp_path / "gate"))
    written = []
    assert run.open(["hint"], ["first"], lambda: written.append("policy"))
    assert written == ["policy"] and run_gate.read(run.gate) == run_gate.GO
    assert run.ended() == GO and (run.hints, run.first) == (["hint"], ["first"])
    run.void()  # too late: the build thread's clean-up changes nothing
    assert run_gate.read(run.gate) == run_gate.GO and run.ended() == GO


def test_a_run_that_ended_undecided_is_abandoned_and_the_build_starts_the_milestone(tmp_path):
    run = EarlyRun(str(tmp_path / "gate"))
    assert run.ended() == ABANDONED
    assert not run.open([], [], lambda: None) and not run.restart(("args",))
    assert run_gate.read(run.gate) is None  # nobody waits at it any more


def test_a_restarted_run_is_told_to_stop_and_keeps_the_build_s_arguments(tmp_path):
    run = EarlyRun(str(tmp_path / "gate"))
    assert run.restart(("env", [], "/ws", {}, []))
    assert run_gate.read(run.gate) == run_gate.STOP
    assert run.ended() == RESTART and run.restart_args == ("env", [], "/ws", {}, [])


def test_a_policy_that_cannot_be_written_stops_the_check_instead_of_leaving_it_waiting(tmp_path):
    run = EarlyRun(str(tmp_path / "gate"))

    def broken():
        raise OSError("disk full")
    try:
        run.open([], [], broken)
    except OSError:
        pass
    else:
        raise AssertionError("the policy's error was swallowed")
    assert run_gate.read(run.gate) == run_gate.STOP and run.ended() == VOID


def test_staleness_is_the_wait_since_the_start(tmp_path):
    now = [100.0]
    run = EarlyRun(str(tmp_path / "gate"), clock=lambda: now[0])
    now[0] += early_runs.WAIT_LIMIT_S - 1
    assert not run.stale()
    now[0] += 2
    assert run.stale()


ACTIONS = st.lists(st.sampled_from(["open", "void", "restart", "ended"]), min_size=1, max_size=6)


@settings(max_examples=200, deadline=None)
@given(ACTIONS)
def test_whatever_the_order_the_first_decision_sticks_and_the_gate_matches_it(actions):
    """The build thread (open, void, restart) and the run's thread (ended) race: the first of them
    decides; the gate file says go exactly when the run counts, and stop when it was voided or
    restarted; an abandoned run's gate is never written."""
    import tempfile
    with tempfile.TemporaryDirectory() as folder:
        run = EarlyRun(os.path.join(folder, "gate"))
        for action in actions:
            if action == "open":
                run.open([], [], lambda: None)
            elif action == "void":
                run.void()
            elif action == "restart":
                run.restart(("args",))
            else:
                run.ended()
        expected = {"open": GO, "void": VOID, "restart": RESTART, "ended": ABANDONED}[actions[0]]
        assert run.ended() == expected
        word = run_gate.read(run.gate)
        assert word == {GO: run_gate.GO, VOID: run_gate.STOP, RESTART: run_gate.STOP, ABANDONED: None}[expected]


# -- in the grader, with rostest and catkin_make replaced by fakes ----------------------------------

class FakeRuns:
    """rostest as the grader sees it: a check that waits at its gate (if it has one), then reads
    its sandbox policy, as the course's checks do."""

    def __init__(self, end_before_gate=()):
        self.calls = []
        self.end_before_gate = set(end_before_gate)
        self.lock = threading.Lock()

    def __call__(self, pkg, test_file, env=None, results_dir=None, **_):
        name = os.path.basename(test_file)[:-len(".test")]
        gated = run_gate.ENV_VAR in env
        with self.lock:
            self.calls.append((name, gated))
        if gated and name in self.end_before_gate:
            self.end_before_gate.discard(name)  # this run's world died before the build ended
            return RostestResult(False, 0, [], None, "the world died", 0.5, False, 1, results_dir)
        if gated and not run_gate.wait(env, limit=30):
            return RostestResult(True, 1, [], None, "skipped at the gate", 0.5, False, 0, results_dir)
        policy = env["COURSE_SANDBOX_POLICY"]
        ok = os.path.isfile(policy)
        return RostestResult(ok, 1, [] if ok else [("test", "no policy at %s" % policy)], None, "ran",
                             1.5, False, 0 if ok else 1, results_dir)


def _grade(tmp_path, monkeypatch, runs, build_ok=True, early=1, milestones=(ARCH, CHATTER), build_hook=None):
    monkeypatch.setattr(runner, "run_rostest", runs)
    monkeypatch.setenv("COURSE_SANDBOX_LEVEL", "none")  # fakes run nothing; tmp_path is in a 0700 folder
    monkeypatch.setattr(workspace, "course_packages", lambda: {"turtlesim"})
    monkeypatch.setattr(workspace, "course_setup", lambda: "/nowhere/setup.bash")
    monkeypatch.setattr(workspace, "course_site", lambda setup: "")

    def build(ws, setup, plan, home, log):
        if build_hook:
            build_hook()
        if build_ok:
            return BuildResult(True, "", "", {"PATH": "/usr/bin"}, {"PATH": "/usr/bin"})
        return BuildResult(False, "", "my_pkg: CMake Error at CMakeLists.txt:3", None)
    monkeypatch.setattr(workspace, "build", build)
    for pkg in ("my_pkg", "chatter"):
        (tmp_path / "alice" / pkg).mkdir(parents=True)
        (tmp_path / "alice" / pkg / "package.xml").write_text(PACKAGE_XML % pkg)
    grader = runner.Grader(list(milestones), runner.Options(str(tmp_path / "out"), jobs=2, early=early),
                           say=lambda line: None)
    verdicts = grader.grade([Submission("alice", str(tmp_path / "alice"))])
    assert sorted(v.milestone.name for v in verdicts) == sorted(m.name for m in milestones), "one verdict each"
    return {v.milestone.name: v for v in verdicts}


def test_the_longest_run_starts_before_the_build_and_its_check_goes_on_after_it(tmp_path, monkeypatch):
    runs = FakeRuns()
    started_before_build = []
    verdicts = _grade(tmp_path, monkeypatch, runs,
                      build_hook=lambda: started_before_build.append(list(runs.calls)))
    assert verdicts["arch"].passed and verdicts["chatter"].passed  # each check found its policy after its gate
    assert sorted(runs.calls) == [("arch", True), ("chatter", False)]
    gate = tmp_path / "out" / "_work" / "alice" / "gates" / "arch"
    assert run_gate.read(str(gate)) == run_gate.GO


def test_a_failed_build_voids_the_early_run_and_gives_the_build_s_verdicts(tmp_path, monkeypatch):
    runs = FakeRuns()
    verdicts = _grade(tmp_path, monkeypatch, runs, build_ok=False)
    assert not verdicts["arch"].passed and "CMake Error" in verdicts["arch"].reason
    assert not verdicts["chatter"].passed and "CMake Error" in verdicts["chatter"].reason
    assert runs.calls == [("arch", True)]
    assert run_gate.read(str(tmp_path / "out" / "_work" / "alice" / "gates" / "arch")) == run_gate.STOP


def test_a_build_longer_than_the_wait_limit_runs_the_milestone_again_from_scratch(tmp_path, monkeypatch):
    monkeypatch.setattr(early_runs, "WAIT_LIMIT_S", 0.0)
    runs = FakeRuns()
    verdicts = _grade(tmp_path, monkeypatch, runs)
    assert verdicts["arch"].passed and verdicts["arch"].output() and "skipped" not in verdicts["arch"].reason
    assert sorted(runs.calls) == [("arch", False), ("arch", True), ("chatter", False)]


def test_an_early_run_that_ended_before_the_build_is_replaced_by_a_run_of_its_own(tmp_path, monkeypatch):
    runs = FakeRuns(end_before_gate={"arch"})

    def hook():  # the build ends only after the early run did
        assert _wait_until(lambda: ("arch", True) in runs.calls, 10)
    verdicts = _grade(tmp_path, monkeypatch, runs, build_hook=hook)
    assert verdicts["arch"].passed, verdicts["arch"].reason  # not "the world died": that run never counted
    assert sorted(runs.calls) == [("arch", False), ("arch", True), ("chatter", False)]


def test_no_early_run_when_asked_for_none_or_for_a_course_s_own_check(tmp_path, monkeypatch):
    runs = FakeRuns()
    _grade(tmp_path, monkeypatch, runs, early=0)
    assert all(not gated for _, gated in runs.calls)
    runs = FakeRuns()
    _grade(tmp_path / "own", monkeypatch, runs, milestones=(OWN, CHATTER), early=2)
    assert sorted(runs.calls) == [("chatter", True), ("own", False)]


def _wait_until(condition, timeout):
    import time
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.01)
    return True
