"""000: ROS 2 basics with turtlesim, Part 5: the pose subscriber (built in its ROS 1 form)."""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("pose_subscriber", "pose_subscriber prints turtle1's X and Y as the turtle moves",
              "000 Part 5, Writing the Subscriber Node / Execution Steps", "pose_subscriber.test",
              ("my_robot_controller",), points=10.0),
]
