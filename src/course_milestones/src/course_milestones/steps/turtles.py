"""The turtle steps, on the course's own turtlesim (the milestone's `world`, recorded by the trust
guard before the student's code ran): `teleport` puts a turtle somewhere (an action), and
`turtle_moves` judges how it moved since the last action from its /TURTLE/pose (steps.motion)."""
from __future__ import annotations

import math
from typing import Dict

import rospy
from turtlesim.msg import Pose
from turtlesim.srv import TeleportAbsolute

from course_milestones.discovery import topic_types
from course_milestones.steps import motion
from course_milestones.steps.state import StepState, course_error, failed
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

SERVICE_WAIT_S = 10.0
POSE_WAIT_S = 5.0
ARRIVED_M = 0.01


def watch(state: StepState, turtle: str) -> TopicRecorder:
    """The recorder of /TURTLE/pose (started on first use; the poses before the next action count)."""
    if turtle not in state.pose_recorders:
        state.pose_recorders[turtle] = TopicRecorder("/%s/pose" % turtle, Pose)
    return state.pose_recorders[turtle]


def watch_all(state: StepState) -> None:
    """Watch every turtle a turtlesim publishes the pose of (an action may move any of them)."""
    for topic, kind in topic_types().items():
        if kind == "turtlesim/Pose" and topic.endswith("/pose"):
            watch(state, topic[1:-len("/pose")])


def teleport(state: StepState, p: Dict, where: str) -> None:
    turtle = p.get("turtle") or "turtle1"
    service = "/%s/teleport_absolute" % turtle
    poses = watch(state, turtle)
    try:
        rospy.wait_for_service(service, SERVICE_WAIT_S)
    except rospy.ROSException:
        raise course_error(where, "no %s: teleport needs the course's turtlesim (world: [turtlesim]) and a turtle "
                                  "named %s" % (service, turtle)) from None
    x, y, theta = float(p["x"]), float(p["y"]), float(p.get("theta") or 0.0)
    state.action("teleporting %s to (%g, %g)" % (turtle, x, y))
    try:
        rospy.ServiceProxy(service, TeleportAbsolute)(x, y, theta)
    except (rospy.ServiceException, rospy.ROSException) as err:
        raise failed("check_failed", "teleporting %s to (%g, %g) failed: %s" % (turtle, x, y, err)) from None
    wait_for(lambda: poses.last is not None and math.hypot(poses.last.x - x, poses.last.y - y) < ARRIVED_M,
             POSE_WAIT_S)
    state.pose_marks[turtle] = poses.count  # the move counts from where it was put


def turtle_moves(state: StepState, p: Dict, where: str) -> None:
    turtle, direction = p.get("turtle") or "turtle1", p.get("direction") or "any"
    if direction not in motion.DIRECTIONS:
        raise course_error(where, "direction %r is not one of %s" % (direction, ", ".join(motion.DIRECTIONS)))
    poses = watch(state, turtle)
    mark = state.pose_marks.get(turtle)
    if mark is None:  # not watched at the last action: from its first pose now on
        mark = 1 if wait_for(lambda: poses.count, POSE_WAIT_S) else 0
        state.pose_marks[turtle] = mark
    min_distance, within = float(p.get("min_distance") or 0.0), float(p.get("within") or 0)

    def since():
        return [(m.x, m.y, m.theta) for m in poses.messages[max(mark - 1, 0):]]
    if not wait_for(lambda: poses.count, POSE_WAIT_S):
        raise failed("not_moving", "no pose of %s (/%s/pose): is turtlesim running, with a turtle of that name?"
                     % (turtle, turtle))
    if wait_for(lambda: motion.judge(since(), direction, min_distance).holds, within, 0.05):
        return
    raise failed("not_moving", "%s %s: %s" % (turtle, state.after_action(), motion.judge(since(), direction,
                                                                                min_distance).text))
