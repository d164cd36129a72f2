"""003: Computer Exercise 1 (turtlesim tasks, the arch drawer, launch files, parameters, Gazebo)."""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("arch", "Writing our first node: the arch drawer (tasks 1-8)", "003 Writing our first node",
              "arch.test", ("my_pkg",), points=40.0),
    Milestone("two_turtles", "Two turtlesims, one teleop, two relays", "003 Launch files", "two_turtles.test",
              ("two_turtles",)),
    Milestone("backgrounds", "Background colours through parameters", "003 ROS parameters", "backgrounds.test",
              ("two_turtles",)),
    Milestone("graph_picture", "rqt_graph picture of the two-turtle system", "003 Part I task 3",
              "graph_picture.test"),
    Milestone("gazebo_rrbot", "RRBot world, coke can, set_model_state", "003 Part II tasks 1-3",
              "gazebo_rrbot.test"),
]
