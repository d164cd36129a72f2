#!/usr/bin/env python3
"""A student's node that fakes the simulator, for trust_guard.test (course_milestones.guard).

    fake_simulator.py --name NODE [--pose TOPIC]... [--teleport SERVICE]... [--snapshot SERVICE --path FILE]

publishes turtlesim/Pose messages at x = y = FAKE_X on each --pose topic (100 Hz), offers
turtlesim/TeleportAbsolute under each --teleport name and std_srvs/Trigger answering FILE under
each --snapshot name. Every call it receives is printed as `CALLED <service>`, so the test can
tell a call that reached it from one the check's guard refused.
"""
import argparse

import rospy
from std_srvs.srv import Trigger, TriggerResponse
from turtlesim.msg import Pose
from turtlesim.srv import TeleportAbsolute, TeleportAbsoluteResponse

FAKE_X = 42.0  # no turtle is ever there: turtlesim's canvas is 11.09 m wide


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--name", required=True)
    parser.add_argument("--pose", action="append", default=[])
    parser.add_argument("--teleport", action="append", default=[])
    parser.add_argument("--snapshot", action="append", default=[])
    parser.add_argument("--path", default="")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node(args.name)
    publishers = [rospy.Publisher(topic, Pose, queue_size=10) for topic in args.pose]

    def teleported(name: str):
        def answer(_req):
            print("CALLED %s" % name, flush=True)
            return TeleportAbsoluteResponse()
        return answer

    def snapshot(name: str):
        def answer(_req):
            print("CALLED %s" % name, flush=True)
            return TriggerResponse(success=True, message=args.path)
        return answer
    for name in args.teleport:
        rospy.Service(name, TeleportAbsolute, teleported(name))
    for name in args.snapshot:
        rospy.Service(name, Trigger, snapshot(name))
    print("READY", flush=True)
    rate = rospy.Rate(100)
    while not rospy.is_shutdown():
        for publisher in publishers:
            publisher.publish(Pose(x=FAKE_X, y=FAKE_X))
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
