"""003: Computer Exercise 1 (turtlesim tasks, the arch drawer, launch files, parameters, Gazebo).

Points are the text's own: 5 per task of "Writing Our First Node" (tasks 1-8), 10 for the
launch-file task, 10 for the parameters task, 5 for Part I task 3 (rqt_graph) and 5 + 5 + 10
for Part II tasks 1-3 (Gazebo). Part I tasks 1, 2 and 4 are report-only command lines.
"""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("arch", "Writing our first node: the arch drawer my_node.py (tasks 1-8)",
              "003 Writing Our First Node, tasks 1-8", "arch.test", ("my_pkg",), points=40.0),
    Milestone("two_turtles", "two_turtles.launch: two turtlesims, one teleop, two relays",
              "003 Launch Files, task", "two_turtles.test", ("two_turtles",), points=10.0),
    Milestone("backgrounds", "change_background_color.launch: a different background for each turtlesim",
              "003 ROS Parameters, task", "backgrounds.test", ("two_turtles",), points=10.0),
    # Checks the course workspace (rqt_graph picture of turtlesim, teleop and rostopic echo).
    Milestone("graph_picture", "rqt_graph of turtlesim, teleop and a second subscriber (rostopic echo)",
              "003 Part I, task 3", "graph_picture.test", points=5.0),
    # Checks the course workspace (the simulator and the texts' commands): no student package.
    Milestone("gazebo_rrbot", "RRBot world, coke can from the database, model_states, set_model_state",
              "003 Part II, tasks 1-3", "gazebo_rrbot.test", points=20.0),
]
