"""001: UPMC ROS part 1 (teleoperation, services, launch files and parameters, TurtleBot3 Burger).
What each milestone checks, step by step: docs/milestones/<name>.md."""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("teleop", "Teleoperation node: keys drive turtle1", "001 2.1 Part A (#2.1.10)", "teleop.test",
              ("mybot_teleop",)),
    Milestone("color", "Pen red near the corners, set_pen on entering and leaving",
              "001 2.2 Part B (#2.2.4-#2.2.7)", "color.test", ("mybot_color",)),
    Milestone("launch_params", "turtlesim.launch with linear_scale/angular_scale, read by the node",
              "001 2.3.1-2.3.7 Part C", "launch_params.test", ("mybot_teleop",)),
    Milestone("turtlebot", "Teleoperating the simulated TurtleBot3 Burger", "001 2.3.8-2.3.12 Part C",
              "turtlebot.test", ("mybot_teleop",)),
]
