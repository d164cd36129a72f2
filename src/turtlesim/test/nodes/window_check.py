#!/usr/bin/env python3
"""On a display, turtlesim_node shows a window with the canvas: background, paths and turtles."""
import json
import os
import subprocess
import unittest

import rospy
import rostest
from course_testkit.screen import VirtualDisplay, grab_screen

from turtlesim.srv import SetPen, TeleportAbsolute


class TurtlesimWindow(unittest.TestCase):
    def test_window_shows_the_canvas(self):
        with VirtualDisplay(size=(800, 600)) as display:
            env = dict(os.environ, DISPLAY=display.display, QT_QPA_PLATFORM="xcb")
            sim = subprocess.Popen(["rosrun", "turtlesim", "turtlesim_node", "__name:=turtlesim"], env=env)
            self.addCleanup(lambda: (sim.terminate(), sim.wait(10)))
            rospy.init_node("turtlesim_window_check")
            rospy.wait_for_service("/turtle1/teleport_absolute", 30)
            rospy.ServiceProxy("/turtle1/set_pen", SetPen)(255, 0, 0, 8, 0)
            teleport = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
            teleport(1.0, 1.0, 0.0)
            teleport(10.0, 1.0, 0.0)
            shot = os.path.join(os.environ.get("ROS_HOME", "/tmp"), "turtlesim_window.png")
            stats = None
            for _attempt in range(50):  # the window maps and paints asynchronously
                stats = json.loads(grab_screen(display.display, shot))
                if stats["reddish"] > 100 and stats["distinct"] > 5:
                    break
                rospy.sleep(0.2)
            self.assertGreater(stats["reddish"], 100, "the red path should be on screen: %s" % stats)
            self.assertFalse(stats["blank"], stats)


if __name__ == "__main__":
    rostest.rosrun("turtlesim", "turtlesim_window", TurtlesimWindow)
