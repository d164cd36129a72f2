"""The runner's pure parts: capped output, results read from a results folder."""
import os

from course_checks import rostest_runner
from course_checks.rostest_runner import CappedText, RostestResult

LAUNCHER_OK = ('<testsuite errors="0" failures="0" tests="1"><testcase classname="rostest.runner.RosTest" '
               'name="testchatter" time="1.1"/></testsuite>')
ROSUNIT = ('<testsuite errors="1" failures="1" tests="3">'
           '<testcase classname="T" name="test_a"><error type="RuntimeError">boom</error></testcase>'
           '<testcase classname="T" name="test_b"><failure type="AssertionError">no topic</failure></testcase>'
           '<testcase classname="T" name="test_c"/></testsuite>')


def test_capped_text_keeps_head_and_tail():
    text = CappedText(head=10, tail=10)
    for _ in range(1000):
        text.add("0123456789" * 100)
    kept = text.text()
    assert kept.startswith("0123456789") and kept.endswith("0123456789")
    assert len(kept) < 100 and "left out" in kept


def test_short_output_is_kept_whole():
    text = CappedText(head=10, tail=20)
    text.add("hello ")
    text.add("world, this is longer")
    assert text.text() == "hello world, this is longer"


def test_read_results_prefers_the_checks_own_file(tmp_path):
    folder = tmp_path / "ros_home" / "test_results" / "course_milestones"
    folder.mkdir(parents=True)
    (folder / "rostest-test_chatter.xml").write_text(LAUNCHER_OK)
    (folder / "rosunit-chatter_check.xml").write_text(ROSUNIT)
    tests, failures, path = rostest_runner.read_results(str(tmp_path))
    assert tests == 3 and len(failures) == 2
    assert os.path.basename(path) == "rosunit-chatter_check.xml"


def test_no_results_at_all(tmp_path):
    assert rostest_runner.read_results(str(tmp_path)) == (0, [], None)


def test_summary_words():
    result = RostestResult(False, 0, [], None, "", 300.0, True, None, "/tmp/x")
    assert "time limit" in result.summary()
    result = RostestResult(False, 0, [], None, "", 1.0, False, 1, "/tmp/x")
    assert "no test result" in result.summary()
    result = RostestResult(False, 2, [("test_b", "no /chatter_talk")], None, "", 1.0, False, 1, "/tmp/x")
    assert result.summary() == "no /chatter_talk"  # the check's sentence, not its test method's name
    result = RostestResult(False, 2, [("test_b", "")], None, "", 1.0, False, 1, "/tmp/x")
    assert result.summary() == "test_b"
