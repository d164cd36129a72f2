#!/usr/bin/env python3
"""turtle_controller.py TURTLE_NAME: arrow keys drive /TURTLE_NAME/cmd_vel (Lab 2, section 4).

One message per key press, like turtle_teleop_key (up/down: +-~linear_speed, left/right:
+-~angular_speed, both 2.0); q quits. Run one controller per turtle, each in its own terminal.
The keyboard handling (raw terminal, escape sequences) is shared with mybot_teleop.
"""
import sys

import rospy
from geometry_msgs.msg import Twist

from mybot_teleop_core.commands import TeleopCommands
from mybot_teleop_core.keys import KeyDecoder
from turtlesim.keyboard import NotATerminal, RawTerminal


def main() -> int:
    args = rospy.myargv(sys.argv)[1:]
    if len(args) != 1:
        print("usage: rosrun lab2_turtlesim turtle_controller.py TURTLE_NAME")
        return 2
    turtle = args[0]
    rospy.init_node("turtle_controller_" + turtle.strip("/").replace("/", "_"))
    commands = TeleopCommands(float(rospy.get_param("~linear_speed", 2.0)),
                              float(rospy.get_param("~angular_speed", 2.0)))
    pub = rospy.Publisher("/%s/cmd_vel" % turtle.strip("/"), Twist, queue_size=10)
    decoder = KeyDecoder()
    try:
        with RawTerminal(program="turtle_controller.py") as terminal:  # raw mode before the prompt
            print("Controlling %s: arrow keys move, q quits." % turtle, flush=True)
            while not rospy.is_shutdown() and not commands.quit:
                try:
                    data = terminal.read(0.1)
                except EOFError:
                    break
                for key in decoder.feed(data):
                    velocity = commands.on_key(key)
                    if velocity is not None:
                        twist = Twist()
                        twist.linear.x, twist.angular.z = velocity.linear, velocity.angular
                        pub.publish(twist)
    except NotATerminal as err:
        rospy.logfatal(str(err))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
