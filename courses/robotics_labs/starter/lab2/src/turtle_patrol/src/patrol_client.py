#!/usr/bin/env python3
"""patrol_client.py: asks turtle1 to patrol a circle (vel 2.0, omega 1.0) through /turtle1/patrol.
Handed out as an example of calling a service: the lab does not edit it."""
import rospy

from turtle_patrol.srv import Patrol


def main() -> None:
    rospy.init_node("patrol_client")
    rospy.wait_for_service("/turtle1/patrol")
    try:
        response = rospy.ServiceProxy("/turtle1/patrol", Patrol)(2.0, 1.0)
    except rospy.ServiceException as err:
        rospy.logerr("patrol call failed: %s", err)
        return
    print(response.cmd)


if __name__ == "__main__":
    main()
