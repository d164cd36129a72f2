"""roslab's look at the student's master: every 0.5 s while it waits for their `roscore`, every
2 s once lab_view follows it (each look costs roslab and the master an XML-RPC call)."""
from __future__ import annotations

import pytest

from course_workbench import roslab

STUDENT = "http://localhost:11311"


@pytest.fixture
def lab():
    lab = roslab.RosLab(0, STUDENT, "token", env={"PATH": "/usr/bin:/bin"})
    yield lab
    if lab.lab_view is not None:
        lab.lab_view.stop()


def running_lab_view(lab: roslab.RosLab) -> None:
    lab.lab_view = roslab.Child(["sleep", "60"], lab.env, "lab_view")


def test_it_looks_often_while_the_student_has_no_master(lab):
    assert lab.poll_period() == roslab.POLL_S
    running_lab_view(lab)
    lab.following = ("http://localhost:40000", 123)  # the page's own master
    assert lab.poll_period() == roslab.POLL_S


def test_it_looks_less_often_once_lab_view_follows_the_students_master(lab):
    running_lab_view(lab)
    lab.following = (STUDENT, 4321)
    assert lab.poll_period() == roslab.SETTLED_POLL_S > roslab.POLL_S


def test_it_looks_often_again_when_the_students_master_is_down_or_lab_view_stopped(lab):
    running_lab_view(lab)
    lab.following = (STUDENT, -1)  # lab_view waits for the student's master to come back
    assert lab.poll_period() == roslab.POLL_S
    lab.following = (STUDENT, 4321)
    lab.lab_view.stop()
    assert lab.poll_period() == roslab.POLL_S
