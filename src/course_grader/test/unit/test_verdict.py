"""Which milestones a submission is graded on, and verdicts in words."""
import json
import os

from course_format.milestone import Milestone

from course_grader import verdict
from course_grader.submissions import Package
from course_grader.verdict import Verdict

CHATTER = Milestone("chatter", "Example pub/sub", "002 section 2", "chatter.test", ("chatter",))
CP1 = Milestone("checkpoint1", "TimestampString", "002 checkpoint 1", "checkpoint1.test", ("my_chatter",))
GRAPH = Milestone("graph_picture", "rqt_graph picture", "003 Part I", "graph_picture.test", (), 5.0)
ALL = [CHATTER, CP1, GRAPH]


def test_select_by_packages_held():
    assert verdict.select(ALL, ["my_chatter"], None, False) == [CP1]
    assert verdict.select(ALL, ["something_else"], None, False) == [CHATTER, CP1]
    assert verdict.select(ALL, ["chatter_pkg"], None, False) == [CHATTER]
    assert verdict.select(ALL, [], None, True) == ALL
    assert verdict.select(ALL, ["my_chatter"], ["graph_picture"], False) == [GRAPH]


def test_missing_package_sentences():
    assert verdict.missing_package(CHATTER, [Package("chatter", "/x/chatter")]) is None
    assert verdict.missing_package(GRAPH, []) is None
    none = verdict.missing_package(CHATTER, [])
    assert "no catkin package found" in none and "'chatter'" in none
    wrong = verdict.missing_package(CP1, [Package("mychatter", "/x/mychatter")])
    assert "expected a catkin package named 'my_chatter', found: mychatter" in wrong
    assert "rename 'mychatter' to 'my_chatter'" in wrong
    broken = verdict.missing_package(CP1, [Package(None, "/x/pkg", "package.xml cannot be read: junk")])
    assert "pkg (package.xml cannot be read: junk)" in broken


def test_verdict_points_and_output():
    failed = Verdict("alice", CHATTER, False, "no executable publishes /chatter_talk", "--- last lines of a.log ---\nx")
    assert failed.points == 0 and failed.output().startswith("FAILED: no executable")
    assert failed.output().endswith("x")
    assert Verdict("alice", GRAPH, True, "").points == 5.0


def test_log_tails_keep_the_end_of_each_log(tmp_path):
    (tmp_path / "talker.py.log").write_text("\n".join("line %d" % i for i in range(100)))
    (tmp_path / "canvas.png").write_bytes(b"png")
    tails = verdict.log_tails(str(tmp_path), lines=3)
    assert tails == "--- last lines of talker.py.log ---\nline 97\nline 98\nline 99"
    assert Verdict("a", CHATTER, True, "", artifacts_dir=str(tmp_path)).canvases() == [str(tmp_path / "canvas.png")]


def test_trim_and_capped_output(tmp_path):
    big = tmp_path / "listener.py.log"
    big.write_bytes(b"x" * 5000 + b"THE END")
    verdict.trim_files(str(tmp_path), keep=100)
    text = big.read_bytes()
    assert text.endswith(b"THE END") and b"left out" in text and os.path.getsize(big) < 200
    assert verdict.output_capped(str(tmp_path)) == []


def test_log_tails_drop_terminal_control_sequences(tmp_path):
    title, bold, plain = "\x1b]2;/ws/a.launch http://localhost:1/\x07", "\x1b[1m", "\x1b[0m"
    (tmp_path / "roslaunch.log").write_text(title + bold + "process[a-1]: started" + plain + "\n")
    assert verdict.log_tails(str(tmp_path)).splitlines()[1] == "process[a-1]: started"


def test_longest_first_puts_unknown_then_slow_milestones_first():
    from course_grader.runner import longest_first
    assert longest_first(ALL, {"chatter": 4.0, "checkpoint1": 7.5}) == [GRAPH, CP1, CHATTER]


def test_a_run_ended_at_a_sandbox_limit_fails_whatever_its_check_saw(tmp_path):
    report = tmp_path / "sandbox.json"
    report.write_text(json.dumps({"hits": {"processes": "your code reached the process limit", "cpu": "a process"}}))
    hits = verdict.sandbox_hits(str(report))
    assert verdict.ended_by_limit(hits)
    assert verdict.sandbox_notes(hits).splitlines() == ["sandbox limit: a process",
                                                        "sandbox limit: your code reached the process limit"]
    assert not verdict.ended_by_limit({"cpu": "a process of yours used its 300 s"}), "a CPU note does not end a run"
    for text in ("", "[1]", '{"hits": [1]}', '{"hits": {"memory": 3}}'):
        report.write_text(text)
        assert verdict.sandbox_hits(str(report)) == {}, text
    assert verdict.sandbox_hits(str(tmp_path / "none.json")) == {}


def test_a_rosbuild_package_of_the_expected_name_is_named_as_such(tmp_path):
    old = tmp_path / "lab2" / "src" / "mybot_teleop"
    old.mkdir(parents=True)
    (old / "manifest.xml").write_text("<package/>")
    (old / "CMakeLists.txt").write_text("include($ENV{ROS_ROOT}/core/rosbuild/rosbuild.cmake)\n")
    milestone = Milestone("teleop", "Teleop", "x", "teleop.test", ("mybot_teleop",))
    said = verdict.missing_package(milestone, [], str(tmp_path))
    assert said.startswith("lab2/src/mybot_teleop is a rosbuild package (manifest.xml, no package.xml)")
    assert getattr(said, "cause", "") == "rosbuild"
    (tmp_path / "other").mkdir()
    assert "no catkin package found" in verdict.missing_package(milestone, [], str(tmp_path / "other"))


def test_a_students_text_quotes_their_paths_from_the_package_down_even_cut_at_the_start():
    src, work, out = "/tmp/g/grades/_work/alice/ws/src", "/tmp/g/grades/_work/alice", "/tmp/g/grades"
    text = ("ending with 'ades/_work/alice/ws/src/chatter/scripts/talker.py\", line 3'\n"
            "File \"/tmp/g/grades/_work/alice/ws/src/chatter/scripts/talker.py\"; see /tmp/g/grades/_work/alice/runs/x")
    assert verdict.without_grader_paths(text, [src, work, out]) == (
        "ending with 'chatter/scripts/talker.py\", line 3'\nFile \"chatter/scripts/talker.py\"; see runs/x")
    printed = "output folder seen as '/tmp/g/grades'; looked in ['/tmp', '/tmp/g/grades/_work', '/tmp/g/gradesx']"
    assert verdict.without_grader_paths(printed, [src, work, out]) == (
        "output folder seen as '<grader's folder>'; looked in ['/tmp', '_work', '/tmp/g/gradesx']")


def test_what_a_run_printed_adds_only_causes_the_files_did_not_name(tmp_path):
    (tmp_path / "talker.py.log").write_text("talker.py: 2: import: not found\n"
                                            "NameError: name 'raw_input' is not defined\n")
    found = verdict.output_hints(str(tmp_path))
    assert [getattr(h, "cause", "") for h in found] == ["no_shebang", "python2"]
    from course_format import causes
    from_files = [causes.finding("no_shebang", "chatter/scripts/talker.py has no #! line")]
    assert [getattr(h, "cause", "") for h in verdict.output_hints(str(tmp_path), from_files)] == ["python2"]
