"""roslab: the lab page (course_web's lab_view) behind JupyterLab's /roslab/.

    rosrun course_workbench roslab --port PORT

jupyter-server-proxy starts it on the first request to /roslab/, with the port to serve on, and
stops it (SIGTERM) with JupyterLab. The page follows the student's master, the ROS_MASTER_URI
the terminals have (http://localhost:11311 unless set):

- Until a master answers there, roslab runs one of its own on a free loopback port, with
  turtlesim, and lab_view on it: the page shows a turtle from the first click. The student's
  `roscore` is free to start: their default port is not taken.
- Once the student's master answers, roslab stops its own master and turtlesim, and runs
  lab_view on the student's.
- A rospy node never registers again with a master that restarted (docs/rospy_limits.md), so
  lab_view is started again whenever the student's master is a new one (another process). While
  it is down, lab_view stays, and the page's panels say that the master does not answer.

lab_view listens on 127.0.0.1 and requires the token in $COURSE_WORKBENCH_TOKEN, which the proxy
presents as lab_view's cookie once Jupyter has authenticated the request.
"""
from __future__ import annotations

import argparse
import ctypes
import os
import signal
import subprocess
import sys
import threading
import time
from typing import Dict, List, Optional, Sequence

from course_net.ports import free_port
from course_workbench import master_probe
from course_workbench.names import DEFAULT_MASTER_URI, TOKEN_VAR

CALLER_ID = "/workbench_roslab"
LAB_VIEW_NAME = "workbench_lab_view"  # not /lab_view: the student may run their own
POLL_S = 0.5  # while the student has no master: their `roscore` is taken up within half a second
# Once lab_view follows the student's master, a look every 2 s is enough to see it restarted; each
# look is an XML-RPC call costing roslab and the master about 1.6 ms of CPU together.
SETTLED_POLL_S = 2.0
MASTER_TIMEOUT_S = 2.0
START_TIMEOUT_S = 30.0
STOP_TIMEOUT_S = 5.0
PR_SET_PDEATHSIG = 1


def master_pid(uri: str) -> Optional[int]:
    """The process id of the master at `uri`, or None when nothing answers as a master there."""
    return master_probe.master_pid(uri, CALLER_ID, MASTER_TIMEOUT_S)


def _die_with_parent() -> None:
    """In the child, before exec: SIGTERM when roslab dies, however it dies."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM)


class Child:
    """A process of its own group; stop() is Ctrl+C, then SIGKILL for the group.

    Nodes are started through `rosrun`, which execs them (the same process, so the same group and
    the same death signal): roslab itself then needs no roslib, whose package search (catkin_pkg,
    rospkg) would keep 5.6 MiB of roslab's 17 MiB for two look-ups."""

    def __init__(self, command: Sequence[str], env: Dict[str, str], name: str) -> None:
        self.name = name
        self.proc = subprocess.Popen(list(command), env=env, stdin=subprocess.DEVNULL,
                                     start_new_session=True, preexec_fn=_die_with_parent)

    def running(self) -> bool:
        return self.proc.poll() is None

    def stop(self) -> None:
        if self.running():
            try:
                os.killpg(self.proc.pid, signal.SIGINT)
                self.proc.wait(STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                pass
            except ProcessLookupError:
                return
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self.proc.wait()


class RosLab:
    """The state: which master lab_view follows, and what roslab started."""

    def __init__(self, port: int, student_uri: str, token: str, env: Optional[Dict[str, str]] = None) -> None:
        self.port, self.student_uri, self.token = port, student_uri, token
        self.env = dict(os.environ if env is None else env)
        self.stopping = threading.Event()
        self.own: List[Child] = []  # our master and turtlesim, while the student has none
        self.own_uri: Optional[str] = None
        self.lab_view: Optional[Child] = None
        self.following: Optional[tuple] = None  # (uri, master pid) lab_view registered with
        self.seen_student = False

    def node_env(self, uri: str) -> Dict[str, str]:
        env = dict(self.env, ROS_MASTER_URI=uri, PYTHONUNBUFFERED="1")
        env.pop(TOKEN_VAR, None)
        return env

    def start_own(self) -> None:
        port = free_port()
        self.own_uri = "http://localhost:%d" % port
        env = self.node_env(self.own_uri)
        env["ROS_HOSTNAME"] = "localhost"
        env.pop("ROS_IP", None)
        print("roslab: no ROS master at %s yet: starting one of the page's own, with turtlesim (%s)"
              % (self.student_uri, self.own_uri), flush=True)
        self.own.append(Child(["rosmaster", "--core", "-p", str(port)], env, "rosmaster"))
        deadline = time.monotonic() + START_TIMEOUT_S
        while master_pid(self.own_uri) is None:
            if not self.own[0].running() or time.monotonic() > deadline or self.stopping.is_set():
                raise RuntimeError("roslab: the page's own master did not start on %s" % self.own_uri)
            time.sleep(0.05)
        # no ~image rate: the page draws the canvas from ~scene, and ~image renders only for a subscriber
        self.own.append(Child(["rosrun", "turtlesim", "turtlesim_node"], env, "turtlesim"))

    def stop_own(self) -> None:
        for child in reversed(self.own):
            child.stop()
        self.own.clear()
        self.own_uri = None

    def start_lab_view(self, uri: str, pid: int) -> None:
        if self.lab_view is not None:
            self.lab_view.stop()
        env = self.node_env(uri)
        env["LAB_VIEW_TOKEN"] = self.token
        self.lab_view = Child(["rosrun", "course_web", "lab_view", "--port", str(self.port), "--address", "127.0.0.1",
                               "__name:=%s" % LAB_VIEW_NAME], env, "lab_view")
        self.following = (uri, pid)
        print("roslab: the lab page follows the master at %s" % uri, flush=True)

    def lab_view_running(self) -> bool:
        return self.lab_view is not None and self.lab_view.running()

    def step(self) -> None:
        """One look at the student's master, and what follows from it."""
        pid = master_pid(self.student_uri)
        if pid is not None:
            self.seen_student = True
            if self.own:
                print("roslab: your master at %s answers: the page follows it" % self.student_uri, flush=True)
                if self.lab_view is not None:
                    self.lab_view.stop()
                    self.lab_view = None
                self.stop_own()
            if self.following != (self.student_uri, pid) or not self.lab_view_running():
                self.start_lab_view(self.student_uri, pid)
        elif not self.seen_student:
            if not self.own:
                self.start_own()
            own_pid = master_pid(self.own_uri)
            if own_pid is not None and (self.following != (self.own_uri, own_pid) or not self.lab_view_running()):
                self.start_lab_view(self.own_uri, own_pid)
        elif not self.lab_view_running():
            # the student's master is down: lab_view stays (its page says so), or comes back
            self.start_lab_view(self.student_uri, -1)

    def poll_period(self) -> float:
        """How long until the next look at the student's master: longer once lab_view follows it."""
        settled = self.following is not None and self.following[0] == self.student_uri and self.following[1] != -1
        return SETTLED_POLL_S if settled and self.lab_view_running() else POLL_S

    def run(self) -> None:
        parent = os.getppid()
        try:
            while not self.stopping.is_set():
                self.step()
                self.stopping.wait(self.poll_period())
                if os.getppid() != parent:  # JupyterLab is gone, however it went
                    break
        finally:
            if self.lab_view is not None:
                self.lab_view.stop()
            self.stop_own()


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="roslab", description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", type=int, required=True, help="where lab_view serves the page")
    parser.add_argument("--master-uri", default=os.environ.get("ROS_MASTER_URI") or DEFAULT_MASTER_URI,
                        help="the student's master (default: $ROS_MASTER_URI)")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    token = os.environ.get(TOKEN_VAR, "")
    if not token:
        print("roslab: %s is not set: roslab runs behind JupyterLab (make jupyter), which sets it" % TOKEN_VAR,
              file=sys.stderr)
        return 2
    lab = RosLab(args.port, args.master_uri, token)
    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, lambda *_: lab.stopping.set())
    lab.run()
    return 0
