"""Which turtle names are acceptable: legal, relative or global, ROS graph names."""
from __future__ import annotations

import re
from typing import Optional

_NAME = re.compile(r"/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*")


def name_error(name: str) -> Optional[str]:
    """Why `name` cannot name a turtle, or None when it can.

    A turtle's name becomes the namespace of its topics and services, so it must
    be a legal ROS graph name (no private `~` names, no empty parts).
    """
    if not _NAME.fullmatch(name):  # not match(): `$` would let a trailing newline through
        return ("invalid turtle name [%s]: a name starts with a letter and holds only "
                "letters, digits, '_' and '/'" % name)
    return None
