#!/usr/bin/env python3
"""Milestone `pose_subscriber` (000 Part 5): `rosrun my_robot_controller pose_subscriber` subscribes
/turtle1/pose and prints the turtle's X and Y on its terminal as the turtle moves.

The script's name is found (pose_subscriber first, then any executable of the package that
subscribes /turtle1/pose); the printed format is the student's: the turtle is put at two places
and the numbers printed after each must include its X and Y (any format, >= 1 decimal). Where the
output labels both numbers (`X: 2.30, Y: 8.70`, `x=2.3 y=8.7`, `{'x': 2.3, 'y': 8.7}`, print(msg)),
the number after the x label must be X and the one after the y label Y: the text prints "X" and "Y"
for msg.x and msg.y. Output with no label, or one label only (`x, y = 2.3 8.7`), is read unlabelled.
"""
import re
from typing import Dict, List, NamedTuple, Tuple

import rospy
import rostest
from turtlesim.srv import TeleportAbsolute

from course_rospy import quick_exit
from course_format import causes
from course_milestones import guard
from course_milestones.discovery import subscribes, system_state
from course_milestones.milestone_case import MilestoneCase
from course_milestones.students import ONE_MESSAGE, not_found_message, start_registering
from course_milestones.trusted import TURTLESIM
from course_checks.artifacts import save_canvas
from course_checks.waiting import wait_for

TOPIC = "/turtle1/pose"
PLACES = [(2.3, 8.7), (9.4, 3.1)]
CLOSE = 0.06  # a value printed with one decimal is within 0.05
NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?")
# A label: a lone x or y (any case; `pose.x` too, not `pos_x`, `0x`, `yaw`), an optional closing
# quote, then spaces and at most one ':' or '=' before the number (`x: 2.3`, `X=2.3`, `'x': 2.3`,
# `x 2.3`). `x, y = 2.3 8.7` labels only y: a label followed by anything else labels nothing.
LABELLED = re.compile(r"\b([xXyY])\b['\"]?[ \t]*(?:[:=][ \t]*)?(" + NUMBER.pattern + ")")


def labelled(text: str) -> Tuple[List[str], List[str]]:
    """The numbers printed right after an x label and right after a y label in `text`, as printed."""
    found: Dict[str, List[str]] = {"x": [], "y": []}
    for label, number in LABELLED.findall(text):
        found[label.lower()].append(number)
    return found["x"], found["y"]


def close(numbers: List[str], value: float) -> bool:
    return any(abs(float(n) - value) < CLOSE for n in numbers)


class Read(NamedTuple):
    """What the output printed after a move shows of X=x, Y=y."""
    got_x: bool
    got_y: bool
    xs: List[str]  # the numbers after its x labels, and after its y labels: both used, or both empty
    ys: List[str]
    anywhere: bool  # x and y both among its numbers, labelled or not

    @property
    def mislabelled(self) -> bool:
        """Both printed, but not each after its own label (x and y swapped)."""
        return bool(self.xs) and self.anywhere and not (self.got_x and self.got_y)


def read(text: str, x: float, y: float) -> Read:
    """Whether `text` shows X=x and Y=y. When it uses both an x and a y label, the number after an x
    label must be x and the one after a y label y; else any of its numbers counts."""
    numbers = NUMBER.findall(text)
    anywhere = close(numbers, x) and close(numbers, y)
    xs, ys = labelled(text)
    if xs and ys:
        return Read(close(xs, x), close(ys, y), xs, ys, anywhere)
    return Read(close(numbers, x), close(numbers, y), [], [], anywhere)


@guard.judged  # a violation of the trust policy fails the test, first
class PoseSubscriberMilestone(MilestoneCase):
    started = None

    @classmethod
    def setUpClass(cls):
        cls.pkg = rospy.get_param("~pkg")
        rospy.wait_for_service("/turtle1/teleport_absolute", 30)
        cls.started, cls.tried = start_registering(cls.pkg, [], subscribes(TOPIC), hint="pose",
                                                   log_name="pose_subscriber")

    @classmethod
    def tearDownClass(cls):
        save_canvas()
        if cls.started is not None:
            cls.started.keyboard.end()

    def output(self):
        return self.started.keyboard.node.output()

    def test_prints_the_position_as_the_turtle_moves(self):
        self.assertTrue(self.started is not None, not_found_message(self.pkg, "subscribes %s" % TOPIC, self.tried))
        teleport = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
        for place, (x, y) in enumerate(PLACES):
            mark = len(self.output())
            teleport(x, y, 0.0)

            def printed() -> Read:
                return read(self.output()[mark:], x, y)
            seen = wait_for(lambda: all(printed()[:2]), 5)
            if seen:
                continue
            got = printed()
            name = self.started.path.rsplit("/", 1)[-1]
            why = self.cause(name, printed_before=place > 0)
            if not why and got.mislabelled:
                self.fail(causes.finding("not_printed", (
                    "turtle1 moved to X=%.2f, Y=%.2f and %s printed both numbers, but not each after its own "
                    "label: after its x label it printed %s, after its y label %s (last output: %r); the text "
                    "prints msg.x after X and msg.y after Y (are x and y swapped?)") % (
                    x, y, name, got.xs[-1], got.ys[-1], self.output()[-200:])))
            missing = " and ".join(w for w, ok in (("X", got.got_x), ("Y", got.got_y)) if not ok)
            silent = "turtle1 moved to X=%.2f, Y=%.2f but %s printed no %s on its terminal (last output: %r)" % (
                x, y, name, missing, self.output()[-200:])
            self.fail(causes.finding(causes.of(why, "not_printed"), why + silent))

    def cause(self, name: str, printed_before: bool) -> str:
        """Why the node printed nothing, said first when it is known: it exited (after printing an
        earlier place, `printed_before`, or before printing any), or it stopped listening while
        still running (the same words whether this is seen before the check found the node or after)."""
        node = self.started.keyboard.node
        reg = self.started.registration
        did = "%s subscribed %s (node %s), then " % (name, TOPIC, reg.node)
        if not node.running():
            return causes.finding(causes.exited(printed_before),
                                  did + "exited with status %s; so " % node.proc.returncode)
        if TOPIC not in system_state().get(reg.node, reg).subscribes:
            return causes.finding("stopped_listening",
                                  did + "stopped listening while still running: %s; so " % ONE_MESSAGE)
        return ""


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("pose_subscriber_check")
    guard.install([TURTLESIM])  # before any student code: believe only this simulator
    rostest.rosrun("course_milestones", "pose_subscriber", PoseSubscriberMilestone)
