"""A ROS 2 package handed in where the course builds ROS 1 catkin packages, found before the build.

A package.xml exporting `<build_type>ament_python</build_type>` (what `ros2 pkg create
--build-type ament_python` writes, with a setup.py whose entry_points name the nodes) or
`ament_cmake`, or with an ament buildtool, is ROS 2's. catkin_make cannot build a workspace
holding one: it stops with CMake's "non-homogeneous workspace ... Try 'catkin_make_isolated'",
which points at the workspace's CMakeLists.txt, not the student's, and catkin_make_isolated
cannot build an ament package either. So the grader says what the package is and what a catkin
package needs instead, and builds nothing.

package.xml is read as catkin reads it (catkin_pkg), its conditions evaluated for ROS 1: a package
that builds with catkin under ROS 1 and with ament under ROS 2 is a catkin package here.
Pure file reading.
"""
from __future__ import annotations

import os
import re
from typing import List, NamedTuple, Optional, Sequence, Tuple

from course_format import causes

MAX_MANIFEST_BYTES = 1024 * 1024
# The environment catkin evaluates package.xml's conditions in, as far as this course goes.
ROS1_CONTEXT = {"ROS_VERSION": "1", "ROS_PYTHON_VERSION": "3"}


class Ros2Package(NamedTuple):
    name: str
    kind: str  # ament_python, ament_cmake, ...
    line: int  # of package.xml where it says so (0 when not found)
    said: str  # that element, as written


def _line_of(text: str, tag: str, value: str) -> Tuple[int, str]:
    match = re.search(r"<%s\b[^>]*>\s*%s\s*</%s\s*>" % (tag, re.escape(value), tag), text)
    if not match:
        return 0, "<%s>%s</%s>" % (tag, value, tag)
    return text.count("\n", 0, match.start()) + 1, re.sub(r"\s+", " ", match.group(0))


def ros2_package(folder: str) -> Optional[Ros2Package]:
    """What makes the package in `folder` a ROS 2 one, or None (a catkin package, or a package.xml
    catkin_pkg cannot read: the build says why)."""
    from catkin_pkg.package import parse_package_string
    try:
        with open(os.path.join(folder, "package.xml"), "rb") as f:
            text = f.read(MAX_MANIFEST_BYTES).decode("utf-8", errors="replace")
        package = parse_package_string(text, warnings=[])
        package.evaluate_conditions(ROS1_CONTEXT)
        build_type = package.get_build_type()
    except Exception:  # noqa: BLE001 - unreadable, or broken in any way catkin_pkg may meet: the build says how
        return None
    if build_type.startswith("ament"):
        return Ros2Package(package.name, build_type, *_line_of(text, "build_type", build_type))
    for tool in package.buildtool_depends:
        if tool.name.startswith("ament") and tool.evaluated_condition is not False:
            return Ros2Package(package.name, tool.name, *_line_of(text, "buildtool_depend", tool.name))
    return None


def _what_to_change(found: Ros2Package) -> str:
    python = found.kind == "ament_python"
    nodes = ("each node an executable script (#!/usr/bin/env python3, chmod +x) that `rosrun %s <script>` runs, "
             "in place of setup.py's entry_points" % found.name if python else
             "each node an add_executable() target (or an executable script) that `rosrun %s <node>` runs"
             % found.name)
    return ("Make it a catkin package: in package.xml, <buildtool_depend>catkin</buildtool_depend> and no "
            "<build_type> export; a CMakeLists.txt with find_package(catkin REQUIRED COMPONENTS ...) and "
            "catkin_package() (`catkin_create_pkg %s rospy std_msgs` writes both); %s; %s"
            % (found.name, nodes, "rospy in place of rclpy" if python else "roscpp in place of rclcpp (rospy in "
               "place of rclpy)"))


def finding(found: Ros2Package, root: str, folder: str) -> causes.Finding:
    """The sentence for one ROS 2 package (`folder`, under the submission's files `root`)."""
    manifest = os.path.join(os.path.relpath(folder, root), "package.xml")
    where = "%s line %d: %s" % (manifest, found.line, found.said) if found.line else manifest
    return causes.finding("ros2_package", "%s is a ROS 2 (%s) package (%s): this course builds ROS 1 catkin "
                                          "packages, with catkin_make. %s" % (found.name, found.kind, where,
                                                                              _what_to_change(found)))


def problems(folders: Sequence[str], root: str) -> List[Tuple[str, causes.Finding]]:
    """(name, sentence) of each ROS 2 package among `folders` (package folders under `root`)."""
    said = []
    for folder in folders:
        found = ros2_package(folder)
        if found:
            said.append((found.name, finding(found, root, folder)))
    return said


def reason(milestone_packages: Sequence[str], found: Sequence[Tuple[str, causes.Finding]]) -> causes.Finding:
    """A milestone's verdict when the submission holds the ROS 2 packages `found` (problems):
    what its own package is, or that nothing was built because of the others."""
    own = [text for name, text in found if name in milestone_packages]
    others = [text for name, text in found if name not in milestone_packages]
    if own:
        return causes.finding("ros2_package", "\n".join(own + others))
    return causes.finding("ros2_package", "the submission does not build: catkin_make cannot build a workspace "
                                          "that holds a ROS 2 package, so none of its packages was built:\n%s"
                          % "\n".join(others))
