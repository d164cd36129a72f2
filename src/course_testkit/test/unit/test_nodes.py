"""NodeProcess.wait: the exit code of a process that ends by itself, None for one still running."""
import sys

from course_testkit.nodes import NodeProcess


def test_wait_gives_the_exit_code():
    node = NodeProcess([sys.executable, "-c", "raise SystemExit(3)"])
    assert node.wait(30) == 3


def test_wait_gives_none_while_running_and_stop_ends_it():
    node = NodeProcess([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        assert node.wait(0.2) is None
        assert node.running()
    finally:
        node.stop(5)
    assert not node.running()
