"""Whether an address stays on this machine.

ROS 1 and the lab page both care: a node that advertises 127.0.0.1 cannot be reached from
another host (ros_net_check warns), and a page bound to loopback needs no token (course_web).
"""
from __future__ import annotations

import ipaddress

LOCALHOST = "localhost"


def is_loopback(host: str) -> bool:
    """True for 127.0.0.0/8, ::1 and the name localhost; False for other names and addresses."""
    if host == LOCALHOST:
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False
