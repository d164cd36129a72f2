"""How long each milestone's run takes on the reference, alone (`--jobs 1`, 2 cores): the order
the first grading into a fresh --out starts runs in, longest first, before its own
`_work/durations.json` exists. Only a scheduling hint: a wrong or missing value changes the
order, never a verdict. Measured with `python3 bench/milestone_profile.py`."""
from __future__ import annotations

from typing import Dict

TYPICAL_S: Dict[str, float] = {
    "arch": 15.7,
    "turtlebot": 12.3,
    "gazebo_rrbot": 12.2,
    "tf2_static": 9.4,
    "tf2_follow": 8.6,
    "launch_params": 8.5,
    "param": 6.8,
    "checkpoint3": 6.1,
    "graph_picture": 6.1,
    "checkpoint1": 5.6,
    "backgrounds": 5.4,
    "checkpoint2": 4.8,
    "two_turtles": 4.8,
    "color": 4.4,
    "teleop": 3.9,
    "pose_subscriber": 3.7,
    "chatter": 3.0,
    "interfaces": 1.9,
}
