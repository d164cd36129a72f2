#!/usr/bin/env python3
"""spawn_two_server.py: offers the service /spawn_two (turtle_motions/SpawnTwo): two turtles spawned
in turtlesim at (x1, y1) and (x2, y2), heading 0, with the names turtlesim gives them, answered."""
import rospy
from turtlesim.srv import Spawn

from turtle_motions.srv import SpawnTwo, SpawnTwoResponse


class SpawnTwoServer:
    def __init__(self):
        rospy.wait_for_service("/spawn")
        self.spawn = rospy.ServiceProxy("/spawn", Spawn)
        rospy.Service("/spawn_two", SpawnTwo, self.handle)

    def handle(self, request):
        first = self.spawn(request.x1, request.y1, 0.0, "").name
        second = self.spawn(request.x2, request.y2, 0.0, "").name
        rospy.loginfo("spawned %s at (%g, %g) and %s at (%g, %g)", first, request.x1, request.y1, second,
                      request.x2, request.y2)
        return SpawnTwoResponse(first, second)


def main():
    rospy.init_node("spawn_two_server")
    SpawnTwoServer()
    rospy.spin()


if __name__ == "__main__":
    main()
