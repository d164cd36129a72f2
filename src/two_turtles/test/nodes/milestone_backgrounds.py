#!/usr/bin/env python3
"""After change_background_color.launch the two canvases show different backgrounds, each the
one its parameters ask for (read back through the colour under the idle turtle)."""
import unittest

import rospy
import rostest
from turtlesim.msg import Color

from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for

NAMESPACES = ("/turtlesim1", "/turtlesim2")
DEFAULT = (69, 86, 255)


class BackgroundsMilestone(unittest.TestCase):
    def test_backgrounds_differ(self):
        sensors = {ns: TopicRecorder(ns + "/turtle1/color_sensor", Color) for ns in NAMESPACES}
        wanted = {}
        for ns in NAMESPACES:
            self.assertTrue(wait_for(lambda: rospy.has_param(ns + "/turtlesim/background_r"), 20))
            wanted[ns] = tuple(int(rospy.get_param("%s/turtlesim/background_%s" % (ns, c))) for c in "rgb")
        self.assertNotEqual(wanted["/turtlesim1"], wanted["/turtlesim2"], "both backgrounds set alike")

        def shown(ns):
            m = sensors[ns].last
            return m is not None and (m.r, m.g, m.b) == wanted[ns]
        for ns in NAMESPACES:
            self.assertTrue(wait_for(lambda: shown(ns), 30),
                            "%s shows %s, params say %s" % (ns, sensors[ns].last, wanted[ns]))
        self.assertTrue(any(w != DEFAULT for w in wanted.values()), "nothing changed from the default")


if __name__ == "__main__":
    rospy.init_node("milestone_backgrounds")
    rostest.rosrun("two_turtles", "milestone_backgrounds", BackgroundsMilestone)
