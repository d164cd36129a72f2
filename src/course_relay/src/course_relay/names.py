"""Which topic names the relay accepts, judged before any ROS call, the way topic_tools does.

topic_tools (roscpp) accepts a graph resource name whose first character is a letter, `/` or
`~` and whose other characters are letters, digits, `_` and `/`; it dies with "Character [c]
... is not valid in Graph Resource Name [name]" on anything else. We say the same, but exit
cleanly and at once, also for the cases rospy would only find at the master (and then hang on):
an empty name, or one that resolves to the global namespace `/`.
"""
from __future__ import annotations

import string
from typing import Optional

FIRST_CHARS = frozenset(string.ascii_letters + "/~")
OTHER_CHARS = frozenset(string.ascii_letters + string.digits + "_/")


def topic_name_problem(name: str) -> Optional[str]:
    """Why `name` is not a valid topic name (roscpp's wording), or None when it is."""
    if not name:
        return "an empty name is not a topic"
    if name[0] not in FIRST_CHARS:
        return ("Character [%s] is not valid as the first character in Graph Resource Name [%s]. "
                "Valid characters are a-z, A-Z, / and in some cases ~." % (name[0], name))
    for index, char in enumerate(name[1:], start=1):
        if char not in OTHER_CHARS:
            return ("Character [%s] at element [%d] is not valid in Graph Resource Name [%s]. "
                    "Valid characters are a-z, A-Z, 0-9, / and _." % (char, index, name))
    if not name.strip("/"):
        return "[%s] is the global namespace, not a topic" % name
    return None
