"""quick_exit against a live master: rospy's registration thread is woken once rospy is shut
down (rospy itself wakes it only before, so its shutdown waits out the thread's 0.5 s poll), and
quick_exit.spin() ends a node on SIGINT even when the signal reaches another thread than the
main one (a plain Event.wait() in the main thread would never see it)."""
import json
import signal
import textwrap

import pytest

from course_testkit.master import PrivateMaster
from course_checks.waiting import wait_for

PYTHON = "/usr/bin/python3"
STARTUP_S = 30.0
EXIT_S = 20.0

# Records, for each notify of rospy's registration thread's condition, whether rospy was shut down.
NOTIFIES = textwrap.dedent("""
    import gc, json, sys, threading
    import rospy
    from rospy.impl.registration import RegManager
    from course_rospy import quick_exit
    if sys.argv[1] == "installed":
        quick_exit.install()
    rospy.init_node("notify_probe", disable_signals=True)
    manager = next(o for o in gc.get_objects() if isinstance(o, RegManager))
    seen = []

    class Recording(threading.Condition):
        def notify_all(self):
            seen.append(rospy.is_shutdown())
            super().notify_all()
        notifyAll = notify_all

    manager.cond.__class__ = Recording
    rospy.signal_shutdown("probe")
    print(json.dumps(seen))
""")

# Spins with SIGINT blocked in the main thread: the kernel delivers it to another thread.
SPINNER = textwrap.dedent("""
    import signal, sys
    import rospy
    from course_rospy import quick_exit
    quick_exit.install()
    rospy.init_node("spin_probe")
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    print("spinning", flush=True)
    quick_exit.spin()
    print("spin returned", flush=True)
""")


@pytest.fixture(scope="module")
def master():
    with PrivateMaster() as m:
        yield m


def notifies(master, mode):
    probe = master.start([PYTHON, "-c", NOTIFIES, mode], "notify_probe_%s" % mode)
    assert wait_for(lambda: not probe.running(), STARTUP_S + EXIT_S), probe.output()[-2000:]
    lines = [line for line in probe.output().splitlines() if line.startswith("[")]
    assert lines, probe.output()[-2000:]
    return json.loads(lines[-1])


def test_rospy_alone_wakes_its_registration_thread_only_before_the_flag(master):
    """The control: why rospy's shutdown waits for the thread's next poll."""
    seen = notifies(master, "plain")
    assert seen and not any(seen), seen


def test_quick_exit_wakes_it_once_rospy_is_shut_down(master):
    assert any(notifies(master, "installed"))


def test_spin_returns_on_a_sigint_another_thread_received(master):
    node = master.start([PYTHON, "-c", SPINNER], "spin_probe")
    assert wait_for(lambda: "spinning" in node.output() or not node.running(), STARTUP_S), node.output()[-2000:]
    assert node.running(), node.output()[-2000:]
    node.proc.send_signal(signal.SIGINT)
    assert wait_for(lambda: not node.running(), EXIT_S), "still spinning after SIGINT:\n" + node.output()[-2000:]
    assert "spin returned" in node.output(), node.output()[-2000:]


def test_spin_returns_at_once_when_rospy_is_already_shut_down(master):
    script = SPINNER.replace("print(\"spinning\", flush=True)", "rospy.signal_shutdown(\"before spin\")")
    node = master.start([PYTHON, "-c", script], "spin_after_shutdown")
    assert wait_for(lambda: not node.running(), STARTUP_S + EXIT_S), node.output()[-2000:]
    assert "spin returned" in node.output(), node.output()[-2000:]
