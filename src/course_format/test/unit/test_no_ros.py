"""The course format imports no ROS: the grader's command line and course-lint read a course file
before any master runs, and a course's format must be readable where ROS is not installed.
Checked in a fresh interpreter: what importing every module of the package adds to sys.modules."""
import json
import os
import pkgutil
import subprocess
import sys

import course_format

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE_SRC = os.path.normpath(os.path.join(HERE, "..", "..", "src"))
# Top-level modules that are ROS (Debian's ROS, the message packages) or this workspace's ROS side.
ROS = {"rospy", "rosgraph", "roslib", "roslaunch", "rostest", "rosnode", "rosservice", "rostopic", "rosbag",
       "rosmsg", "rosparam", "rospkg", "rosunit", "genpy", "genmsg", "catkin", "catkin_pkg", "tf", "tf2_ros",
       "tf2_py", "actionlib", "actionlib_msgs", "message_filters", "topic_tools", "course_milestones",
       "course_checks", "course_rospy", "course_sandbox", "course_grader"}
PROBE = """
import importlib, json, sys
before = set(sys.modules)
for name in sys.argv[1:]:
    importlib.import_module(name)
print(json.dumps(sorted(set(sys.modules) - before)))
"""


def modules():
    return ["course_format"] + ["course_format." + m.name for m in pkgutil.iter_modules(course_format.__path__)]


def is_ros(name: str) -> bool:
    top = name.split(".")[0]
    return top in ROS or top.endswith(("_msgs", "_srvs")) or any(p in ("msg", "srv") for p in name.split(".")[1:])


def test_every_module_of_the_package_is_probed():
    assert {"course_format.course_file", "course_format.schema", "course_format.milestone",
            "course_format.causes"} <= set(modules())


def test_importing_the_course_format_imports_no_ros():
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in (PACKAGE_SRC, os.environ.get("PYTHONPATH")) if p))
    out = subprocess.run([sys.executable, "-c", PROBE] + modules(), env=env, stdout=subprocess.PIPE, check=True,
                         universal_newlines=True).stdout
    added = json.loads(out.splitlines()[-1])
    assert "course_format.course_file" in added and "yaml" in added  # it did import them
    assert not [m for m in added if is_ros(m)], "course_format imports ROS: %s" % [m for m in added if is_ros(m)]


def test_the_probe_sees_a_ros_import():
    assert is_ros("rospy.impl") and is_ros("std_msgs.msg") and is_ros("turtlesim.srv._Spawn")
    assert not is_ros("yaml") and not is_ros("course_format.schema")
