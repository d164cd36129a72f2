#!/usr/bin/env python
import sys
import rospy
from turtle_patrol.srv import Patrol


def patrol_client(name):
    rospy.init_node(name + '_patrol_client')
    rospy.wait_for_service('/' + name + '/patrol')
    try:
        patrol_proxy = rospy.ServiceProxy('/' + name + '/patrol', Patrol)
        rospy.loginfo('Command ' + name + ' to patrol')
        patrol_proxy(2.0, 1.0, 5.5, 5.5, 0.0)
    except rospy.ServiceException as e:
        rospy.loginfo(e)


if __name__ == '__main__':
    patrol_client(sys.argv[1] if len(sys.argv) > 1 else 'turtle1')
