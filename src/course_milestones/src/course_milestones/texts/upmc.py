"""001: UPMC ROS part 1 (teleoperation, services, launch files and parameters, TurtleBot3 Burger)."""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("teleop", "Teleoperation node", "001 2.1 Part A", "teleop.test", ("mybot_teleop",)),
    Milestone("color", "Pen red in the corners, background near the sides", "001 2.2 Part B", "color.test",
              ("mybot_color",)),
    Milestone("launch_params", "Launch file and parameters", "001 2.3.1-2.3.7 Part C", "launch_params.test",
              ("mybot_teleop",)),
    Milestone("turtlebot", "Teleoperating the simulated TurtleBot3 Burger", "001 2.3.8-2.3.12 Part C",
              "turtlebot.test", ("mybot_teleop",)),
]
