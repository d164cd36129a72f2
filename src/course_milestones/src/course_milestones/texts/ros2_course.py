"""004: the ROS 2 course chapters (TF2, custom interfaces, parameters), built in their ROS 1 form."""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("tf2_follow", "TF2 broadcaster and follower", "004 10 TF2", "tf2_follow.test"),
    Milestone("tf2_static", "Static transform A -> B", "004 10.4", "tf2_static.test"),
    Milestone("interfaces", "Person.msg, Add.srv, Progress.action", "004 11 custom interfaces",
              "interfaces.test", ("pkg_interfaces",)),
    Milestone("param", "Declare, set, dump and load parameters", "004 12 parameters", "param.test",
              ("pkg_param",)),
]
