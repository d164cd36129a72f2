#!/usr/bin/env python3
"""Milestone `arch` (003, Writing Our First Node, tasks 1-8): `rosrun my_pkg my_node.py`, then
check the interfaces the tasks name and draw two arches, one past pi with a pause in the middle.

Before each arch the turtle is teleported away from the centre with a turned heading: a drawer
that calls /reset first (task 7) starts the arch from the centre heading 0; one that does not
starts from where the turtle was left.
"""
import math

import rospy
import rosservice
import rostest
from std_msgs.msg import Float32
from std_srvs.srv import Trigger
from turtlesim.msg import Pose
from turtlesim.srv import TeleportAbsolute

from course_rospy import quick_exit
from course_format import causes
from course_milestones import discovery, guard, students
from course_milestones.milestone_case import MilestoneCase, failure
from course_milestones.trusted import TURTLESIM
from course_milestones.turning import TurnTracker, heading_error, wrap
from course_checks.artifacts import artifact_path, save_canvas
from course_checks.nodes import NodeProcess
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

SCRIPT = "my_node.py"  # task 8: rosrun my_pkg my_node.py
CENTRE = 5.544445
TOLERANCE = 0.15  # rad: "use a threshold for the proximity" (task 5)
OVERSHOOT = 0.6  # rad past the target while still turning: it will not stop there
STILL_POSES = 19  # ~0.3 s of poses with zero velocity
MIN_PATH = 0.05  # m the pen must travel during an arch (2 px): less is a turn in place, no arch
AWAY = [(2.5, 8.5, -2.0), (8.5, 2.5, 2.5)]  # where each arch's turtle is left before the request


@guard.judged  # a violation of the trust policy fails the test, first
class ArchMilestone(MilestoneCase):
    node = None
    drawer = None

    @classmethod
    def setUpClass(cls):
        cls.pkg = rospy.get_param("~pkg")
        cls.poses = TopicRecorder("/turtle1/pose", Pose)
        rospy.wait_for_service("/turtle1/teleport_absolute", 30)
        before = set(discovery.system_state())
        try:
            cls.node = NodeProcess.rosrun(cls.pkg, SCRIPT, log_path=artifact_path("my_node"),
                                          sandbox=students.run_sandbox())
        except FileNotFoundError:
            found = discovery.describe(discovery.list_executables(cls.pkg))
            raise failure(causes.finding(students.start_cause(cls.pkg), "no executable %s in package %s (found: %s): "
                                         "task 8 runs `rosrun %s %s`" % (SCRIPT, cls.pkg, found, cls.pkg, SCRIPT)))
        cls.drawer = discovery.wait_for_registration(
            before, lambda r: "/draw_arch" in r.subscribes and "/resume_drawing" in r.services
            and "/pause_drawing" in r.services and "/turtle1/cmd_vel" in r.publishes, 30, cls.node.running)
        if cls.drawer is None:
            cls.drawer = next(iter(discovery.new_nodes(before).values()), None)
        cls.draw = rospy.Publisher("/draw_arch", Float32, queue_size=10)

    @classmethod
    def tearDownClass(cls):
        save_canvas()
        if cls.node is not None:
            cls.node.end()

    # -- tasks 1-4, 6: what `rosnode info drawer` shows (task 8) ----------------------------------

    def registration(self):
        if self.drawer is None:
            self.fail(causes.finding(students.start_cause(self.pkg, [students.output_of(self.node)]),
                                     "%s registered no node (did it crash? see my_node.log)" % SCRIPT))
        return self.drawer

    def test_1_node_named_drawer(self):
        self.assertTrue(self.registration().node == "/drawer", causes.finding(
            "wrong_name", "task 1: name the node drawer (it registered as %s)" % self.registration().node))

    def test_2_subscribes_pose(self):
        self.assertTrue("/turtle1/pose" in self.registration().subscribes, causes.finding(
            "not_subscribed", "task 2: the node does not subscribe /turtle1/pose (it subscribes %s)"
            % (self.registration().subscribes,)))

    def test_3_draw_arch_topic(self):
        self.assertTrue("/draw_arch" in self.registration().subscribes,
                        causes.finding("not_subscribed", "task 3: the node does not subscribe /draw_arch"))
        kind = discovery.topic_types().get("/draw_arch")
        self.assertTrue(kind == "std_msgs/Float32",
                        causes.finding("wrong_type", "task 3: /draw_arch should carry std_msgs/Float32, not %s" % kind))

    def test_4_cmd_vel_publisher(self):
        self.assertTrue("/turtle1/cmd_vel" in self.registration().publishes,
                        causes.finding("not_published", "task 4: the node does not publish /turtle1/cmd_vel (it "
                                       "publishes %s)" % (self.registration().publishes,)))

    def test_6_services(self):
        for name in ("/pause_drawing", "/resume_drawing"):
            self.assertTrue(name in self.registration().services,
                            causes.finding("no_service", "task 6: the node offers no service %s" % name))
            kind = rosservice.get_service_type(name)
            self.assertTrue(kind == "std_srvs/Trigger",
                            causes.finding("wrong_type", "task 6: %s should be std_srvs/Trigger, not %s"
                                           % (name, kind)))

    # -- tasks 5, 7, 8: drawing --------------------------------------------------------------------

    def test_7_arches(self):
        self.registration()
        self.draw_arch(1.2, AWAY[0])
        self.draw_arch(3.8, AWAY[1], pause_after=1.0)

    def leave_turtle_at(self, x, y, theta):
        teleport = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
        teleport(x, y, theta)
        near = wait_for(lambda: self.poses.last is not None and math.hypot(self.poses.last.x - x,
                                                                           self.poses.last.y - y) < 0.01, 5)
        self.assertTrue(near, causes.finding("not_moving", "could not place turtle1 at (%.1f, %.1f) before the arch"
                                             % (x, y)))
        self.assertTrue(wait_for(self.still, 10),
                        causes.finding("not_moving", "turtle1 keeps moving before any /draw_arch request"))

    def still(self, count=STILL_POSES):
        recent = self.poses.messages[-count:]
        return len(recent) == count and all(abs(p.linear_velocity) < 1e-6 and abs(p.angular_velocity) < 1e-6
                                            for p in recent)

    def moving_since(self, index):
        return next((i for i, p in enumerate(self.poses.messages[index:], index)
                     if abs(p.linear_velocity) > 1e-6 or abs(p.angular_velocity) > 1e-6), None)

    def draw_arch(self, angle, away, pause_after=None):
        self.leave_turtle_at(*away)
        self.assertTrue(wait_for(lambda: self.draw.get_num_connections() > 0, 10),
                        causes.finding("not_subscribed", "nothing subscribes /draw_arch"))
        mark = self.poses.count
        self.draw.publish(Float32(angle))
        first = wait_for(lambda: self.moving_since(mark), 10)
        self.assertTrue(first is not None,
                        causes.finding("not_moving", "after /draw_arch %.2f the turtle did not start drawing" % angle))
        start = self.poses.messages[first]
        self.assertTrue(math.hypot(start.x - CENTRE, start.y - CENTRE) < 0.3,
                        causes.finding("wrong_value", "task 7: the arch of %.2f started where the turtle was left "
                                       "(%.2f, %.2f), not at the centre: call /reset before each arch"
                                       % (angle, start.x, start.y)))
        tracker = TurnTracker()
        index = first
        paused = False
        deadline = rospy.get_time() + angle / 0.1 + 20.0
        while rospy.get_time() < deadline:
            messages = self.poses.messages
            for pose in messages[index:]:
                tracker.feed(pose.theta)
            index = len(messages)
            if tracker.turned > angle + OVERSHOOT:
                self.fail(causes.finding("not_moving", "task 5: asked for an arch of %.2f rad, the turtle turned "
                                         "%.2f rad and did not stop" % (angle, tracker.turned)))
            if pause_after is not None and not paused and tracker.turned > pause_after:
                paused = True
                self.check_pause_and_resume(angle)
                continue
            if self.still() and tracker.turned > 0.05:
                break
            rospy.sleep(0.05)
        else:
            self.fail(causes.finding("not_moving", "task 5: the arch of %.2f rad did not end within %.0f s"
                                     % (angle, angle / 0.1 + 20.0)))
        travelled = path_length(self.poses.messages[first:])
        self.assertTrue(travelled >= MIN_PATH,
                        causes.finding("not_moving", "the arch of %.2f rad was not drawn: the turtle turned in place "
                                       "(it moved %.2f m); an arch needs a forward speed as well as a turn rate, "
                                       "like the skeleton's twist_msg.linear.x = 1 with angular.z = 0.5 (task 4)"
                                       % (angle, travelled)))
        theta = self.poses.last.theta
        self.assertTrue(heading_error(theta, angle) < TOLERANCE,
                        causes.finding("wrong_value", "task 5: the arch of %.2f rad stopped at heading %.2f, wanted "
                                       "%.2f (turned %.2f rad)" % (angle, theta, wrap(angle), tracker.turned)))

    def check_pause_and_resume(self, angle):
        pause = rospy.ServiceProxy("/pause_drawing", Trigger)
        resume = rospy.ServiceProxy("/resume_drawing", Trigger)
        self.assertTrue(pause().success,
                        causes.finding("wrong_answer", "task 6: /pause_drawing answered success=False"))
        self.assertTrue(wait_for(self.still, 5),
                        causes.finding("not_moving", "task 6: the turtle kept moving after /pause_drawing"))
        held = self.poses.last
        rospy.sleep(1.0)
        now = self.poses.last
        self.assertTrue(math.hypot(now.x - held.x, now.y - held.y) + abs(wrap(now.theta - held.theta)) < 0.02,
                        causes.finding("not_moving", "task 6: the turtle moved while paused"))
        self.assertTrue(resume().success,
                        causes.finding("wrong_answer", "task 6: /resume_drawing answered success=False"))
        mark = self.poses.count
        self.assertTrue(wait_for(lambda: self.moving_since(mark), 5) is not None,
                        causes.finding("not_moving", "task 6: the arch of %.2f did not go on after /resume_drawing"
                                       % angle))


def path_length(poses):
    """Metres the turtle travelled over consecutive poses (its pen's line)."""
    return sum(math.hypot(b.x - a.x, b.y - a.y) for a, b in zip(poses, poses[1:]))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("arch_check")
    guard.install([TURTLESIM])  # before any student code: believe only this simulator
    rostest.rosrun("course_milestones", "arch", ArchMilestone)
