"""progress_server on Ctrl+C during a running goal: it exits 0 with no thread's traceback, and the
client hears that its goal ended (preempted, with the sum so far).

rospy's shutdown closes every topic (its pre-shutdown hook) before is_shutdown() turns true, and
actionlib's threads publish whenever is_shutdown() is false: a publish in between raises
"publish() to a closed topic" in its thread ("Exception in thread ...", once in 12 runs). The
window lasts microseconds; here the node runs with HOLD_S added to it (a pre-shutdown hook of our
own, after rospy's), longer than a period of actionlib's status timer (0.2 s) and of a goal's
step (0.1 s), so whatever the node would publish from another thread then, it does."""
import signal
import textwrap

import pytest
import roslib.packages

from course_testkit.master import PrivateMaster
from course_checks.waiting import wait_for

PYTHON = "/usr/bin/python3"
HOLD_S = 0.6
STARTUP_S = 30.0
EXIT_S = 20.0

# The node as rosrun runs it, with the hold: rospy.init_node adds rospy's own pre-shutdown hook
# (it closes the topics), ours comes after it.
HELD = textwrap.dedent("""
    import runpy, sys, time
    import rospy, rospy.core
    init_node = rospy.init_node

    def held_init_node(*args, **kwargs):
        init_node(*args, **kwargs)
        rospy.core.add_preshutdown_hook(lambda reason: time.sleep(%r))
    rospy.init_node = held_init_node
    sys.argv = sys.argv[1:]
    runpy.run_path(sys.argv[0], run_name="__main__")
""" % HOLD_S)


def node(name: str) -> str:
    return roslib.packages.find_node("pkg_interfaces", name)[0]


@pytest.fixture
def master():
    with PrivateMaster() as m:
        yield m


def test_ctrl_c_during_a_goal_ends_it_and_exits_cleanly(master):
    server = master.start([PYTHON, "-c", HELD, node("progress_server")], "progress_server")
    client = master.start([PYTHON, node("progress_client"), "1000"], "progress_client")
    assert wait_for(lambda: client.output().count("progress:") >= 3 or not server.running(), STARTUP_S), \
        "the goal should be running:\n%s\n%s" % (server.output()[-2000:], client.output()[-2000:])
    server.proc.send_signal(signal.SIGINT)
    code = server.wait(EXIT_S)
    said = server.output()
    assert code == 0 and "Traceback" not in said and "Exception" not in said, \
        "progress_server on Ctrl+C (exit %s):\n%s" % (code, said[-3000:])
    assert client.wait(EXIT_S) == 0 and "Result: sum = " in client.output(), \
        "the client should be told its goal ended:\n%s" % client.output()[-2000:]
