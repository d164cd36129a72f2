#!/usr/bin/env python3
"""Milestone `backgrounds` (003 "ROS Parameters", task): with two_turtles.launch running, `roslaunch
two_turtles change_background_color.launch` gives turtlesim1 one background and turtlesim2
another. Read on the canvases themselves (each turtle's color_sensor sees the background under
it), not only in the parameters: turtlesim applies background_r/g/b on /clear (or /reset) only.
"""

import rospy
import rostest
from turtlesim.msg import Color

from course_rospy import quick_exit
from course_format import causes
import two_sims
from course_milestones import launch_files as lf
from course_milestones.milestone_case import MilestoneCase
from course_milestones.students import Roslaunch
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

CHANGE_FILE = "change_background_color.launch"


class BackgroundsMilestone(MilestoneCase):
    launches = []
    sims = {}

    @classmethod
    def setUpClass(cls):
        cls.pkg = rospy.get_param("~pkg")
        cls.sensors = {ns: TopicRecorder(ns + "/turtle1/color_sensor", Color) for ns in two_sims.NAMESPACES}
        cls.problem = lf.missing_launch_file(cls.pkg, two_sims.LAUNCH_FILE) or lf.missing_launch_file(cls.pkg, CHANGE_FILE)
        if cls.problem:
            return
        cls.launches.append(Roslaunch(cls.pkg, two_sims.LAUNCH_FILE, "roslaunch_two_turtles"))
        cls.sims = two_sims.wait_for_simulators(30)
        cls.problem = two_sims.missing_simulators(cls.sims)
        wait_for(lambda: all(r.last for r in cls.sensors.values()), 10)

    @classmethod
    def tearDownClass(cls):
        two_sims.save_canvases(cls.sims)
        for launch in reversed(cls.launches):
            launch.end()

    def shown(self, ns):
        return two_sims.colour_of(self.sensors[ns].last)

    def params(self, ns):
        node = self.sims[ns]
        try:
            return tuple(int(rospy.get_param("%s/background_%s" % (node, c))) for c in "rgb")
        except (KeyError, ValueError, TypeError):
            return None

    def test_change_background_color_launch(self):
        self.assertFalse(self.problem, self.problem)
        before = {ns: self.shown(ns) for ns in two_sims.NAMESPACES}
        self.assertTrue(all(before.values()),
                        causes.finding("wrong_launch", "no color_sensor from the turtles of two_turtles.launch"))
        self.launches.append(Roslaunch(self.pkg, CHANGE_FILE, "roslaunch_change_background_color"))

        def both_changed():
            now = {ns: self.shown(ns) for ns in two_sims.NAMESPACES}
            return all(now[ns] != before[ns] for ns in now) and len(set(now.values())) == 2
        wait_for(both_changed, 10)
        for ns in two_sims.NAMESPACES:
            wanted = self.params(ns)
            shown = self.shown(ns)
            if shown == before[ns] and wanted is not None and wanted != shown:
                self.fail(causes.finding("param_ignored", "%s's parameters say background %s but its canvas still "
                                         "shows %s: a parameter change takes effect only when the launch file also "
                                         "calls %s/clear" % (ns, wanted, shown, ns)))
            self.assertTrue(shown != before[ns], causes.finding(
                "wrong_launch", "%s's background did not change (still %s; %s/background_r/g/b = %s)"
                % (ns, shown, self.sims[ns], wanted)))
        self.assertTrue(self.shown("/turtlesim1") != self.shown("/turtlesim2"), causes.finding(
            "wrong_value", "both simulators show the same background %s: the text asks for another colour for "
            "turtlesim2" % (self.shown("/turtlesim1"),)))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("backgrounds_check")
    rostest.rosrun("course_milestones", "backgrounds", BackgroundsMilestone)
