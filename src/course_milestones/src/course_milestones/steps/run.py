"""The runtime of a data milestone: each primitive of course_format.schema mapped to the function that does
it (one module per kind of thing it looks at), and the steps run in order until the first that
fails. The node `run_steps` (course_milestones/nodes) calls run_steps() here.

Every primitive takes (state, params, where): the milestone's shared StepState, the step's
parameters with the schema's defaults filled in, and the step's place in the course file. A
failure is a StepFailed whose finding carries its cause; anything else a primitive raises is the
check's own fault, said as such (cause grader_error), never a bare traceback.
"""
from __future__ import annotations

from typing import Callable, Dict, Optional, Sequence

from course_format import causes, saved, schema
from course_milestones import students
from course_milestones.steps import (built, drawing, frames, params, rest, services, starting, terminal, topics,
                                     turtles)
from course_milestones.steps.state import Started, StepFailed, StepState, course_error

Primitive = Callable[[StepState, Dict, str], None]
# Causes a step's own `cause` does not replace: the node is gone, or the check itself is at fault.
KEEPS_OWN_CAUSE = frozenset(("node_exited", "exited_early", "stopped_listening", "unregistered", "check_failed",
                             "grader_error", "package_missing", "not_started", "not_executable", "no_shebang",
                             "windows_line_endings", "python2"))

# Checks that see the node do what is asked (the messages it sends, the lines it prints); registering
# a topic or a service is not yet doing it (a node without rospy.spin() registers, then exits).
SEES_WORK = frozenset(("publishes", "prints"))

RUNNERS: Dict[str, Primitive] = {
    "start": starting.start,
    "publishes": topics.publishes,
    "subscribes": topics.subscribes,
    "advertises": services.advertises,
    "call": services.call,
    "publish": topics.publish,
    "set_param": params.set_param,
    "param_is": params.param_is,
    "prints": terminal.prints,
    "type": terminal.type_keys,
    "teleport": turtles.teleport,
    "turtle_moves": turtles.turtle_moves,
    "running": starting.running,
    "generated": built.generated,
    "tf_frame": frames.tf_frame,
    "tf_follows": frames.tf_follows,
    "draws": drawing.draws,
    "in_bounds": drawing.in_bounds,
    "pen_colour": drawing.pen_colour,
    "stops_at": rest.stops_at,
    "turns": rest.turns,
}
# Parameters resolved by their step itself, not before it runs: a call's `expect` may name what the
# call saves (course_format.saved).
RESOLVED_LATER = {"call": ("expect",)}


def new_state(packages: Sequence[str] = (), package: str = "") -> StepState:
    """The state a milestone's steps share; every turtle's pose is watched from each action on.
    `package`: the package holding the student's code when it is not `packages[0]` (a rostest's
    ~pkg), which then stands for it in the steps' commands."""
    renamed = {packages[0]: package} if packages and package and package != packages[0] else {}
    return StepState(tuple(packages) + tuple(renamed.values()), on_action=(turtles.watch_all,), renamed=renamed)


def with_defaults(primitive: str, given: Dict) -> Dict:
    """The step's parameters, each missing one at the schema's default (the loader does it too)."""
    return {**{p.name: p.default for p in schema.PRIMITIVES[primitive].params}, **dict(given or {})}


def crashed(state: StepState) -> Optional[Started]:
    """The first started process that exited with a status other than 0 (a crash: a client that
    ran to its end exits with 0, and a process a step ends is no longer among the started)."""
    for started in state.started.values():
        node = started.process.node
        if not node.running() and node.proc.returncode not in (0, None):
            return started
    return None


def with_crash(state: StepState, finding: str) -> str:
    """A check's failure told from its cause: a started process that crashed comes first, whenever
    the crash came (before the check looked, or while it waited), and the failure is its exit's
    (course_format.causes.exited); a failure that already says a node is gone keeps its words."""
    gone = crashed(state)
    if gone is None or causes.of(finding) in KEEPS_OWN_CAUSE:
        return finding
    return causes.finding(state.exit_cause(gone), "`%s` exited with status %s%s; so: %s" % (
        gone.command, gone.process.node.proc.returncode, students.last_words(gone.process), finding))


def run_step(state: StepState, primitive: str, given: Dict, where: str) -> Optional[str]:
    """Run one step; its failure's finding (a causes.Finding), or None when it passed."""
    if primitive not in RUNNERS:
        return course_error(where, "unknown primitive %r (known: %s)" % (primitive, ", ".join(RUNNERS))).finding
    try:
        resolved = saved.resolve_step(primitive, with_defaults(primitive, given), state.saved,
                                      RESOLVED_LATER.get(primitive, ()))
    except saved.Unknown as err:
        return course_error(where, "%s names %s, which no step before it saved (saved: %s)" % (
            primitive, err, ", ".join(sorted(state.saved)) or "none")).finding
    try:
        RUNNERS[primitive](state, resolved, where)
    except StepFailed as failure:
        finding = with_crash(state, failure.finding)
        own = (given or {}).get("cause")
        if own and causes.of(finding) not in KEEPS_OWN_CAUSE and own in causes.BY_KEY:
            return causes.finding(own, finding)
        return finding
    except Exception as err:  # noqa: BLE001 - the check's own fault: said, with the step, not as a traceback
        return causes.finding("grader_error", "the check failed on the step at %s (%s): %s: %s" % (
            where, primitive, type(err).__name__, err))
    if primitive in SEES_WORK:
        state.saw_working((given or {}).get("node"))
    return None


def run_steps(state: StepState, steps: Sequence) -> Optional[str]:
    """Run `steps` (each with .primitive, .params, .where) in order; the first failure's finding,
    or None when every step passed."""
    for step in steps:
        finding = run_step(state, step.primitive, step.params, step.where)
        if finding is not None:
            return finding
    return None
