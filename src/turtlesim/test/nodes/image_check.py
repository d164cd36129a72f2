#!/usr/bin/env python3
"""~image streams the rendered canvas only while subscribed; ~snapshot writes a PNG of it; ~scene
and ~canvas give the lab page the canvas as drawing commands and a snapshot (turtlesim.scene)."""
import base64
import json
import os
import unittest
import xmlrpc.client

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import rosgraph
import rospy
import rostest
from PyQt5.QtGui import QImage
from PyQt5.QtWidgets import QApplication
from sensor_msgs.msg import Image
from std_msgs.msg import String
from std_srvs.srv import Trigger

from turtlesim.constants import DEFAULT_BACKGROUND_RGB, METER_PX, WORLD_SIZE
from turtlesim.srv import SetPen, TeleportAbsolute
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for
from course_testkit.tcpros import node_api


def pixel(msg: Image, x: int, y: int):
    i = y * msg.step + x * 3
    return tuple(bytearray(msg.data[i:i + 3]))


def turtlesim_sends_to_us(topic: str) -> bool:
    """Whether turtlesim itself lists our subscriber on `topic` (its bus info). Our side counts the
    connection a moment before turtlesim does, and turtlesim records ~scene's lines only while it
    counts a subscriber: a line drawn in between never comes."""
    me = rospy.get_caller_id()
    _, _, info = xmlrpc.client.ServerProxy(node_api(rosgraph.get_master_uri(), "/turtlesim")).getBusInfo(me)
    return any(c[1] == me and c[2] == "o" and c[4] == topic for c in info)


def green_line(msg: String) -> bool:
    """A ~scene update holding the green line of test_scene_tells_... (pen 0 255 0, width 4, x 90 -> 270)."""
    return any(s[:4] == [0, 255, 0, 4] and s[4] == 90.0 and s[6] == 270.0 for s in json.loads(msg.data)["strokes"])


class TurtlesimImage(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.app = QApplication.instance() or QApplication([])
        rospy.init_node("turtlesim_image_check")
        # turtle1's services come after the node's own (~snapshot, ~canvas): wait for those we call.
        for service in ("/turtlesim/snapshot", "/turtlesim/canvas", "/turtle1/set_pen", "/turtle1/teleport_absolute"):
            rospy.wait_for_service(service, 20)

    def test_image_shows_background_paths_and_turtle(self):
        teleport = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
        rospy.ServiceProxy("/turtle1/set_pen", SetPen)(255, 0, 0, 5, 0)
        teleport(1.0, 1.0, 0.0)
        teleport(4.0, 1.0, 0.0)
        image = TopicRecorder("/turtlesim/image", Image)
        msg = image.wait(lambda m: pixel(m, 90, 454) == (255, 0, 0), timeout=10)
        self.assertIsNotNone(msg, "the red path should show in the image")
        self.assertEqual((msg.width, msg.height, msg.encoding, msg.step), (500, 500, "rgb8", 1500))
        self.assertEqual(pixel(msg, 5, 5), DEFAULT_BACKGROUND_RGB)
        self.assertNotEqual(pixel(msg, 180, 454), DEFAULT_BACKGROUND_RGB, "the turtle icon is drawn")
        image.unregister()

    def test_image_topic_is_advertised_and_streams(self):
        master = rosgraph.Master("/image_check")
        self.assertIn("/turtlesim/image", dict(master.getSystemState()[0]))
        image = TopicRecorder("/turtlesim/image", Image)
        self.assertIsNotNone(image.wait(timeout=10))
        image.unregister()

    def test_scene_tells_the_lines_and_canvas_gives_the_whole_picture(self):
        scene = TopicRecorder("/turtlesim/scene", String)
        self.assertTrue(wait_for(lambda: turtlesim_sends_to_us("/turtlesim/scene"), 10),
                        "turtlesim should connect ~scene to our subscriber")
        teleport = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
        rospy.ServiceProxy("/turtle1/set_pen", SetPen)(0, 255, 0, 4, 0)
        teleport(2.0, 8.0, 0.0)
        teleport(6.0, 8.0, 0.0)  # a green line 4 m long at y = 8 m
        green = wait_for(lambda: next((m for m in scene.messages if green_line(m)), None), 10)
        self.assertIsNotNone(green, "the green line should come as a stroke on ~scene: %s" % scene.messages[-3:])
        update = json.loads(green.data)
        self.assertEqual([t[0] for t in update["turtles"]], ["turtle1"])
        snapshot = json.loads(rospy.ServiceProxy("/turtlesim/canvas", Trigger)().message)
        self.assertGreaterEqual(snapshot["seq"], update["seq"])
        self.assertEqual(snapshot["run"], update["run"])
        paths = QImage.fromData(base64.b64decode(snapshot["paths"]), "PNG")
        colour = paths.pixelColor(180, round((WORLD_SIZE - 8.0) * METER_PX))
        self.assertEqual((colour.red(), colour.green(), colour.blue()), (0, 255, 0))
        scene.unregister()

    @staticmethod
    def _remove(path: str) -> None:
        if path.endswith(".png") and os.path.isfile(path):
            os.remove(path)

    def test_snapshot_writes_a_png_and_answers_its_path(self):
        answer = rospy.ServiceProxy("/turtlesim/snapshot", Trigger)()
        self.assertTrue(answer.success, answer.message)
        self.addCleanup(self._remove, answer.message)  # the node's default folder: leave nothing there
        self.assertTrue(os.path.isfile(answer.message), answer.message)
        self.assertTrue(answer.message.endswith(".png"))
        png = QImage(answer.message)
        self.assertEqual((png.width(), png.height()), (500, 500))
        corner = png.pixelColor(2, 2)
        self.assertEqual((corner.red(), corner.green(), corner.blue()), DEFAULT_BACKGROUND_RGB)
        second = rospy.ServiceProxy("/turtlesim/snapshot", Trigger)()
        self.addCleanup(self._remove, second.message)
        self.assertNotEqual(second.message, answer.message, "each snapshot gets its own file")


if __name__ == "__main__":
    rostest.rosrun("turtlesim", "turtlesim_image", TurtlesimImage)
