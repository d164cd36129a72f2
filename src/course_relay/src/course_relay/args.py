"""The command line of `topic_tools relay`: relay IN_TOPIC [OUT_TOPIC], OUT defaulting to IN_relay.

Both names are checked here, before the node starts, so a bad one ends the program at once with
a message saying which name is not valid and why (exit status 1, like any SystemExit message).
"""
from __future__ import annotations

from typing import List, Sequence, Tuple

from course_relay.names import topic_name_problem

USAGE = "usage: relay IN_TOPIC [OUT_TOPIC]"


def parse_relay_args(argv: Sequence[str]) -> Tuple[str, str]:
    """argv without ROS remapping args (name:=value) and without the program name."""
    args: List[str] = [a for a in argv if ":=" not in a]
    if not 1 <= len(args) <= 2:
        raise SystemExit(USAGE)
    in_topic = args[0]
    out_topic = args[1] if len(args) == 2 else in_topic + "_relay"
    for role, name in (("IN_TOPIC", in_topic), ("OUT_TOPIC", out_topic)):
        problem = topic_name_problem(name)
        if problem:
            raise SystemExit("relay: %s [%s] is not a valid topic name: %s\n%s" % (role, name, problem, USAGE))
    return in_topic, out_topic
