"""A data milestone's steps name a node that exited by what a check saw it do first: exited_early
when no check saw it work (a listener without rospy.spin() registers, then exits), node_exited once
a `publishes` or `prints` step passed on it (no master needed: the processes are stand-ins)."""
from course_format import causes
from course_milestones.steps import run
from course_milestones.steps.state import Started, StepState


class Node:
    """A started process's node: what it printed, and whether it still runs."""

    def __init__(self, output=""):
        self.text, self.proc = output, type("Proc", (), {"returncode": None})()

    def running(self):
        return self.proc.returncode is None

    def output(self):
        return self.text

    def exit(self, code=0):
        self.proc.returncode = code


class Process:
    def __init__(self, node):
        self.node = node

    def end(self):
        self.node.exit(-2)


def started(state, name="listener"):
    node = Node()
    state.add(Started(name, "rosrun pkg %s.py" % name, Process(node), "/" + name, {}, False))
    return node


def prints(state, pattern, node="listener"):
    return run.run_step(state, "prints", {"node": node, "pattern": pattern, "within": 0}, "course.yaml:1")


def test_a_node_that_exits_before_printing_exited_early():
    state = StepState()
    node = started(state)
    node.exit(0)
    finding = prints(state, "I heard")
    assert causes.of(finding) == "exited_early" and "exited with status 0" in finding
    assert causes.label("exited_early") == "exited before doing what was asked"


def test_a_node_that_printed_then_exits_did_some_of_it():
    state = StepState()
    node = started(state)
    node.text = "I heard hello world 1\n"
    assert prints(state, "I heard") is None
    node.exit(1)
    finding = prints(state, "I heard hello world 2")
    assert causes.of(finding) == "node_exited"


def test_what_another_node_did_does_not_count_and_a_new_start_forgets():
    state = StepState()
    talker = started(state, "talker")
    talker.text = "hello world 1\n"
    assert prints(state, "hello", node="talker") is None
    listener = started(state)
    listener.exit(0)
    assert causes.of(prints(state, "I heard")) == "exited_early"
    again = started(state, "talker")  # the same name started anew: it has done nothing yet
    again.exit(0)
    assert causes.of(prints(state, "hello", node="talker")) == "exited_early"


def test_a_steps_own_cause_does_not_hide_an_exit():
    state = StepState()
    started(state).exit(0)
    finding = run.run_step(state, "prints", {"node": "listener", "pattern": "x", "within": 0, "cause": "wrong_value"},
                           "course.yaml:1")
    assert causes.of(finding) == "exited_early"


# -- a crash is the cause, whenever it came ---------------------------------------------------------------

def test_a_check_failing_after_a_started_process_crashed_says_the_crash_first():
    state = StepState()
    driver = started(state, "driver")
    driver.text = "Traceback ...\nTypeError: expected Twist\n"
    started(state)  # the listener runs on and prints nothing
    driver.exit(1)
    finding = prints(state, "I heard")
    assert causes.of(finding) == "exited_early"
    assert finding.startswith("`rosrun pkg driver.py` exited with status 1, its output ending with ")
    assert "TypeError: expected Twist" in finding and "; so: `rosrun pkg listener.py` printed no line" in finding


def test_a_crash_after_the_check_saw_the_node_work_is_node_exited_and_a_clean_exit_no_cause():
    state = StepState()
    driver = started(state, "driver")
    driver.text = "driving\n"
    assert prints(state, "driving", node="driver") is None
    started(state)
    driver.exit(0)  # a client or a driver that ran to its end: not a crash
    assert causes.of(prints(state, "I heard")) == "not_printed"
    driver.exit(139)
    assert causes.of(prints(state, "I heard")) == "node_exited"


def test_a_failure_that_says_its_node_is_gone_is_not_said_twice():
    state = StepState()
    started(state).exit(2)
    finding = prints(state, "I heard")
    assert causes.of(finding) == "exited_early" and finding.count("exited with status 2") == 1


# -- saved values, named ${NAME} ------------------------------------------------------------------------

def test_a_step_names_what_an_earlier_step_saved_and_a_pattern_matches_it_literally():
    state = StepState()
    node = started(state)
    state.saved["spawned"] = "turtle.2"
    node.text = "killed turtle.2\n"
    assert prints(state, "^killed ${spawned}$") is None
    node.text = "killed turtleX2\n"
    state.output_marks = {}
    assert causes.of(prints(state, "^killed ${spawned}$")) == "not_printed"  # the dot is no wildcard


def test_a_name_nothing_saved_is_a_course_file_error():
    state = StepState()
    started(state)
    finding = prints(state, "${nobody}")
    assert causes.of(finding) == "check_failed"
    assert finding.startswith("course file error at course.yaml:1: prints names ${nobody}, which no step before it "
                              "saved (saved: none)")
