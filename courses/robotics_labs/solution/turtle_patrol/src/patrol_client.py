#!/usr/bin/env python3
"""patrol_client.py [TURTLE [VEL OMEGA [X Y THETA]]]: asks TURTLE (turtle1) to patrol a circle.

Defaults: vel 2.0, omega 1.0, starting at the centre (5.54, 5.54) heading 0.
"""
import sys

import rospy

from turtle_patrol.srv import Patrol

DEFAULTS = ["turtle1", 2.0, 1.0, 5.544445, 5.544445, 0.0]


def main() -> int:
    args = rospy.myargv(sys.argv)[1:]
    if len(args) not in (0, 1, 3, 6):
        print(__doc__)
        return 2
    turtle = args[0] if args else DEFAULTS[0]
    numbers = [float(a) for a in args[1:]] + DEFAULTS[1 + len(args[1:]):]
    rospy.init_node("patrol_client", anonymous=True)
    name = "/%s/patrol" % turtle
    rospy.wait_for_service(name)
    try:
        response = rospy.ServiceProxy(name, Patrol)(*numbers)
    except rospy.ServiceException as err:
        rospy.logerr("patrol call failed: %s" % err)
        return 1
    print(response.cmd)
    return 0


if __name__ == "__main__":
    sys.exit(main())
