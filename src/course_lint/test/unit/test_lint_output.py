"""What course-lint reads from the grader (results.json), the statuses it gives the mutants (an
`equivalent` annotation moves a survivor out of the score; one that names no survivor is a
problem of the course file, at its line), and the lines and JSON it writes of them."""
import json

import pytest

from course_format import course_file
from course_format.course_file import Course
from course_format.milestone import Equivalent, Milestone

from course_lint import cli, lint, mutants

RATE = mutants.by_names(["rate_div10"])[0]
OPERATORS = mutants.by_names(["rate_div10", "publish_removed"])
CHATTER = Milestone("chatter", "Example pub/sub", "002 section 2", "chatter.test", ("chatter",),
                    course_file="/courses/demo/course.yaml",
                    equivalent=(Equivalent("rate_div10_1", "section 2 fixes no rate", 12),))


def outcome(name, status, graded=True, why=""):
    mutant = mutants.Mutant("chatter", RATE, "src/example_pub.py", 11, "rate = rospy.Rate(1.0)", "")
    passed = status != lint.KILLED
    return lint.Outcome(name, mutant, graded, passed, "" if passed else "FAILED: too slow", status, why)


REFERENCE = lint.Outcome("reference", None, True, True, "")


def test_verdict_from_results_json(tmp_path):
    (tmp_path / "chatter__reference").mkdir()
    (tmp_path / "chatter__reference" / "results.json").write_text(json.dumps({"tests": [
        {"name": "chatter: Example pub/sub (002 section 2)", "status": "failed", "output": "FAILED: nothing on /chatter_talk\n",
         "extra_data": {"milestone": "chatter"}}]}))
    assert lint.verdict(str(tmp_path), "chatter__reference", "chatter") == (True, False, "FAILED: nothing on /chatter_talk")
    assert lint.verdict(str(tmp_path), "chatter__reference", "color")[:2] == (False, False)
    graded, passed, reason = lint.verdict(str(tmp_path), "chatter__rate_div10_1", "chatter")
    assert (graded, passed) == (False, False) and reason.startswith("not graded: no results.json")


def test_an_annotation_moves_its_survivor_out_of_the_score():
    results, problems = lint.annotated(CHATTER, [outcome("rate_div10_1", lint.SURVIVED),
                                                 outcome("rate_div10_2", lint.KILLED)], OPERATORS)
    assert problems == []
    assert [(o.name, o.status, o.why) for o in results] == [
        ("rate_div10_1", lint.EQUIVALENT, "section 2 fixes no rate"), ("rate_div10_2", lint.KILLED, "")]
    result = lint.MilestoneLint(CHATTER, REFERENCE, results, [])
    assert (len(result.killed), result.scored) == (1, 1)
    assert cli.milestone_line(result) == (
        "chatter  1/1 killed  survivors: none  equivalent: rate_div10_1 (chatter/src/example_pub.py:11: section 2 "
        "fixes no rate)  not run: none")


@pytest.mark.parametrize("status, graded, words", [
    (lint.KILLED, True, "names no surviving mutant: rate_div10_1 is killed (FAILED: too slow)"),
    (lint.NOT_RUN, False, "names no surviving mutant: rate_div10_1 is not run (line 11 never ran): it needs no "
                          "annotation"),
    (lint.SURVIVED, False, "names no surviving mutant: rate_div10_1 got no verdict from the grader (FAILED: too slow)"),
])
def test_an_annotation_naming_no_survivor_is_a_problem_at_its_line(status, graded, words):
    named = outcome("rate_div10_1", status, graded, "line 11 never ran" if status == lint.NOT_RUN else "")
    if status == lint.SURVIVED:
        named = named._replace(passed=False, reason="FAILED: too slow")
    results, problems = lint.annotated(CHATTER, [named], OPERATORS)
    assert results == [named] and [why for _, why in problems] == [words]
    course = Course("demo", "Demo", "/courses/demo", "/courses/demo/course.yaml", None, None, [CHATTER])
    result = lint.MilestoneLint(CHATTER, REFERENCE, results, [], tuple(problems))
    assert cli.problems(course, [result]) == ["/courses/demo/course.yaml:12: milestones[0].equivalent.rate_div10_1: "
                                              + words]


def test_an_annotation_of_a_mutant_not_made_is_a_problem_unless_its_operator_was_left_out():
    results, problems = lint.annotated(CHATTER, [outcome("rate_div10_2", lint.SURVIVED)], OPERATORS)
    assert [why for _, why in problems] == ["names no mutant of this milestone (its mutants: rate_div10_2)"]
    assert results[0].status == lint.SURVIVED
    assert lint.annotated(CHATTER, [], mutants.by_names(["publish_removed"])) == ([], [])  # --operators publish_removed


def test_milestone_lines_show_every_status():
    result = lint.MilestoneLint(CHATTER, REFERENCE, [
        outcome("rate_div10_1", lint.SURVIVED), outcome("rate_div10_2", lint.KILLED),
        outcome("rate_div10_3", lint.NOT_RUN, graded=False, why="example_pub.py never ran")], [])
    assert cli.milestone_line(result) == (
        "chatter  1/2 killed  survivors: rate_div10_1 (a loop rate divided by ten, chatter/src/example_pub.py:11)  "
        "equivalent: none  not run: rate_div10_3 (chatter/src/example_pub.py:11: example_pub.py never ran)")
    failing = lint.MilestoneLint(CHATTER, lint.Outcome("reference", None, True, False, "FAILED"),
                                 [outcome("rate_div10_1", lint.KILLED), outcome("rate_div10_2", lint.SURVIVED, False)], [])
    assert cli.milestone_line(failing) == ("chatter  REFERENCE FAILS  1/2 killed  survivors: rate_div10_2 (a loop rate "
                                           "divided by ten, chatter/src/example_pub.py:11; not graded)  equivalent: none"
                                           "  not run: none")
    assert cli.summary([result, failing]) == "mutants: 5 made, 2 killed, 2 survived, 0 equivalent, 1 not run"


def test_json_gives_each_mutant_its_status_and_counts_the_score_over_killed_and_survived():
    results, problems = lint.annotated(CHATTER, [
        outcome("rate_div10_1", lint.SURVIVED), outcome("rate_div10_2", lint.KILLED),
        outcome("rate_div10_3", lint.NOT_RUN, graded=False, why="line 11 never ran"),
        outcome("rate_div10_4", lint.SURVIVED)], OPERATORS)
    course = Course("demo", "Demo", "/courses/demo", "/courses/demo/course.yaml", None, None, [CHATTER])
    table = cli.as_json(course, [lint.MilestoneLint(CHATTER, REFERENCE, results, [], tuple(problems),
                                                    (("python", "measured"),))])
    assert (table["killed"], table["survived"], table["equivalent"], table["not_run"], table["total"], table["made"]) \
        == (1, 1, 1, 1, 2, 4)
    milestone = table["milestones"][0]
    assert [(m["name"], m["status"], m["graded"]) for m in milestone["mutants"]] == [
        ("rate_div10_1", "equivalent", True), ("rate_div10_2", "killed", True), ("rate_div10_3", "not run", False),
        ("rate_div10_4", "survived", True)]
    assert milestone["mutants"][0]["why"] == "section 2 fixes no rate" and milestone["measured"] == {"python": "measured"}
    assert (milestone["killed"], milestone["total"], table["problems"]) == (1, 2, [])


COURSE = """name: demo
title: Demo
milestones:
  - id: chatter
    title: Example pub/sub
    text: 002 section 2
    packages: [chatter]
    check: chatter.test
    equivalent:
      rate_div10_1: "section 2 fixes no rate"
"""


def test_the_course_file_reads_annotations_with_their_lines(tmp_path):
    (tmp_path / "checks").mkdir()
    (tmp_path / "checks" / "chatter.test").write_text("<launch/>")
    milestone = course_file.parse(COURSE, str(tmp_path / "course.yaml")).milestones[0]
    assert milestone.equivalent == (Equivalent("rate_div10_1", "section 2 fixes no rate", 10),)


@pytest.mark.parametrize("annotations, error", [
    ('      Rate: "x"\n', "course.yaml:11: milestones[0].equivalent.Rate: 'Rate': name a mutant as course-lint does"),
    ('      rate_div10_2: ""\n', "course.yaml:11: milestones[0].equivalent.rate_div10_2: expected the reason"),
])
def test_the_course_file_refuses_an_annotation_without_a_name_or_a_reason(tmp_path, annotations, error):
    (tmp_path / "checks").mkdir()
    (tmp_path / "checks" / "chatter.test").write_text("<launch/>")
    with pytest.raises(course_file.CourseError) as raised:
        course_file.parse(COURSE + annotations, str(tmp_path / "course.yaml"), "course.yaml")
    assert any(p.startswith(error) for p in raised.value.problems), raised.value.problems
