"""The command line of `topic_tools relay`: relay IN_TOPIC [OUT_TOPIC], OUT defaulting to IN_relay."""
from __future__ import annotations

from typing import List, Sequence, Tuple

USAGE = "usage: relay IN_TOPIC [OUT_TOPIC]"


def parse_relay_args(argv: Sequence[str]) -> Tuple[str, str]:
    """argv without ROS remapping args (name:=value) and without the program name."""
    args: List[str] = [a for a in argv if ":=" not in a]
    if not 1 <= len(args) <= 2:
        raise SystemExit(USAGE)
    in_topic = args[0]
    out_topic = args[1] if len(args) == 2 else in_topic + "_relay"
    return in_topic, out_topic
