"""NodeProcess: the exit code of a process that ends by itself, None for one still running; its
output reaches its log line by line, whatever language it is written in."""
import shutil
import subprocess
import sys

import pytest

from course_checks.nodes import NodeProcess
from course_checks.waiting import wait_for


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


C_NODE = r"""
#include <stdio.h>
#include <unistd.h>
#include <iostream>
int main() {
  printf("x=%.2f y=%.2f\n", 5.54, 5.54);  /* no fflush, as a student writes it */
  std::cout << "from cout" << "\n";
  sleep(60);
  return 0;
}
"""


def test_a_cpp_node_printing_without_flush_reaches_its_log_while_running(tmp_path):
    """A C++ node's stdout to a file is block-buffered: its lines would show only when it exits.
    On the student's terminal they show at once; the log must too."""
    compiler = shutil.which("g++")
    if compiler is None:
        pytest.skip("no C++ compiler")
    (tmp_path / "node.cpp").write_text(C_NODE)
    subprocess.run([compiler, "-o", str(tmp_path / "node"), str(tmp_path / "node.cpp")], check=True)
    log = tmp_path / "node.log"
    node = NodeProcess([str(tmp_path / "node")], log_path=str(log))
    try:
        assert wait_for(lambda: "from cout" in log.read_text(), 10), log.read_text()
        assert log.read_text().startswith("x=5.54 y=5.54\n")
        assert node.running()
    finally:
        node.stop(5)
