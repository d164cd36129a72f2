"""The grader's side of the sandbox: which isolation is in force, and the policy of each build and
milestone run (what the student's code may write, what it must not see).

Paths: the overlay workspace `<out>/_work/<student>/ws` and each run's student home
`<out>/_work/<student>/runs/<milestone>/student` are the only places student code writes; the
grader's output folder (every student's verdicts and files), the class folder, the grader's
home and the checkout's reference solutions (`reference`: solutions/ and its overlay) are hidden;
the rest of the course checkout stays readable. Each run's trusted files (rostest's
ROS_HOME with the JUnit XML, the policy itself) are next to the student home, out of its view.
"""
from __future__ import annotations

import os
import pwd
from typing import Dict, Optional, Sequence

from course_sandbox import access, levels, pids_cgroup
from course_checks import isolation
from course_sandbox.policy import DEFAULT_USER, Limits, Policy, grading_gid, normalised
from course_sandbox.run import end_user_processes

SANDBOX_USER_VAR = "COURSE_SANDBOX_USER"


class SandboxPlan:
    """One grading's sandbox settings: the level (probed once), the user, and the paths."""

    def __init__(self, out: str, course_root: str, class_paths: Sequence[str] = (),
                 user: Optional[str] = None, reference: Sequence[str] = (), limits: Limits = Limits()) -> None:
        self.limits = limits
        self.user = user or os.environ.get(SANDBOX_USER_VAR, DEFAULT_USER)
        self.level = levels.detect(self.user)
        # Without PID namespaces, this grading's processes are told apart by their real group.
        self.gid = grading_gid(os.getpid()) if self.level == levels.USER else -1
        self.out = os.path.realpath(out)
        self.course_root = os.path.realpath(course_root)
        home = os.path.expanduser("~")
        hidden = normalised([self.out, home, "/root", "/run/user"]
                            + [os.path.dirname(os.path.abspath(p)) for p in class_paths]
                            + [os.path.abspath(p) for p in class_paths]
                            + [os.path.realpath(p) for p in reference])
        # A hidden folder holding the course (the grader's home) still shows the course: the
        # sandbox mounts the deeper path last.
        self.hidden = [p for p in hidden if p not in ("/", self.course_root)]
        self._check_reachable()

    def _check_reachable(self) -> None:
        """Student code must read the course and write below the output folder: refuse, with
        what to do, when the sandbox user cannot even reach them (a 0700 home on the way)."""
        if self.level == levels.NONE:
            return
        can_traverse = access.traverser(*access.identity(self.level, self.user))
        for what, path in (("the course checkout", self.course_root), ("the output folder", self.out)):
            blocked = access.unreachable_part(path, can_traverse)
            if blocked:
                raise levels.Unavailable(
                    "the sandbox user %s cannot reach %s at %s: %s does not let it through (mode %o). "
                    "Put it where other users can pass (e.g. /srv or /opt), or `chmod o+x %s`"
                    % (self.user, what, path, blocked, os.stat(blocked).st_mode & 0o7777, blocked))

    def describe(self) -> str:
        """The isolation in force, in words: the sandbox's level, how a run's processes are
        counted, and the runs' network."""
        network = ("each run has its own loopback-only network" if isolation.network_namespace_works()
                   else "the runs share the machine's network (network namespaces refused)")
        processes = pids_cgroup.describe(pids_cgroup.available(), Limits().processes)
        return "%s; %s; %s" % (levels.describe(self.level, self.user), processes, network)

    def end_leftovers(self) -> None:
        """Once every run is over: without PID namespaces (`user only`) a student's helper that
        left its session and emptied its environment is found by its user alone."""
        if self.level == levels.USER:
            end_user_processes(self.user, self.gid)

    def give(self, path: str) -> str:
        """Make `path` (a folder tree the trusted side created) the student's: owned by the sandbox
        user when the level switches users. Returns `path`."""
        os.makedirs(path, exist_ok=True)
        if levels.switches_user(self.level):
            entry = pwd.getpwnam(self.user)
            for folder, dirs, files in os.walk(path):
                for name in [folder] + [os.path.join(folder, n) for n in dirs + files]:
                    os.lchown(name, entry.pw_uid, entry.pw_gid)
        return path

    def policy(self, writable: Sequence[str], home: str, student_env: Optional[Dict[str, str]] = None,
               report: str = "", disk_folder: str = "", readable: Sequence[str] = ()) -> Policy:
        """A sandbox's policy; `disk_folder`: the student's work folder, bounded on disk in total;
        `readable`: folders shown read-only besides the course (a run's own etc/ros)."""
        return Policy(self.level, self.user, normalised(writable), list(self.hidden),
                      [self.course_root] + normalised(readable),
                      home, student_env, self.limits, report=report, gid=self.gid, disk_folder=disk_folder)


def parse_env(data: bytes) -> Dict[str, str]:
    """`env -0` output (from the student's sandbox: untrusted) as a dict; malformed entries dropped."""
    env: Dict[str, str] = {}
    for item in data.split(b"\0"):
        if b"=" in item:
            key, value = item.split(b"=", 1)
            name = key.decode("utf-8", "replace")
            if name and name.replace("_", "a").isalnum():
                env[name] = value.decode("utf-8", "replace")
    return env


def overlay_paths(course_env: Dict[str, str], ws: str) -> Dict[str, str]:
    """The trusted side's environment for grading the overlay `ws`: the course's, with the
    overlay's packages found first (ROS_PACKAGE_PATH, CMAKE_PREFIX_PATH: rospack and rosrun's
    search), and nothing that would load the student's code into a trusted process (no
    PYTHONPATH, LD_LIBRARY_PATH or PATH of the overlay: checks build message classes from the
    .msg files, course_milestones.messages). Computed, never sourced: the overlay's setup.bash and
    env hooks are the student's code."""
    env = dict(course_env)

    def prepend(var: str, value: str) -> None:
        rest = [p for p in env.get(var, "").split(os.pathsep) if p and p != value]
        env[var] = os.pathsep.join([value] + rest)
    prepend("ROS_PACKAGE_PATH", os.path.join(ws, "src"))
    prepend("CMAKE_PREFIX_PATH", os.path.join(ws, "devel"))
    return env
