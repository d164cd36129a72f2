#!/usr/bin/env python3
"""user_pub.py: asks for a line of text, publishes it with the time it was entered on
/user_messages (my_chatter/TimestampString), again and again until Ctrl+C or end of input."""
import rospy

from my_chatter.msg import TimestampString

PROMPT = "Please enter a line of text and press <Enter>:"


def main() -> None:
    rospy.init_node("user_pub", anonymous=True)
    pub = rospy.Publisher("/user_messages", TimestampString, queue_size=10)
    while not rospy.is_shutdown():
        try:
            text = input(PROMPT + "\n")
        except (EOFError, KeyboardInterrupt):
            break
        pub.publish(TimestampString(message=text, timestamp=rospy.get_time()))
    rospy.sleep(0.5)  # let the last message leave before the node goes away


if __name__ == "__main__":
    main()
