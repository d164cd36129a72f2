"""A student's first lab (002 section 2, the chatter package) done through a JupyterLab workbench
as a student does it: `catkin_create_pkg` and `catkin_make` typed in a terminal, the talker and
the listener written through the contents API (the editor's save). The workbench's tests on the
host and `make docker-check` in the image (course_testkit.course_image) take the same steps.

Needs course_testkit.jupyter alone (tornado, no ROS).
"""
from __future__ import annotations

from course_testkit.jupyter import JupyterError, JupyterServer, Terminal

TOPIC = "/chatter_talk"  # what the milestone `chatter` wants the talker to publish on
WRONG_TOPIC = "/chatter"
BUGGY_FOLDER = "buggy"  # in the student's home, beside catkin_ws
# The self-check's verdicts as it prints them.
PASSED = "PASS  chatter"
FAILED = "FAIL  chatter"
BUGGY_REASON = "no executable in package chatter publishes %s" % TOPIC
CHECK_TIMEOUT_S = 240.0
BUILD_TIMEOUT_S = 300.0

TALKER = '''#!/usr/bin/env python3
"""Publishes a counted greeting on %(topic)s, ten times a second."""
import rospy
from std_msgs.msg import String


def main():
    rospy.init_node("talker")
    publisher = rospy.Publisher("%(topic)s", String, queue_size=10)
    rate = rospy.Rate(10)
    count = 0
    while not rospy.is_shutdown():
        publisher.publish(String(data="hello number %%d" %% count))
        count += 1
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
'''
LISTENER = '''#!/usr/bin/env python3
"""Prints what it hears on %(topic)s."""
import rospy
from std_msgs.msg import String


def heard(message):
    print("I heard: %%s" %% message.data, flush=True)


if __name__ == "__main__":
    rospy.init_node("listener")
    rospy.Subscriber("%(topic)s", String, heard)
    rospy.spin()
'''


def _must(term: Terminal, command: str, timeout: float = 120.0) -> str:
    code, said = term.run(command, timeout)
    if code != 0:
        raise JupyterError("`%s` exited %d in the workbench's terminal:\n%s" % (command, code, said[-3000:]))
    return said


def make_chatter(server: JupyterServer, term: Terminal) -> str:
    """The chatter package in ~/catkin_ws/src, made and built as the text says; catkin_make's output."""
    _must(term, "cd ~/catkin_ws/src && catkin_create_pkg chatter rospy std_msgs")
    server.make_folder("catkin_ws/src/chatter/scripts")
    server.write_file("catkin_ws/src/chatter/scripts/talker.py", TALKER % {"topic": TOPIC})
    server.write_file("catkin_ws/src/chatter/scripts/listener.py", LISTENER % {"topic": TOPIC})
    return _must(term, "chmod +x ~/catkin_ws/src/chatter/scripts/*.py && cd ~/catkin_ws && catkin_make",
                 BUILD_TIMEOUT_S)


def make_buggy_copy(server: JupyterServer, term: Terminal) -> str:
    """~/buggy/chatter: the package again, its talker on the wrong topic; the folder (from the home)."""
    _must(term, "mkdir -p ~/%s && cp -r ~/catkin_ws/src/chatter ~/%s/" % (BUGGY_FOLDER, BUGGY_FOLDER))
    server.write_file("%s/chatter/scripts/talker.py" % BUGGY_FOLDER, TALKER % {"topic": WRONG_TOPIC})
    return BUGGY_FOLDER
