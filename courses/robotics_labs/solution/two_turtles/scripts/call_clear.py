#!/usr/bin/env python3
"""call_clear.py SERVICE...: wait for each std_srvs/Empty service (e.g. /turtlesim1/clear), call it once, exit.

Used by change_background_color.launch: turtlesim reads its background params only on clear.
"""
import sys

import rospy
from std_srvs.srv import Empty


def main() -> int:
    services = rospy.myargv(sys.argv)[1:]
    if not services:
        print("usage: call_clear.py SERVICE [SERVICE...]")
        return 2
    rospy.init_node("call_clear", anonymous=True)
    failed = 0
    for name in services:
        try:
            rospy.wait_for_service(name, timeout=30)
            rospy.ServiceProxy(name, Empty)()
            rospy.loginfo("called %s" % name)
        except (rospy.ROSException, rospy.ServiceException) as err:
            rospy.logerr("could not call %s: %s" % (name, err))
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
