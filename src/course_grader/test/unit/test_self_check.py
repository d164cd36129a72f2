"""course-check's own words: each verdict and its reason, and what it refuses before grading.
(The grading itself is the grader's: src/course_workbench/test/integration drives it end to end.)"""
from course_grader import self_check


def test_each_verdict_is_a_line_and_a_failure_gives_its_reason_without_the_logs():
    results = {"tests": [
        {"name": "chatter: Example (002 section 2)", "status": "passed", "output": "passed\n\nlogs..."},
        {"name": "checkpoint1: TimestampString (002 section 3)", "status": "failed",
         "output": "FAILED: no executable publishes /user_messages\nsandbox: a note\n\n--- user_pub.py log ---\nx"},
    ]}
    assert self_check.verdict_lines(results) == [
        "PASS  chatter: Example (002 section 2)",
        "FAIL  checkpoint1: TimestampString (002 section 3)",
        "      no executable publishes /user_messages",
        "      sandbox: a note",
    ]


def test_nothing_to_grade_is_said_before_the_grader_starts(tmp_path, capsys):
    empty = tmp_path / "src"
    empty.mkdir()
    assert self_check.main([str(empty), "--out", str(tmp_path / "out")]) == 2
    assert "no catkin package in %s" % empty in capsys.readouterr().err
    assert self_check.main([str(tmp_path / "missing")]) == 2
    assert "is not a folder" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_the_report_never_goes_into_the_students_sources(tmp_path, capsys):
    pkg = tmp_path / "src" / "chatter"
    pkg.mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='2'><name>chatter</name></package>")
    assert self_check.main([str(tmp_path / "src"), "--out", str(tmp_path / "src" / "report")]) == 2
    assert "inside" in capsys.readouterr().err
