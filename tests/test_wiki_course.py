"""The second course, courses/ros_wiki_beginner (the ROS wiki's beginner tutorials), graded as a TA
would: one `rosrun course_grader grade --course courses/ros_wiki_beginner` run over every sample
(each graded on the milestones its expected.json names) and over the course's reference solution
(graded as a submission: every milestone, each must pass). Each verdict and reason is compared
with the sample's expected.json as for the built-in course (course_testkit.sample_grading). Without a grader run: every milestone has a correct and a buggy sample, and
every Python node of the course is executable in git.

The grading starts as soon as the session knows these tests will run (start_early, called by the
root conftest.py), so it overlaps the rest of a suite; the first test that needs it waits.
"""
from __future__ import annotations

from pathlib import Path
from typing import Dict

import pytest
import yaml

from course_testkit import sample_grading
from course_testkit.gradings import processes_of
from course_testkit.sample_grading import CourseGrading

ROOT = Path(__file__).resolve().parents[1]
COURSE = ROOT / "courses" / "ros_wiki_beginner"
MILESTONES = [m["id"] for m in yaml.safe_load((COURSE / "course.yaml").read_text())["milestones"]]
JOBS = 2
GRADER_TIMEOUT_S = 1800


def course_state() -> str:
    """What git says of the course's folder, or its files where there is no checkout (a sample
    must not change it; the rest of a shared checkout may change while the grader runs)."""
    return sample_grading.git_state(ROOT, str(COURSE))


GRADING = pytest.StashKey[CourseGrading]()


def start_early(config: pytest.Config) -> None:
    grading = CourseGrading(ROOT, COURSE, JOBS, "grader-wiki-")
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
    """The verdict, its reason and its cause as expected (course_testkit.sample_grading)."""
    problem = sample_grading.verdict_problem(graded, sample, milestone, expected)
    assert not problem, problem


def test_nothing_left_running(graded: Path) -> None:
    left = processes_of(str(graded))
    assert not left, "processes left running after grading:\n" + "\n".join(left)


def test_the_course_folder_is_unchanged(request: pytest.FixtureRequest, graded: Path) -> None:
    assert course_state() == request.config.stash[GRADING].checkout_before, "the grading changed " + str(COURSE)


def test_every_milestone_has_a_correct_and_a_buggy_sample() -> None:
    assert sample_grading.without_both_samples(COURSE, MILESTONES) == {}


def test_the_python_nodes_are_executable_in_git() -> None:
    """A node without its executable bit in git is not found by rosrun once checked out."""
    why = sample_grading.not_a_checkout(ROOT)
    if why:
        pytest.skip("git's file modes cannot be read: %s" % why)
    assert sample_grading.not_executable_in_git(ROOT, COURSE) == []
