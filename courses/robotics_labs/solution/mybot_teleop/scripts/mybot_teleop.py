#!/usr/bin/env python3
"""mybot_teleop: arrow keys -> geometry_msgs/Twist (UPMC part 1, parts A and C).

Params (checked with has_param, as in the text): linear_scale (2.0),
angular_scale (2.0), cmd_vel_topic_name (turtle1/cmd_vel); private
~publish_mode ("on_key" or "continuous") and ~rate (10 Hz, continuous mode).
Keys: arrows move, s stops, q quits.
"""
import sys

import rospy
from geometry_msgs.msg import Twist

from course_keyboard.terminal import NotATerminal, RawTerminal
from mybot_teleop_core.commands import ON_KEY, TeleopCommands, Velocity
from mybot_teleop_core.keys import KeyDecoder


def param_or_default(name, default):
    """The text's pattern: use the parameter if the server has it, else a default."""
    if rospy.has_param(name):
        return rospy.get_param(name)
    return default


def to_twist(velocity: Velocity) -> Twist:
    message = Twist()
    message.linear.x = velocity.linear
    message.angular.z = velocity.angular
    return message


def main() -> int:
    rospy.init_node("mybot_teleop", anonymous=False)
    linear_scale = float(param_or_default("linear_scale", 2.0))
    angular_scale = float(param_or_default("angular_scale", 2.0))
    topic_name = param_or_default("cmd_vel_topic_name", "turtle1/cmd_vel")
    try:
        commands = TeleopCommands(linear_scale, angular_scale, rospy.get_param("~publish_mode", ON_KEY))
    except ValueError as err:
        rospy.logerr(str(err))
        return 2
    period = 1.0 / max(float(rospy.get_param("~rate", 10.0)), 0.1)
    pub = rospy.Publisher(topic_name, Twist, queue_size=10)
    decoder = KeyDecoder()
    try:
        with RawTerminal(program="mybot_teleop") as terminal:  # raw mode before the prompt
            print("Command sent to " + pub.resolved_name)
            print("Use the arrow keys to move, 's' to stop, 'q' to quit (%s mode)." % commands.mode, flush=True)
            next_tick = rospy.get_time() + period
            while not rospy.is_shutdown() and not commands.quit:
                try:
                    data = terminal.read(min(period, 0.1))
                except EOFError:
                    break
                for key in decoder.feed(data):
                    velocity = commands.on_key(key)
                    if velocity is not None:
                        pub.publish(to_twist(velocity))
                    if commands.quit:
                        break
                if rospy.get_time() >= next_tick:
                    next_tick += period
                    velocity = commands.on_tick()
                    if velocity is not None:
                        pub.publish(to_twist(velocity))
    except NotATerminal as err:
        rospy.logfatal(str(err))
        return 1
    except rospy.ROSInterruptException:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
