#!/usr/bin/env python3
"""turtle_controller.py TURTLE_NAME: arrow keys drive /TURTLE_NAME/cmd_vel (Lab 2, section 4).

One message per key press, like turtle_teleop_key (up/down: +-~linear_speed, left/right:
+-~angular_speed, both 2.0); s stops the turtle, q stops it and quits. Run one controller
per turtle, each in its own terminal. The keyboard (raw terminal, escape sequences, the
arrows' map) is the course library course_keyboard.
"""
import sys
from typing import Optional, Tuple

import rospy
from geometry_msgs.msg import Twist

from course_keyboard.decoder import KeyDecoder
from course_keyboard.drive import arrow_velocity
from course_keyboard.terminal import NotATerminal, RawTerminal

STOP_KEYS, QUIT_KEYS = ("s", "S"), ("q", "Q")


def command_for(key: str, linear_speed: float, angular_speed: float) -> Optional[Tuple[float, float]]:
    """(linear, angular) to publish for a key: an arrow's move, zero for s and q; None for other keys."""
    if key in STOP_KEYS or key in QUIT_KEYS:
        return 0.0, 0.0
    return arrow_velocity(key, linear_speed, angular_speed)


def main() -> int:
    args = rospy.myargv(sys.argv)[1:]
    if len(args) != 1:
        print("usage: rosrun lab2_turtlesim turtle_controller.py TURTLE_NAME")
        return 2
    turtle = args[0]
    rospy.init_node("turtle_controller_" + turtle.strip("/").replace("/", "_"))
    linear_speed = float(rospy.get_param("~linear_speed", 2.0))
    angular_speed = float(rospy.get_param("~angular_speed", 2.0))
    pub = rospy.Publisher("/%s/cmd_vel" % turtle.strip("/"), Twist, queue_size=10)
    decoder = KeyDecoder()
    try:
        with RawTerminal(program="turtle_controller.py") as terminal:  # raw mode before the prompt
            print("Controlling %s: arrow keys move, q quits." % turtle, flush=True)
            while not rospy.is_shutdown():
                try:
                    data = terminal.read(0.1)
                except EOFError:
                    break
                for key in decoder.feed(data):
                    command = command_for(key, linear_speed, angular_speed)
                    if command is not None:
                        twist = Twist()
                        twist.linear.x, twist.angular.z = command
                        pub.publish(twist)
                    if key in QUIT_KEYS:
                        return 0
    except NotATerminal as err:
        rospy.logfatal(str(err))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
