"""000: ROS 2 basics with turtlesim (built in its ROS 1 form)."""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("pose_subscriber", "Pose subscriber prints turtle1's pose", "000 pose subscriber (ROS 1 form)",
              "pose_subscriber.test", ("my_robot_controller",)),
]
