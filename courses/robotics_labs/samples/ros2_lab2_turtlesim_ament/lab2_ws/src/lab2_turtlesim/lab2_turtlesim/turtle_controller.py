"""ros2 run lab2_turtlesim turtle_controller TURTLE: w/s drive the turtle forward/backward, a/d turn it."""
import sys

import rclpy
from geometry_msgs.msg import Twist
from rclpy.node import Node

MOVES = {'w': (2.0, 0.0), 's': (-2.0, 0.0), 'a': (0.0, 2.0), 'd': (0.0, -2.0)}


class TurtleController(Node):

    def __init__(self, turtle):
        super().__init__(turtle + '_controller')
        self.cmd = self.create_publisher(Twist, '/' + turtle + '/cmd_vel', 10)

    def send(self, key):
        if key not in MOVES:
            return
        twist = Twist()
        twist.linear.x, twist.angular.z = MOVES[key]
        self.cmd.publish(twist)


def main():
    rclpy.init(args=sys.argv)
    args = rclpy.utilities.remove_ros_args(sys.argv)
    node = TurtleController(args[1] if len(args) > 1 else 'turtle1')
    try:
        for line in sys.stdin:
            for key in line.strip():
                node.send(key)
    except KeyboardInterrupt:
        pass
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
