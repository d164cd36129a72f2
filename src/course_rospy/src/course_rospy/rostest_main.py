"""Debian's rostest, run unchanged, with its XML-RPC servers stopped before their sockets close.

rostest hosts the run's master and roslaunch's server in its own process. At the end of a run
both are shut down the way rospy shuts its node down: the socket is closed while the server's
loop still waits in select(), and the loop then spins on a core until the process exits
(course_rospy.quick_exit tells the whole story). That was about 0.1 CPU s per run, every
milestone run of a grading.

`python3 -P -m course_rospy.rostest_main /usr/bin/rostest ARGS...` installs quick_exit and then runs
the rostest script itself as __main__ (its PATH hook for `python` shebangs included), so what it
does, prints and exits with is rostest's own.
"""
from __future__ import annotations

import runpy
import sys

from course_rospy import quick_exit


def main(argv: list) -> None:
    """argv: [this module, rostest's script, its arguments...]."""
    quick_exit.install()
    script = argv[1]
    sys.argv = [script] + argv[2:]
    runpy.run_path(script, run_name="__main__")


if __name__ == "__main__":
    main(sys.argv)
