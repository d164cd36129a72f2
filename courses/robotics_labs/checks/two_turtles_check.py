#!/usr/bin/env python3
"""Milestone `two_turtles` (003 "Launch Files", task): `roslaunch two_turtles two_turtles.launch`
brings up two turtlesims (groups turtlesim1 and turtlesim2), one teleop publishing
/turtle1/cmd_vel, and two relays from /turtle1/cmd_vel to each simulator's velocity topic;
"Play with the arrows and make sure that the two turtles are moving together".

The launch file runs on a pseudo-terminal, so its turtle_teleop_key reads the arrows we press.
"""
import math

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from course_rospy import quick_exit
from course_format import causes
from course_milestones import discovery
import two_sims
from course_milestones import launch_files as lf
from course_milestones.milestone_case import MilestoneCase
from course_milestones.students import Roslaunch
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

COMMAND_TOPIC = "/turtle1/cmd_vel"


class TwoTurtlesMilestone(MilestoneCase):
    launch = None
    sims = {}

    @classmethod
    def setUpClass(cls):
        cls.pkg = rospy.get_param("~pkg")
        cls.poses = {ns: TopicRecorder(ns + "/turtle1/pose", Pose) for ns in two_sims.NAMESPACES}
        cls.problem = lf.missing_launch_file(cls.pkg, two_sims.LAUNCH_FILE)
        if cls.problem:
            return
        cls.launch = Roslaunch(cls.pkg, two_sims.LAUNCH_FILE, "roslaunch_two_turtles")
        cls.sims = two_sims.wait_for_simulators(30)
        cls.problem = two_sims.missing_simulators(cls.sims)
        wait_for(lambda: all(r.last for r in cls.poses.values()), 10)

    @classmethod
    def tearDownClass(cls):
        two_sims.save_canvases(cls.sims)
        if cls.launch is not None:
            cls.launch.end()

    def setUp(self):
        self.assertFalse(self.problem, self.problem)

    def moved(self, start, ns, distance=0.3):
        now = self.poses[ns].last
        return math.hypot(now.x - start[ns].x, now.y - start[ns].y) > distance

    def diagnosis(self, start):
        """Which turtles moved, and where the relays send /turtle1/cmd_vel."""
        moved = [ns + "/turtle1" for ns in two_sims.NAMESPACES if self.moved(start, ns)]
        relays = [r for r in two_sims.readers_of(COMMAND_TOPIC, rospy.get_name()) if r.node not in self.sims.values()]
        outputs = sorted({t for r in relays for t in r.publishes if t != "/rosout"})
        return ("a Twist on /turtle1/cmd_vel moved %s; %d relay node(s) read /turtle1/cmd_vel (%s) and publish to %s; "
                "the turtles listen on %s" % (" and ".join(moved) if moved else "no turtle", len(relays),
                                              ", ".join(r.node for r in relays) or "none", ", ".join(outputs) or
                                              "nothing", " and ".join(ns + "/turtle1/cmd_vel"
                                                                      for ns in two_sims.NAMESPACES)))

    def test_1_relays_move_both_turtles(self):
        start = {ns: r.last for ns, r in self.poses.items()}
        pub = rospy.Publisher(COMMAND_TOPIC, Twist, queue_size=1)
        twist = Twist()
        twist.linear.x, twist.angular.z = 2.0, 1.0

        def both_moved():
            pub.publish(twist)
            return all(self.moved(start, ns) for ns in two_sims.NAMESPACES)
        ok = wait_for(both_moved, 10, interval=0.1)
        self.assertTrue(ok, causes.finding("wrong_launch", self.diagnosis(start)))

        def same_command():  # each pose reports the command its turtle runs; both relays need a moment
            pub.publish(twist)
            return all(abs(p.linear_velocity - twist.linear.x) < 1e-3 and abs(p.angular_velocity - twist.angular.z)
                       < 1e-3 for p in (self.poses[ns].last for ns in two_sims.NAMESPACES))
        same = wait_for(same_command, 5, interval=0.1)
        a, b = (self.poses[ns].last for ns in two_sims.NAMESPACES)
        pub.publish(Twist())
        self.assertTrue(same, causes.finding(
            "wrong_launch", "the two turtles got different commands from one Twist (%s/%s, published for 5 s): "
            "%s/%s and %s/%s" % (twist.linear.x, twist.angular.z, a.linear_velocity, a.angular_velocity,
                                 b.linear_velocity, b.angular_velocity)))
        relays = [r for r in two_sims.readers_of(COMMAND_TOPIC, rospy.get_name()) if r.node not in self.sims.values()]
        self.assertTrue(len(relays) >= 2, causes.finding(
            "wrong_launch", "the text asks for two relay nodes reading /turtle1/cmd_vel, found %s"
            % (", ".join(r.node for r in relays) or "none")))

    def test_2_arrows_move_both_turtles(self):
        teleop = wait_for(lambda: [n for n, r in discovery.system_state().items()
                                   if COMMAND_TOPIC in r.publishes and n != rospy.get_name()], 10,
                          discovery.MASTER_POLL_S)
        self.assertTrue(teleop, causes.finding("wrong_launch", "no node of the launch file publishes /turtle1/cmd_vel: "
                                               "add the teleop node (turtlesim's turtle_teleop_key)"))
        start = {ns: r.last for ns, r in self.poses.items()}
        moved = self.launch.press_until("up", lambda: all(self.moved(start, ns, 0.5) for ns in two_sims.NAMESPACES),
                                        tries=6)
        self.assertTrue(moved, causes.finding("wrong_launch", "pressing 'up' in the launch terminal did not move both "
                                              "turtles: " + self.diagnosis(start).replace("a Twist on /turtle1/cmd_vel",
                                                                                          "the teleop")))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("two_turtles_check")
    rostest.rosrun("course_milestones", "two_turtles", TwoTurtlesMilestone)
