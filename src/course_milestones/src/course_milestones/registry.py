"""The built-in course's milestones (courses/robotics_labs/course.yaml), in the order of the texts:
the list the grader reads when no --course is given."""
from __future__ import annotations

from typing import Dict, List

from course_milestones import course_file
from course_milestones.milestone import Milestone

MILESTONES: List[Milestone] = course_file.load(course_file.builtin_course_dir()).milestones


def by_name() -> Dict[str, Milestone]:
    return {m.name: m for m in MILESTONES}
