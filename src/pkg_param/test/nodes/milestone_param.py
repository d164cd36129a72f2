#!/usr/bin/env python3
"""Seed 004 (parameters): param_demo logs `Hello muto!`, then `Hello robot!` after
`rosparam set /param_demo/robot_name robot`; `rosparam dump` / `load` restores a value."""
import os
import subprocess
import tempfile
import unittest

import rospy
import rostest

from course_testkit.recorders import RosoutRecorder
from course_testkit.waiting import wait_for


class ParamMilestone(unittest.TestCase):
    def test_set_dump_load(self):
        log = RosoutRecorder()
        self.assertTrue(wait_for(lambda: log.matching(r"^Hello muto!$"), 15), "no `Hello muto!`")
        subprocess.run(["rosparam", "set", "/param_demo/robot_name", "robot"], check=True, timeout=20)
        self.assertTrue(wait_for(lambda: log.matching(r"^Hello robot!$"), 10), "the change was not picked up")
        dump = os.path.join(tempfile.mkdtemp(), "params.yaml")
        subprocess.run(["rosparam", "dump", dump, "/param_demo"], check=True, timeout=20)
        subprocess.run(["rosparam", "set", "/param_demo/robot_name", "other"], check=True, timeout=20)
        self.assertTrue(wait_for(lambda: log.matching(r"^Hello other!$"), 10))
        subprocess.run(["rosparam", "load", dump, "/param_demo"], check=True, timeout=20)
        self.assertEqual(rospy.get_param("/param_demo/robot_name"), "robot")
        count = len(log.matching(r"^Hello robot!$"))
        self.assertTrue(wait_for(lambda: len(log.matching(r"^Hello robot!$")) > count, 10))


if __name__ == "__main__":
    rospy.init_node("milestone_param")
    rostest.rosrun("pkg_param", "milestone_param", ParamMilestone)
