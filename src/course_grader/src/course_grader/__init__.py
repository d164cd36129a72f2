"""Grade a class of ROS submissions against the course milestones (see cli.py)."""
