"""The turtle motions course, courses/turtle_motions (drive a straight line, turn in place, go to a
goal, spawn two turtles), graded as a TA would: one `rosrun course_grader grade --course
courses/turtle_motions` run over every sample (derived ones made as course_testkit.samples does,
each graded on the milestones its expected.json names) and over the reference solution (every
milestone must pass). It is the course of the steps `stops_at` and `turns`, and of a call's saved
values named by later steps: every verdict, reason and cause is compared with the sample's
expected.json (course_testkit.sample_grading), a crash included (bad_straight_crash: the same
reason however soon after registering the node crashes). Without a grader run: every milestone has
a correct and a buggy sample, the course uses each of those steps, and its Python nodes are
executable in git.

The grading starts as soon as the session knows these tests will run (start_early, called by the
root conftest.py), so it overlaps the rest of a suite; the first test that needs it waits.
"""
from __future__ import annotations

from pathlib import Path
from typing import Dict

import pytest

from course_format import course_file, saved
from course_testkit import sample_grading
from course_testkit.gradings import processes_of
from course_testkit.sample_grading import CourseGrading

ROOT = Path(__file__).resolve().parents[1]
COURSE = ROOT / "courses" / "turtle_motions"
MILESTONES = [m.name for m in course_file.load(str(COURSE)).milestones]
JOBS = 2
GRADER_TIMEOUT_S = 1800

GRADING = pytest.StashKey[CourseGrading]()


def start_early(config: pytest.Config) -> None:
    grading = CourseGrading(ROOT, COURSE, JOBS, "grader-motions-")
    config.stash[GRADING] = grading
    config.add_cleanup(grading.stop)


@pytest.fixture(scope="module")
def graded(request: pytest.FixtureRequest) -> Path:
    if GRADING not in request.config.stash:  # this module was not known to be selected at collection
        start_early(request.config)
    return request.config.stash[GRADING].graded(GRADER_TIMEOUT_S)


@pytest.mark.parametrize("sample,milestone,expected", sample_grading.course_expectations(COURSE, MILESTONES),
                         ids=lambda v: v if isinstance(v, str) else "")
def test_verdict(graded: Path, sample: str, milestone: str, expected: Dict) -> None:
    problem = sample_grading.verdict_problem(graded, sample, milestone, expected)
    assert not problem, problem


def test_nothing_left_running(graded: Path) -> None:
    left = processes_of(str(graded))
    assert not left, "processes left running after grading:\n" + "\n".join(left)


def test_the_course_folder_is_unchanged(request: pytest.FixtureRequest, graded: Path) -> None:
    assert sample_grading.git_state(ROOT, str(COURSE)) == request.config.stash[GRADING].checkout_before, \
        "the grading changed " + str(COURSE)


def test_no_reason_begins_with_the_check_s_test_method_name(graded: Path) -> None:
    """A student reads the check's sentence, not `test_steps: ...` (the name of run_steps' test method)."""
    for sample in sample_grading.course_samples(COURSE):
        for milestone, test in sample_grading.tests_of(graded, sample.name).items():
            assert "test_steps" not in test["output"], "%s/%s: %s" % (sample.name, milestone, test["output"][:300])


def test_every_milestone_has_a_correct_and_a_buggy_sample() -> None:
    assert sample_grading.without_both_samples(COURSE, MILESTONES) == {}


def test_the_course_uses_the_steps_it_was_written_for() -> None:
    steps = [s for m in course_file.load(str(COURSE)).milestones for s in m.steps]
    assert {"stops_at", "turns"} <= {s.primitive for s in steps}
    assert any(s.primitive == "call" and s.params["save"] for s in steps)
    assert any(saved.references(s.params) for s in steps if s.primitive != "call")
    assert any("differs" in str(s.params.get("expect")) for s in steps)


def test_the_python_nodes_are_executable_in_git() -> None:
    why = sample_grading.not_a_checkout(ROOT)
    if why:
        pytest.skip("git's file modes cannot be read: %s" % why)
    assert sample_grading.not_executable_in_git(ROOT, COURSE) == []
