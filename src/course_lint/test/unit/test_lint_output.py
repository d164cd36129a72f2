"""What course-lint reads from the grader (results.json) and the lines it prints of it."""
import json

from course_format.course_file import Course
from course_format.milestone import Milestone

from course_lint import cli, lint, mutants

CHATTER = Milestone("chatter", "Example pub/sub", "002 section 2", "chatter.test", ("chatter",))
RATE = mutants.by_names(["rate_div10"])[0]


def outcome(name, passed, graded=True):
    mutant = mutants.Mutant("chatter", RATE, "src/example_pub.py", 11, "rate = rospy.Rate(1.0)", "")
    return lint.Outcome(name, mutant, graded, passed, "" if passed else "FAILED: too slow")


def test_verdict_from_results_json(tmp_path):
    (tmp_path / "chatter__reference").mkdir()
    (tmp_path / "chatter__reference" / "results.json").write_text(json.dumps({"tests": [
        {"name": "chatter: Example pub/sub (002 section 2)", "status": "failed", "output": "FAILED: nothing on /chatter_talk\n",
         "extra_data": {"milestone": "chatter"}}]}))
    assert lint.verdict(str(tmp_path), "chatter__reference", "chatter") == (True, False, "FAILED: nothing on /chatter_talk")
    assert lint.verdict(str(tmp_path), "chatter__reference", "color")[:2] == (False, False)
    graded, passed, reason = lint.verdict(str(tmp_path), "chatter__rate_div10_1", "chatter")
    assert (graded, passed) == (False, False) and reason.startswith("not graded: no results.json")


def test_milestone_lines():
    reference = lint.Outcome("reference", None, True, True, "")
    result = lint.MilestoneLint(CHATTER, reference, [outcome("rate_div10_1", True), outcome("rate_div10_2", False)], [])
    assert cli.milestone_line(result) == ("chatter  1/2 killed  survivors: rate_div10_1 (a loop rate divided by ten, "
                                          "chatter/src/example_pub.py:11)")
    failing = lint.MilestoneLint(CHATTER, lint.Outcome("reference", None, True, False, "FAILED"),
                                 [outcome("rate_div10_1", False), outcome("rate_div10_2", False, graded=False)], [])
    assert cli.milestone_line(failing) == ("chatter  REFERENCE FAILS  1/2 killed  survivors: rate_div10_2 (a loop rate "
                                           "divided by ten, chatter/src/example_pub.py:11; not graded)")
    course = Course("demo", "Demo", "/courses/demo", "/courses/demo/course.yaml", None, None, [CHATTER])
    table = cli.as_json(course, [result])
    assert (table["killed"], table["total"], table["milestones"][0]["mutants"][1]["killed"]) == (1, 2, True)

