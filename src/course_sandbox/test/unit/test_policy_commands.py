"""The sandbox's rules as data and as command lines, without running anything."""
import os

from hypothesis import given
from hypothesis import strategies as st

from course_sandbox import access, commands, levels
from course_sandbox.policy import Limits, Policy
from course_sandbox.run import Counted, LimitHits, judge_usage, student_env
from course_sandbox.procs import Usage

paths = st.lists(st.text(st.characters(blacklist_categories=("Cs",), blacklist_characters="\0"), max_size=30),
                 max_size=4)


@given(paths, paths, paths, st.one_of(st.none(), st.dictionaries(st.text(max_size=10), st.text(max_size=10))))
def test_a_policy_survives_its_json(writable, hidden, readable, env):
    policy = Policy(levels.FULL, "someone", writable, hidden, readable, "/h", env, Limits(processes=7), "/r.json")
    assert Policy.from_json(policy.to_json()) == policy


def _mounts(args):
    """(option, target) of each mount in a bubblewrap argument list."""
    found, i = [], 0
    while i < len(args):
        if args[i] in ("--tmpfs", "--dir"):
            found.append((args[i], args[i + 1]))
            i += 2
        elif args[i] in ("--bind", "--ro-bind", "--dev-bind", "--symlink", "--bind-fd", "--ro-bind-fd"):
            found.append((args[i], args[i + 2]))
            i += 3
        elif args[i] in ("--proc", "--size"):
            i += 2
        else:
            i += 1
    return found


def test_deeper_rules_are_mounted_after_the_folders_they_are_in(tmp_path):
    out, ws, course = tmp_path / "out", tmp_path / "out" / "_work" / "alice" / "ws", tmp_path / "course"
    for folder in (ws, course, course / "grades"):
        folder.mkdir(parents=True)
    policy = Policy(levels.FULL, writable=[str(ws)], hidden=[str(out), str(course / "grades")],
                    readable=[str(course)])
    mounts = _mounts(commands.view_args(policy, lambda path: True))
    order = [target for _, target in mounts]
    assert mounts[0] == ("--ro-bind", "/") and ("--tmpfs", "/tmp") in mounts
    assert order.index(str(out)) < order.index(str(ws)), "the workspace must show through the hidden output"
    assert order.index(str(course)) < order.index(str(course / "grades")), "outputs inside the course stay hidden"
    assert ("--bind", str(ws)) in mounts and ("--ro-bind", str(course)) in mounts


def test_a_hidden_file_becomes_empty_and_a_missing_path_is_left_out(tmp_path):
    secret = tmp_path / "alice.zip"
    secret.write_bytes(b"PK")
    policy = Policy(levels.FULL, hidden=[str(secret), str(tmp_path / "gone")])
    mounts = _mounts(commands.view_args(policy, lambda path: True))
    assert ("--ro-bind", str(secret)) in mounts
    assert all(target != str(tmp_path / "gone") for _, target in mounts)


def test_the_user_switch_and_the_process_limit_follow_the_level():
    for level, switches, nproc in [(levels.FULL, True, True), (levels.NAMESPACES, False, True),
                                   (levels.USER, True, True), (levels.NONE, False, False)]:
        argv = commands.enter_command(Policy(level, user="cs"), 42, ["talker"], "/home")
        assert (argv[0] == "setpriv") == switches, level
        assert any(a.startswith("--nproc=") for a in argv) == nproc, level
        assert ("nsenter" in argv) == levels.uses_namespaces(level), level
        assert argv[-1] == "talker" and "--default-signal=INT,TERM" in argv
        counted = commands.enter_command(Policy(level, user="cs"), 42, ["talker"], "/home", counted=True)
        assert not any(a.startswith("--nproc=") for a in counted), "a pids cgroup is the limit: %s" % level


def test_the_weaker_level_wins_and_a_missing_user_stops_a_root_grader(monkeypatch):
    assert levels.weaker(levels.USER, levels.FULL) == levels.USER
    monkeypatch.setattr(levels, "namespaces_work", lambda root, user: True)
    monkeypatch.setattr(levels, "user_exists", lambda user: True)
    monkeypatch.setattr(os, "geteuid", lambda: 0)
    assert levels.detect("cs", {}) == levels.FULL
    assert levels.detect("cs", {levels.LEVEL_VAR: levels.USER}) == levels.USER
    assert levels.detect("cs", {levels.LEVEL_VAR: "stronger-please"}) == levels.FULL
    monkeypatch.setattr(os, "geteuid", lambda: 1000)
    assert levels.detect("cs", {levels.LEVEL_VAR: levels.USER}) == levels.NONE
    monkeypatch.setattr(os, "geteuid", lambda: 0)
    monkeypatch.setattr(levels, "user_exists", lambda user: False)
    try:
        levels.detect("cs", {})
    except levels.Unavailable as err:
        assert "make deps" in str(err)
    else:
        raise AssertionError("a root grader without the sandbox user must refuse")


def test_a_student_process_never_gets_the_trusted_variables():
    policy = Policy(levels.FULL, home="/w/run/student", student_env={"PATH": "/overlay/bin", "ROS_HOME": "/x"})
    given_env = dict(os.environ, ROS_MASTER_URI="http://localhost:1234", COURSE_ARTIFACTS_DIR="/out/alice",
                     COURSE_SANDBOX_POLICY="/out/p.json", ROS_HOME="/out/trusted", DISPLAY=":0")
    env = student_env(policy, dict(given_env, TURTLEBOT3_MODEL="burger"), started_with=given_env)
    assert env["PATH"] == "/overlay/bin" and env["ROS_MASTER_URI"] == "http://localhost:1234"
    assert env["HOME"] == env["ROS_HOME"] == "/w/run/student" and env["ROS_LOG_DIR"] == "/w/run/student/log"
    assert not {"COURSE_ARTIFACTS_DIR", "COURSE_SANDBOX_POLICY", "DISPLAY"} & set(env)
    assert env["TURTLEBOT3_MODEL"] == "burger", "what the check sets on purpose reaches the student's process"


def test_a_student_process_reads_the_runs_etc_folder():
    """The run's etc/ros (roscore.xml without commands) reaches the student's roslaunch, never
    the overlay's own value: its roslaunch loads the same parameters without running rosversion."""
    policy = Policy(levels.FULL, home="/w/run/student", student_env={"PATH": "/overlay/bin", "ROS_ETC_DIR": "/mine"})
    given_env = dict(os.environ, ROS_ETC_DIR="/w/run/etc_ros")
    assert student_env(policy, given_env, started_with=given_env)["ROS_ETC_DIR"] == "/w/run/etc_ros"
    given_env.pop("ROS_ETC_DIR")
    assert "ROS_ETC_DIR" not in student_env(policy, given_env, started_with=given_env)


def test_limits_are_noted_and_the_run_ended_past_memory_or_processes():
    policy = Policy(levels.FULL, limits=Limits(processes=100, memory_bytes=1000, cpu_seconds=10))
    hits = LimitHits()
    assert not judge_usage(policy, [Usage(10, 100, 1.0)], hits) and not hits.hits
    assert judge_usage(policy, [Usage(95, 100, 1.0)], hits) and "process limit" in hits.hits["processes"]
    # With a pids cgroup the kernel's count decides: a refused fork is the limit reached, however
    # few processes the sample saw; its count includes forks not yet in /proc.
    hits = LimitHits()
    assert not judge_usage(policy, [Usage(20, 100, 1.0)], hits, counted=Counted(20, 0)) and not hits.hits
    assert judge_usage(policy, [Usage(20, 100, 1.0)], hits, counted=Counted(20, 3))
    assert "process limit" in hits.hits["processes"]
    hits = LimitHits()
    assert judge_usage(policy, [Usage(20, 100, 1.0)], hits, counted=Counted(96, 0)) and "processes" in hits.hits
    assert hits.as_dict()["peak_tasks"] == 96
    hits = LimitHits()
    assert judge_usage(policy, [], hits, counted=Counted(0, 1)), "refusals count when every process is gone"
    hits = LimitHits()
    assert not judge_usage(policy, [Usage(1, 5000, 1.0)] * 2, hits, shared_memory=lambda: 900)
    assert judge_usage(policy, [Usage(1, 5000, 1.0)] * 2, hits, shared_memory=lambda: 1500)
    assert "memory" in hits.hits and hits.as_dict()["peak_rss_bytes"] == 1500
    judge_usage(policy, [Usage(1, 10, 9.5)], hits)
    assert "CPU" in hits.hits["cpu"]


def test_a_hidden_path_the_sandbox_user_cannot_reach_needs_no_mount(tmp_path):
    (tmp_path / "closed" / "class").mkdir(parents=True)
    (tmp_path / "open" / "out").mkdir(parents=True)
    policy = Policy(levels.FULL, hidden=[str(tmp_path / "closed" / "class"), str(tmp_path / "open" / "out")])
    closed = {str(tmp_path / "closed")}
    mounts = _mounts(commands.view_args(policy, lambda path: path not in closed or path == "/tmp"))
    assert ("--tmpfs", str(tmp_path / "open" / "out")) in mounts
    assert ("--tmpfs", str(tmp_path / "closed" / "class")) in mounts, "below /tmp the sandbox makes its own way"
    policy = Policy(levels.FULL, hidden=["/proc/1/root/etc"])
    mounts = _mounts(commands.view_args(policy, lambda path: path != "/proc/1/root"))
    assert all(target != "/proc/1/root/etc" for _, target in mounts)


def test_the_first_folder_the_user_cannot_pass_is_named():
    assert access.unreachable_part("/a/b/c", lambda p: p != "/a/b") == "/a/b"
    assert access.unreachable_part("/a/b/c", lambda p: True) == ""


def test_the_isolation_sentence_says_why_it_is_weaker():
    from course_sandbox import levels
    assert "this machine refuses namespaces" in levels.describe(levels.USER, "sandboxer", {})
    forced = levels.describe(levels.NONE, "sandboxer", {levels.LEVEL_VAR: "none"})
    assert forced.startswith("none: COURSE_SANDBOX_LEVEL=none asked for it, so")
    assert "refuses" not in forced
    assert "(no user switch: the grader is not root)" in levels.describe(levels.NAMESPACES, "s", {})
    assert "{" not in levels.describe(levels.FULL, "sandboxer", {levels.LEVEL_VAR: "full"})
