"""The flake hunter's report: pytest's JUnit XML from several runs, tallied per test."""
from course_testkit import flakes

HEAD = '<?xml version="1.0" encoding="utf-8"?><testsuites><testsuite name="pytest" tests="4">'
TAIL = "</testsuite></testsuites>"
PASS = '<testcase classname="tests.test_rostests" name="test_rostest[rrbot_camera.test]" time="9.1" />'
FAIL = ('<testcase classname="tests.test_rostests" name="test_rostest[rrbot_camera.test]" time="9.4">'
        '<failure message="AssertionError: rostest rrbot_camera.test failed:&#10;  still arm, same picture: '
        '104 changed pixels&#10;--- output (end) ---">&gt; assert result.passed\nE AssertionError</failure></testcase>')
STEADY = '<testcase classname="src.relay.test_relay" name="test_latched" time="0.2" />'
SKIP = ('<testcase classname="tests.test_netns" name="test_two_hosts" time="0.0">'
        '<skipped type="pytest.skip" message="needs root">x</skipped></testcase>')
SETUP_ERROR = ('<testcase classname="src.relay.test_relay" name="test_types" time="0.0">'
               '<error message="failed on setup with &quot;RuntimeError: no master&quot;">trace</error></testcase>')
TYPES_OK = '<testcase classname="src.relay.test_relay" name="test_types" time="0.1" />'
TEARDOWN_ERROR = ('<testcase classname="src.relay.test_relay" name="test_types" time="0.0">'
                  '<error message="failed on teardown with &quot;OSError&quot;">trace</error></testcase>')

CAMERA = "tests.test_rostests::test_rostest[rrbot_camera.test]"
TYPES = "src.relay.test_relay::test_types"


def run(index, cases, returncode=0, seconds=10.0):
    return flakes.Run(index, seconds, returncode, flakes.parse_outcomes(HEAD + "".join(cases) + TAIL))


def three_runs():
    return [run(1, [PASS, STEADY, SKIP, TYPES_OK]),
            run(2, [FAIL, STEADY, SKIP, SETUP_ERROR], returncode=1, seconds=12.5),
            run(3, [FAIL, STEADY, SKIP, TYPES_OK], returncode=1)]


def test_first_line_joins_a_heading_with_its_next_line_and_cuts_long_ones():
    assert flakes.first_line("rostest x failed:\n  still arm: 104\nmore") == "rostest x failed: still arm: 104"
    assert flakes.first_line("\n  plain message \nsecond") == "plain message"
    assert flakes.first_line("") == ""
    assert len(flakes.first_line("x" * 500)) == flakes.MESSAGE_CHARS


def test_tally_counts_runs_failures_and_skips_and_keeps_the_first_message():
    tallies = flakes.tally(three_runs())
    assert tallies[CAMERA] == flakes.Tally(
        3, 2, 0, 2, "AssertionError: rostest rrbot_camera.test failed: still arm, same picture: 104 changed pixels")
    assert tallies[TYPES] == flakes.Tally(3, 1, 0, 2, 'failed on setup with "RuntimeError: no master"')
    assert tallies["src.relay.test_relay::test_latched"] == flakes.Tally(3, 0, 0, None, "")
    assert tallies["tests.test_netns::test_two_hosts"] == flakes.Tally(0, 0, 3, None, "")


def test_a_test_failing_then_erroring_in_teardown_counts_once():
    outcomes = flakes.parse_outcomes(HEAD + SETUP_ERROR.replace("setup", "call") + TEARDOWN_ERROR + TAIL)
    assert outcomes == (flakes.Outcome(TYPES, flakes.FAILED, 'failed on call with "RuntimeError: no master"'),)


def test_a_test_without_classname_is_named_by_its_name():
    outcomes = flakes.parse_outcomes(HEAD + '<testcase classname="" name="test_x" time="0.1" />' + TAIL)
    assert outcomes == (flakes.Outcome("test_x", flakes.PASSED, ""),)


def test_a_run_without_results_fails_and_is_reported():
    runs = [run(1, [PASS]), flakes.Run(2, 3.0, 4, None)]
    assert flakes.any_failure(runs)
    assert "run 2: no JUnit results (pytest exit code 4) in 3.0 s" in flakes.report(runs)
    assert flakes.read_outcomes("/nonexistent/run-01.xml") is None


def test_report_lists_runs_failing_tests_and_totals():
    text = flakes.report(three_runs())
    assert "run 1: 3 passed, 0 failed, 1 skipped (exit code 0) in 10.0 s" in text
    assert "run 2: 1 passed, 2 failed, 1 skipped (exit code 1) in 12.5 s" in text
    lines = text.splitlines()
    camera = lines.index("  2/3 failed  " + CAMERA)
    assert lines[camera + 1].startswith("      first in run 2: AssertionError: rostest rrbot_camera.test failed:")
    assert lines.index("  1/3 failed  " + TYPES) > camera  # most failures first
    assert "test_latched" not in text
    assert lines[-1] == ("Totals: 3 runs, 2 failed, in 32.5 s (10.8 s per run); 4 tests, 2 failed at least once "
                         "(2 flaky: failed in some runs and passed in others)")
    assert flakes.any_failure(three_runs())


def test_all_passing_runs_report_none_and_show_all_lists_every_test():
    runs = [run(1, [PASS, STEADY]), run(2, [PASS, STEADY])]
    assert not flakes.any_failure(runs)
    assert "Tests that failed at least once:\n  none" in flakes.report(runs)
    assert "  0/2 failed  src.relay.test_relay::test_latched" in flakes.report(runs, show_all=True)
