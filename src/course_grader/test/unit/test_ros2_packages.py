"""ros2_packages: a ROS 2 (ament) package named as such before catkin_make stops on it."""
from course_format import causes

from course_grader import ros2_packages

HEAD = '<?xml version="1.0"?>\n<package format="3">\n  <name>%s</name>\n  <version>0.0.1</version>\n' \
       '  <description>d</description>\n  <maintainer email="s@example.edu">s</maintainer>\n' \
       '  <license>MIT</license>\n'


def _package(root, rel, name, body):
    folder = root / rel
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(HEAD % name + body + "</package>\n")
    return str(folder)


def test_an_ament_python_package_is_named_with_its_line_and_what_to_change(tmp_path):
    folder = _package(tmp_path, "lab2_ws/src/turtle", "lab2_turtlesim",
                      "  <exec_depend>rclpy</exec_depend>\n  <export>\n"
                      "    <build_type>ament_python</build_type>\n  </export>\n")
    [(name, said)] = ros2_packages.problems([folder], str(tmp_path))
    assert name == "lab2_turtlesim" and causes.of(said) == "ros2_package"
    assert said.startswith("lab2_turtlesim is a ROS 2 (ament_python) package (lab2_ws/src/turtle/package.xml line 10: "
                           "<build_type>ament_python</build_type>): this course builds ROS 1 catkin packages"), said
    for words in ("<buildtool_depend>catkin</buildtool_depend>", "catkin_package()",
                  "`rosrun lab2_turtlesim <script>` runs, in place of setup.py's entry_points",
                  "rospy in place of rclpy"):
        assert words in said


def test_ament_cmake_by_export_or_by_buildtool_alone(tmp_path):
    exported = _package(tmp_path, "a", "pkg_a", "  <buildtool_depend>ament_cmake</buildtool_depend>\n"
                                                "  <export><build_type>ament_cmake</build_type></export>\n")
    tool_only = _package(tmp_path, "b", "pkg_b", "  <buildtool_depend>ament_cmake_python</buildtool_depend>\n")
    found = dict(ros2_packages.problems([exported, tool_only], str(tmp_path)))
    assert "pkg_a is a ROS 2 (ament_cmake) package (a/package.xml line 9: <build_type>ament_cmake</build_type>)" \
        in found["pkg_a"] and "roscpp in place of rclcpp" in found["pkg_a"]
    assert "pkg_b is a ROS 2 (ament_cmake_python) package (b/package.xml line 8: " \
           "<buildtool_depend>ament_cmake_python</buildtool_depend>)" in found["pkg_b"]


def test_catkin_packages_and_unreadable_manifests_are_left_to_the_build(tmp_path):
    catkin = _package(tmp_path, "c", "pkg_c", "  <buildtool_depend>catkin</buildtool_depend>\n")
    # one package for both: catkin under ROS 1 (its conditions are catkin's to evaluate)
    both = _package(tmp_path, "d", "pkg_d",
                    '  <buildtool_depend condition="$ROS_VERSION == 1">catkin</buildtool_depend>\n'
                    '  <buildtool_depend condition="$ROS_VERSION == 2">ament_cmake</buildtool_depend>\n'
                    '  <export><build_type condition="$ROS_VERSION == 2">ament_cmake</build_type></export>\n')
    broken = tmp_path / "e"
    broken.mkdir()
    (broken / "package.xml").write_text("<package><name>x</name><export><build_type>ament_python")
    missing = str(tmp_path / "f")
    assert ros2_packages.problems([catkin, both, str(broken), missing], str(tmp_path)) == []


def test_the_reason_of_a_milestone_whose_package_is_another(tmp_path):
    folder = _package(tmp_path, "x", "lab2_turtlesim", "  <export><build_type>ament_python</build_type></export>\n")
    found = ros2_packages.problems([folder], str(tmp_path))
    own = ros2_packages.reason(("lab2_turtlesim",), found)
    other = ros2_packages.reason(("my_chatter",), found)
    assert own == found[0][1] and causes.of(own) == causes.of(other) == "ros2_package"
    assert other.startswith("the submission does not build: catkin_make cannot build a workspace that holds a "
                            "ROS 2 package, so none of its packages was built:\nlab2_turtlesim is a ROS 2")
