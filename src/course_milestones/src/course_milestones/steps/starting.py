"""The `start` and `running` steps: the student's executable or launch file, as the text runs it
(`rosrun PKG SCRIPT`, `roslaunch PKG FILE`), started on a terminal in the run's sandbox
(course_milestones.students), and the nodes the text names, seen at the master.

With `find`, the text leaves the script (or launch file) open: its own name is tried first, then
each other of the package's, until one registers what `find` asks. Without it, the named one must
exist and register a node (or run to its end with status 0, as a client that asks once does).
"""
from __future__ import annotations

import os
import re
import shlex
from typing import Callable, Dict, Mapping, Optional

import rospkg
import rospy

from course_format import causes
from course_milestones import discovery, launch_files, master_log, students
from course_milestones.discovery import Registration, node_uris
from course_milestones.steps.state import Started, StepFailed, StepState, course_error, failed
from course_checks.waiting import wait_for

FIND_KINDS = ("publishes", "subscribes", "advertises", "node")
# s: a launch file's nodes come up one after another: give them longer than one node to show the one asked for
LAUNCH_SETTLED = students.SETTLED + 2.0


def wanted_by(find: Optional[Mapping], where: str) -> Optional[Callable[[Registration], bool]]:
    """The registration `find` asks for ({publishes|subscribes|advertises: NAME} or {node: /NAME})."""
    if not find:
        return None
    if len(find) != 1 or next(iter(find)) not in FIND_KINDS or not isinstance(next(iter(find.values())), str):
        raise course_error(where, "find takes one of %s with a name, not %r" % (", ".join(FIND_KINDS), dict(find)))
    kind, name = next(iter(find.items()))
    if kind == "node":
        return lambda r: r.node == name
    field = {"publishes": "publishes", "subscribes": "subscribes", "advertises": "services"}[kind]
    return lambda r: name in getattr(r, field)


def find_words(find: Mapping) -> str:
    kind, name = next(iter(find.items()))
    return "runs a node named %s" % name if kind == "node" else "%s %s" % (kind, name)


def start(state: StepState, p: Dict, where: str) -> None:
    if bool(p.get("rosrun")) == bool(p.get("roslaunch")):
        raise course_error(where, "a start step gives either rosrun or roslaunch")
    words = shlex.split(p.get("rosrun") or p.get("roslaunch"))
    if len(words) < 2:
        raise course_error(where, "%r: the text's command after rosrun or roslaunch is 'PKG NAME'"
                           % (p.get("rosrun") or p.get("roslaunch")))
    pkg, target, args = words[0], words[1], words[2:] + [str(a) for a in (p.get("args") or [])]
    pkg = state.renamed.get(pkg, pkg)
    wanted = wanted_by(p.get("find"), where)
    name = p.get("as") or target
    try:
        discovery.package_dir(pkg)
    except rospkg.ResourceNotFound:
        raise failed("package_missing", "there is no package %s (the text runs `%s %s`)" % (
            pkg, "rosrun" if p.get("rosrun") else "roslaunch", " ".join(words)))
    # the command as the text types it, its arguments too (a later failure says which run it follows)
    state.action("`%s %s`" % ("rosrun" if p.get("rosrun") else "roslaunch", " ".join([words[0], target] + args)))
    within = float(p.get("within") or students.REGISTER_TIMEOUT)
    if p.get("rosrun"):
        started = _rosrun(pkg, target, args, wanted, p.get("find"), name, within)
    else:
        started = _roslaunch(pkg, target, args, wanted, p.get("find"), name, within)
    state.add(started)


def _rosrun(pkg: str, script: str, args, wanted, find, name: str, within: float) -> Started:
    command = "rosrun %s %s" % (pkg, " ".join([script] + args))
    before = node_uris()
    if wanted is not None:
        found, tried = students.start_registering(pkg, args, wanted, hint="^%s$" % re.escape(script), log_name=name,
                                                  timeout=within, keep_exited=True)
        if found is None:
            text = students.not_found_message(pkg, find_words(find), tried)
            raise StepFailed(causes.finding(causes.of(text, "not_started"), text + discovery.script_hints(pkg)))
        # the executable found, which the text may have named otherwise
        command = "rosrun %s %s" % (pkg, " ".join([os.path.basename(found.path)] + args))
        return Started(name, command, found.keyboard, found.registration.node, before, False)
    paths = [p for p in discovery.list_executables(pkg) if os.path.basename(p) == script]
    if not paths:
        raise failed(students.start_cause(pkg), "`%s`: package %s has no executable %s (found: %s)%s" % (
            command, pkg, script, discovery.describe(discovery.list_executables(pkg)), discovery.script_hints(pkg)))
    history = master_log.History()
    history.mark()
    keyboard, found, seen = students.start_and_wait(paths[:1] + args, lambda r: True, name, within)
    if found is None and keyboard.node.proc.poll() == 0:  # it ran to its end (a client): later steps read its output
        return Started(name, command, keyboard, None, before, False)
    if found is None and not keyboard.node.running():
        # it registered a node, then exited before that was seen: as if seen, so that a crash right
        # after registering fails the same step with the same reason however fast it came
        registered = [node for node in master_log.ever_registered(history.since()) if node not in before]
        if registered:
            return Started(name, command, keyboard, registered[0], before, False)
    if found is None:
        attempt = students.describe_attempt(script, keyboard, seen)
        keyboard.end()
        cause = students.start_cause(pkg, [students.output_of(keyboard.node)])
        raise failed(cause, "`%s` started no node: %s" % (command, attempt))
    return Started(name, command, keyboard, found.node, before, False)


def _roslaunch(pkg: str, filename: str, args, wanted, find, name: str, within: float) -> Started:
    files = discovery.launch_file_names(pkg)
    if wanted is None and filename not in files:
        raise StepFailed(launch_files.missing_launch_file(pkg, filename))
    order = [filename] + [f for f in files if f != filename] if wanted is not None else [filename]
    tried = []
    for launch_file in order:
        if launch_file not in files:
            tried.append("%s is not in the package" % launch_file)
            continue
        before = node_uris()
        launch = students.Roslaunch(pkg, launch_file, "roslaunch_" + name, args)
        found, seen = students.wait_registering(launch, before, wanted or (lambda r: True), within,
                                                settle=LAUNCH_SETTLED)
        command = "roslaunch %s %s" % (pkg, " ".join([launch_file] + args))
        if found is not None:
            return Started(name, command, launch, found.node if wanted is not None else None, before, True)
        tried.append(students.describe_attempt(launch_file, launch, seen))
        launch.end()
    what = find_words(find) if find else "starts a node"
    raise failed("not_started", "no launch file of package %s %s (tried: %s)" % (pkg, what, "; ".join(tried)))


def running(state: StepState, p: Dict, where: str) -> None:
    names = ["/" + str(n).lstrip("/") for n in p.get("nodes") or []]
    if not names:
        raise course_error(where, "running names no node")
    within = float(p.get("within") or 0)
    present = wait_for(lambda: set(names) <= set(discovery.system_state()), within, 0.1)
    if not present:
        registered = sorted(n for n in discovery.system_state() if n != rospy.get_name())
        missing = [n for n in names if n not in registered]
        raise failed("not_running", "no node named %s is running (running: %s)" % (
            ", ".join(missing), ", ".join(registered) or "none"))
