"""Every milestone of the course, in the order of the texts. The one list the grader reads."""
from __future__ import annotations

from typing import Dict, List

from course_milestones.milestone import Milestone
from course_milestones.texts import exercise1, lab2, ros2_basics, ros2_course, upmc

MILESTONES: List[Milestone] = (ros2_basics.MILESTONES + upmc.MILESTONES + lab2.MILESTONES
                               + exercise1.MILESTONES + ros2_course.MILESTONES)


def by_name() -> Dict[str, Milestone]:
    return {m.name: m for m in MILESTONES}
