"""roscore.xml's command parameters, run once per process instead of once per rostest.

Every roslaunch that starts a master (rostest always does) loads `$ROS_ETC_DIR/roscore.xml`
(default /etc/ros), whose `/rosversion` and `/rosdistro` parameters are commands: a shell and
`rosversion` twice, about 0.13 s before the first node starts, in every milestone run. Their
answers do not change while a grader or a test suite runs, so `etc_dir_for_run` gives a run
an etc folder of its own: every entry of the real one linked, and a roscore.xml whose command
parameters read a file holding what the command printed. roslaunch reads a `textfile` parameter
exactly as a `command` one (the same conversion of the same text, trailing newline included),
so the master's parameters are the same.
"""
from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import threading
import xml.etree.ElementTree as ET
from functools import lru_cache
from typing import Mapping, Optional

DEFAULT_ETC_DIR = "/etc/ros"
COMMAND_TIMEOUT_S = 30.0


# A grading starts several runs at once: without it, each ran the commands before the first had
# filled the cache (9 `rosversion` at a grading's start, 1.2 CPU s, where 2 do).
_COMMANDS_ONE_AT_A_TIME = threading.Lock()


def command_output(command: str, path: str) -> Optional[str]:
    """What `command` prints (run as roslaunch runs it, without a shell), or None if it fails;
    run once per process for each command and PATH."""
    with _COMMANDS_ONE_AT_A_TIME:
        return _command_output(command, path)


@lru_cache(maxsize=16)
def _command_output(command: str, path: str) -> Optional[str]:
    try:
        done = subprocess.run(shlex.split(command), stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              env=dict(os.environ, PATH=path), timeout=COMMAND_TIMEOUT_S, check=False)
    except (OSError, subprocess.SubprocessError, ValueError):
        return None
    return done.stdout.decode("utf-8") if done.returncode == 0 else None


def etc_dir_for_run(env: Mapping[str, str], folder: str) -> Optional[str]:
    """Make `folder` an etc/ros for one run whose roscore.xml needs no command (see the module
    docstring); its path, or None (use the real one) when roscore.xml is missing, unreadable or
    one of its commands fails."""
    etc = env.get("ROS_ETC_DIR", DEFAULT_ETC_DIR)
    try:
        tree = ET.parse(os.path.join(etc, "roscore.xml"))
    except (OSError, ET.ParseError):
        return None
    params = [p for p in tree.iter("param") if p.get("command")]
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    os.chmod(folder, 0o755)  # the student's roslaunch reads it too, as the sandbox user
    for index, param in enumerate(params):
        output = command_output(param.get("command"), env.get("PATH", os.defpath))
        if output is None:
            return None
        textfile = os.path.join(folder, "param-%d.txt" % index)
        with open(textfile, "w", encoding="utf-8") as f:
            f.write(output)
        del param.attrib["command"]
        param.set("textfile", textfile)
    tree.write(os.path.join(folder, "roscore.xml"), encoding="unicode")
    for name in os.listdir(folder):  # the files written above: no link is there yet
        os.chmod(os.path.join(folder, name), 0o644)
    try:
        for entry in os.listdir(etc):
            if entry != "roscore.xml":
                os.symlink(os.path.join(etc, entry), os.path.join(folder, entry))
    except OSError:
        return None
    return folder
