"""004: the ROS 2 course chapters (TF2, custom interfaces, parameters), built in their ROS 1 form.

The text gives no points; each milestone weighs 10.
"""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("tf2_follow", "pkg_tf: turtle_tf_broadcaster and turtle_following, turtle2 follows turtle1",
              "004 10 TF2, sections 5-9", "tf2_follow.test", ("pkg_tf",), points=10.0),
    # Checks the course workspace (tf2_ros static_transform_publisher and tf2_echo): no student package.
    Milestone("tf2_static", "Static transform A -> B and tf2_echo A B", "004 10 TF2, section 4",
              "tf2_static.test", points=10.0),
    Milestone("interfaces", "pkg_interfaces: Person.msg, Add.srv (and Progress.action)",
              "004 11 custom interfaces, 11.3-11.4", "interfaces.test", ("pkg_interfaces",), points=10.0),
    Milestone("param", "pkg_param param_demo: node param_declare says Hello <robot_name>, follows a param set",
              "004 12 parameters, 12.3", "param.test", ("pkg_param",), points=10.0),
]
