"""002: Berkeley Lab 2 (publishers and subscribers, custom messages, services)."""
from course_milestones.milestone import Milestone

MILESTONES = [
    Milestone("chatter", "Example publisher and subscriber", "002 section 2", "chatter.test", ("chatter",)),
    Milestone("checkpoint1", "TimestampString publisher and subscriber", "002 section 3, checkpoint 1",
              "checkpoint1.test", ("my_chatter",)),
    Milestone("checkpoint2", "Keyboard controller for the turtle named on the command line, two at once",
              "002 section 4, checkpoint 2", "checkpoint2.test", ("lab2_turtlesim",)),
    Milestone("checkpoint3", "Patrol service for many turtles", "002 section 5, checkpoint 3", "checkpoint3.test",
              ("turtle_patrol",)),
]
