"""Imported first by this sample's talker: where the course's reference solutions show through to
a student's process (a package ROS finds, a module Python imports, a path in the environment, and
with FOLDERS the folders themselves: solutions_ws/, every course's solution/ and samples/), it says what it saw and exits, so the talker never
publishes and the milestone fails. The folders are hidden by the sandbox only: where student code runs with
the grader's rights (isolation none) they are in sight, so the sample probe_no_reference_folders,
the one that looks for them, needs isolation."""
import glob
import importlib.util
import os
import subprocess
import sys

PACKAGES = {"my_chatter", "lab2_turtlesim", "turtle_patrol", "mybot_teleop", "mybot_color", "two_turtles",
            "my_pkg", "my_robot_controller", "pkg_param", "pkg_interfaces", "pkg_tf", "pkg_metapackage"}
MODULES = ("my_chatter", "turtle_patrol", "pkg_interfaces", "my_pkg", "mybot_color_core", "mybot_teleop_core")
FOLDERS = False


def holds_a_file(folder):
    """Whether a file can be read below `folder` (a hidden one is an empty tmpfs, which may hold
    the empty folders the sandbox made to mount deeper hidden paths on)."""
    return any(files for _, _, files in os.walk(folder))


def seen():
    listed = subprocess.run(["rospack", "list-names"], stdout=subprocess.PIPE, universal_newlines=True).stdout
    found = ["package %s" % p for p in sorted(PACKAGES & set(listed.split()))]
    found += ["module %s" % m for m in MODULES if importlib.util.find_spec(m) is not None]
    found += ["%s=%s" % (k, v) for k, v in sorted(os.environ.items()) if "solutions_ws" in v or "/solution" in v]
    for entry in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if FOLDERS else []:
        root = os.path.dirname(os.path.dirname(entry))
        answers = [os.path.join(root, "solutions_ws")] + sorted(
            glob.glob(os.path.join(root, "courses", "*", "solution")) + glob.glob(os.path.join(root, "courses", "*",
                                                                                               "samples")))
        for path in answers:
            if entry and os.path.isdir(path) and holds_a_file(path):
                found.append("folder %s" % path)
    return found


LEAKS = seen()
if LEAKS:
    sys.stderr.write("the reference solutions show through: %s\n" % "; ".join(LEAKS))
    sys.exit(3)
