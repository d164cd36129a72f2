#!/usr/bin/env python3
"""Milestone `graph_picture` (003 Part I, task 3): with turtlesim, `rosrun turtlesim turtle_teleop_key`
and `rostopic echo /turtle1/cmd_vel` running, the rqt_graph picture shows the velocity topic
twice: "Can you see two arrows with the same topic name?". Debian has no rqt_graph: the course's
`rosrun course_graph rqt_graph -o FILE` writes the picture (PNG, SVG, PDF or DOT).

This milestone checks the course workspace (the picture tool), not a student package.
"""
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import rospy
import rostest
from geometry_msgs.msg import Twist

from course_rospy import quick_exit
from course_format import causes
from course_milestones.milestone_case import MilestoneCase
from course_checks.artifacts import artifact_path
from course_checks.keyboard import PtyKeyboard
from course_checks.nodes import NodeProcess
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

TOPIC = "/turtle1/cmd_vel"


def rqt_graph(*args):
    return subprocess.run(["rosrun", "course_graph", "rqt_graph", *args], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, timeout=60)


class GraphPictureMilestone(MilestoneCase):
    failure_cause = "course_tools"  # the course's own tools: unittest's words, this cause
    teleop = None
    echo = None

    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix="graph_picture-"))
        commands = TopicRecorder(TOPIC, Twist)
        cls.teleop = PtyKeyboard.rosrun("turtlesim", "turtle_teleop_key", log_path=artifact_path("teleop"))
        cls.echo = NodeProcess(["rostopic", "echo", TOPIC], log_path=artifact_path("rostopic_echo"))
        # "play with the arrows": a command the echo prints
        cls.teleop.press_until("up", lambda: commands.count > 0, tries=10)
        commands.unregister()  # the picture shows the text's nodes only
        dot = cls.tmp / "settled.dot"

        def settled():
            return rqt_graph("-o", str(dot)).returncode == 0 and len(cls.subscribers(dot.read_text())) >= 2
        wait_for(settled, 30, interval=0.5)

    @classmethod
    def tearDownClass(cls):
        for proc in (cls.echo, cls.teleop):
            if proc is not None:
                proc.end()
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @staticmethod
    def subscribers(dot):
        return re.findall(r'"%s" -> "([^"]+)";' % re.escape(TOPIC), dot)

    def test_two_arrows_out_of_the_velocity_topic(self):
        dot_path = self.tmp / "task3.dot"
        out = rqt_graph("-o", str(dot_path))
        self.assertTrue(out.returncode == 0, causes.finding("course_tools", "rqt_graph failed: %s" % out.stderr))
        dot = dot_path.read_text()
        self.assertTrue('"/teleop_turtle" -> "%s";' % TOPIC in dot,
                        causes.finding("course_tools", "no arrow /teleop_turtle -> %s" % TOPIC))
        readers = self.subscribers(dot)
        self.assertTrue("/turtlesim" in readers and any(r.startswith("/rostopic") for r in readers),
                        causes.finding("course_tools", "%s should have two arrows, to /turtlesim and to the rostopic "
                                       "echo node; it has: %s" % (TOPIC, ", ".join(readers) or "none")))

    def test_png_for_the_report(self):
        path = artifact_path("rqt_graph", ".png")
        out = rqt_graph("-o", path)
        self.assertTrue(out.returncode == 0, causes.finding("course_tools", out.stderr))
        self.assertTrue(out.stdout.strip() == path,
                        causes.finding("course_tools", "rqt_graph should print the picture's path"))
        self.assertTrue(Path(path).read_bytes().startswith(b"\x89PNG"), causes.finding("course_tools", "not a PNG"))

    def test_svg_names_the_nodes_and_the_topic(self):
        out = rqt_graph("-o", str(self.tmp / "g.svg"))
        self.assertTrue(out.returncode == 0, causes.finding("course_tools", out.stderr))
        svg = (self.tmp / "g.svg").read_text()
        for name in ("/teleop_turtle", "/turtlesim", TOPIC):
            self.assertTrue(name in svg, causes.finding("course_tools", "%s missing from the SVG" % name))

    def test_views(self):
        out = rqt_graph("--nodes-only", "-o", str(self.tmp / "n.dot"))
        self.assertTrue(out.returncode == 0, causes.finding("course_tools", out.stderr))
        nodes_only = (self.tmp / "n.dot").read_text()
        self.assertTrue("/teleop_turtle" in nodes_only and "shape=box" not in nodes_only,
                        causes.finding("course_tools", nodes_only))
        out = rqt_graph("--ns", "/turtle1", "-o", str(self.tmp / "ns.dot"))
        self.assertTrue(out.returncode == 0, causes.finding("course_tools", out.stderr))
        in_ns = (self.tmp / "ns.dot").read_text()
        self.assertTrue(TOPIC in in_ns and "/teleop_turtle" not in in_ns, causes.finding("course_tools", in_ns))

    def test_bad_extension_is_a_clear_error(self):
        out = rqt_graph("-o", str(self.tmp / "g.jpg"))
        self.assertTrue(out.returncode == 2 and "use one of the extensions" in out.stderr,
                        causes.finding("course_tools", out.stderr))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("graph_picture_check")
    rostest.rosrun("course_milestones", "graph_picture", GraphPictureMilestone)
