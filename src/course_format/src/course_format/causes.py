"""Why a milestone failed, as a key a TA groups a class's failures by: the one vocabulary of causes.

A failure's text is for its student (paths, names, their own node's words); its cause is for the
class: "not linked with catkin_LIBRARIES" is one group whatever the target's name. The cause is
given where the failure is made, never guessed from the text afterwards:
- the grader's own findings (a build's hints, a package missing, messages not built, a script
  without its executable bit) are `Finding`s: a sentence (a str, so every caller that joins or
  prints it is unchanged) carrying its key;
- a check (a MilestoneCase) that fails with a Finding as its message records the key in its run's
  artifacts folder (`causes.json`, written by the trusted check), where the grader reads it.
A failure nobody gave a cause to is CHECK_FAILED, grouped per milestone.
"""
from __future__ import annotations

import json
import os
from typing import Dict, List, NamedTuple


class Cause(NamedTuple):
    key: str
    label: str  # what the TA reads for the group


CAUSES = (
    Cause("not_unpacked", "the submission cannot be unpacked"),
    Cause("package_missing", "the package the text names is missing (or named otherwise)"),
    Cause("build_failed", "does not build (no more precise cause known)"),
    Cause("not_linked", "not linked with ${catkin_LIBRARIES}"),
    Cause("not_compiled_in", "a function declared but never compiled into the executable"),
    Cause("no_add_dependencies", "no add_dependencies on the package's own messages"),
    Cause("unknown_package", "find_package or an #include names a package that does not exist"),
    Cause("noetic_cxx", "C++ written for ROS Noetic that Debian 12's compiler refuses"),
    Cause("messages_not_built", "messages or services not built (add_message_files, generate_messages)"),
    Cause("module_not_built", "a Python module not built (setup.py, catkin_python_setup)"),
    Cause("shadows_course", "installs Python modules the course provides"),
    Cause("not_executable", "a #! script without its executable bit (chmod +x)"),
    Cause("windows_line_endings", "a #! script with Windows line endings"),
    Cause("no_shebang", "a script without a #! line (run by sh)"),
    Cause("python2", "Python 2 code (Noetic runs Python 3)"),
    Cause("package_xml", "package.xml leaves out a dependency the build uses, or has another format's tags"),
    Cause("rosbuild", "a rosbuild package (manifest.xml), not a catkin one"),
    Cause("ros2_package", "a ROS 2 (ament) package, not a catkin one"),
    Cause("wrong_topic", "publishes or subscribes on another topic than the text's"),
    Cause("stopped_listening", "did what was asked, then stopped listening while still running"),
    Cause("unregistered", "did what was asked, then unregistered it while still running"),
    Cause("node_exited", "did what was asked, then exited"),
    Cause("exited_early", "exited before doing what was asked"),
    Cause("not_started", "the executable or launch file the text runs is missing, or does not start the node asked"),
    Cause("not_running", "a node the text names is not running"),
    Cause("not_published", "publishes nothing on the text's topic"),
    Cause("silent", "advertises the text's topic but sends no message on it"),
    Cause("not_subscribed", "does not subscribe to the text's topic"),
    Cause("wrong_type", "a topic or service of another type than the text's"),
    Cause("wrong_rate", "publishes slower or faster than the text asks"),
    Cause("wrong_value", "a message field or parameter with another value than the text's"),
    Cause("no_service", "does not offer the text's service"),
    Cause("wrong_answer", "a service answers otherwise than the text says (or fails)"),
    Cause("not_printed", "does not print what the text shows on its terminal"),
    Cause("not_moving", "the turtle does not move as the text says"),
    Cause("not_generated", "a message, service or action the text defines is not generated"),
    Cause("no_frame", "a TF frame the text names is missing, or has another parent"),
    Cause("wrong_name", "a node named otherwise than the text's"),
    Cause("wrong_launch", "a launch file does not start the nodes, remappings or parameters the text names"),
    Cause("param_ignored", "a parameter set does not change what the node does"),
    Cause("course_tools", "the course's own simulator or tools did not work as the text says (report it)"),
    Cause("timeout", "did not finish within the milestone's time limit"),
    Cause("sandbox_limit", "reached a sandbox limit (memory, processes)"),
    Cause("grader_error", "the grader failed (report it)"),
    Cause("interrupted", "not graded: the grading was stopped (Ctrl+C, SIGTERM)"),
    Cause("check_failed", "failed the milestone's check (no more precise cause known)"),
)
BY_KEY: Dict[str, Cause] = {c.key: c for c in CAUSES}
CHECK_FAILED = "check_failed"
BUILD_FAILED = "build_failed"
# Where a check records the causes of its failures, in its run's artifacts folder.
RECORD_FILE = "causes.json"


class Finding(str):
    """A failure's sentence that carries its cause's key (`cause`)."""
    cause = CHECK_FAILED


def finding(key: str, text: str) -> Finding:
    """`text` carrying the cause `key` (which must be in the vocabulary: a typo fails at once)."""
    if key not in BY_KEY:
        raise ValueError("unknown cause %r (see course_format.causes.CAUSES)" % key)
    made = Finding(text)
    made.cause = key
    return made


def exited(did: bool) -> str:
    """The cause of a node that exited: node_exited when the check saw it do some of what was asked
    first, exited_early when it did not (registering a topic is not yet doing what was asked)."""
    return "node_exited" if did else "exited_early"


def of(text: object, default: str = "") -> str:
    """The cause `text` carries, else `default`."""
    return getattr(text, "cause", default) if isinstance(text, Finding) else default


def label(key: str) -> str:
    """The words for a cause key (the key itself when unknown: a results.json of another version)."""
    return BY_KEY[key].label if key in BY_KEY else key


def record(folder: str, key: str) -> None:
    """Append `key` to the causes recorded in `folder` (a check's artifacts folder)."""
    keys = recorded(folder) + [key]
    path = os.path.join(folder, RECORD_FILE)
    with open(path + ".tmp", "w") as f:
        json.dump(keys, f)
    os.replace(path + ".tmp", path)


def recorded(folder: str) -> List[str]:
    """The known cause keys recorded in `folder`, first first (none when no or a bad file)."""
    try:
        with open(os.path.join(folder, RECORD_FILE)) as f:
            keys = json.load(f)
    except (OSError, ValueError):
        return []
    return [k for k in keys if isinstance(k, str) and k in BY_KEY] if isinstance(keys, list) else []
