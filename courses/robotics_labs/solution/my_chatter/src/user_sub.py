#!/usr/bin/env python3
"""user_sub.py (no Python package in src/: it would shadow the generated my_chatter.msg): prints each /user_messages message with the time it was sent and received."""
import rospy

from my_chatter.msg import TimestampString


def received_line(message: str, sent_at: float, received_at: float) -> str:
    """The output line of the lab text (section 3.1, subscriber step 2)."""
    return "Message: %s, Sent at: %f, Received at: %f" % (message, sent_at, received_at)


def callback(msg: TimestampString) -> None:
    # The receive time is not in the message: it is the subscriber's clock on arrival.
    print(received_line(msg.message, msg.timestamp, rospy.get_time()), flush=True)


if __name__ == "__main__":
    rospy.init_node("user_sub", anonymous=True)
    rospy.Subscriber("/user_messages", TimestampString, callback)
    rospy.spin()
