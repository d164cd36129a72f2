"""~/milestones under a hub (course_workbench.startup.link_milestones): the course's milestone
pages, where a launch from the LMS naming a milestone opens the workbench; a student's own file
of that name is never replaced."""
from __future__ import annotations

import os

from course_workbench.startup import link_milestones


def course(tmp_path, name="courses/robotics_labs"):
    pages = tmp_path / "checkout" / name / "milestones"
    pages.mkdir(parents=True)
    (pages / "chatter.md").write_text("# chatter\n")
    return str(tmp_path / "checkout")


def test_the_home_links_the_courses_milestone_pages(tmp_path):
    checkout, home = course(tmp_path), tmp_path / "home"
    home.mkdir()
    link = link_milestones(str(home), checkout)
    assert link == str(home / "milestones") and (home / "milestones" / "chatter.md").read_text() == "# chatter\n"
    assert link_milestones(str(home), checkout) == link  # a second start keeps it


def test_another_course_of_the_checkout(tmp_path):
    checkout, home = course(tmp_path, "courses/turtle_motions"), tmp_path / "home"
    home.mkdir()
    assert link_milestones(str(home), checkout) is None  # the built-in course's pages are not there
    assert link_milestones(str(home), checkout, "courses/turtle_motions") == str(home / "milestones")


def test_a_students_own_milestones_folder_stays(tmp_path):
    checkout, home = course(tmp_path), tmp_path / "home"
    (home / "milestones").mkdir(parents=True)
    (home / "milestones" / "mine.txt").write_text("notes")
    assert link_milestones(str(home), checkout) is None
    assert not os.path.islink(home / "milestones") and (home / "milestones" / "mine.txt").read_text() == "notes"
