"""A private ROS master on loopback, for a tool, a benchmark or a test that needs a live graph.

The master listens on a free port the kernel picks (never 11311), so no client left with the
default ROS_MASTER_URI on this machine can reach into it, and it binds to 127.0.0.1 only
(ROS_HOSTNAME=localhost, no ROS_IP). By default it is `rosmaster --core` alone: every socket of
the run stays on loopback, whereas Debian's rosout (a roscpp node) binds its XML-RPC server to
0.0.0.0 whatever ROS_HOSTNAME says. Ask for `rosout=True` to get what `roscore` gives (master,
rosout and its /rosout_agg, the /run_id and /rosdistro parameters).

Used as a context manager, it is ready when the block starts (the master answers getSystemState,
and rosout has registered when asked for) and everything it started is stopped when the block
ends, however it ends: the nodes started through it, the master, and whatever they started
(processes carry the run token of course_checks.isolation, so even a node that left its process
group is found). Its ROS_HOME is a fresh folder, removed after a clean run and kept, for its
logs, when the block raised.
"""
from __future__ import annotations

import os
import shutil
import tempfile
import xmlrpc.client
from pathlib import Path
from types import TracebackType
from typing import Dict, List, Mapping, Optional, Sequence, Type

from course_checks import isolation
from course_checks.nodes import NodeProcess
from course_checks.waiting import wait_for

HOSTNAME = "localhost"
CALLER_ID = "/course_testkit_master"
STARTUP_TIMEOUT_S = 30.0
POLL_INTERVAL_S = 0.05
STOP_TIMEOUT_S = 15.0
# The variables a private master sets for its clients, and the one it removes (ROS_IP would win
# over ROS_HOSTNAME and could name an outside address).
CLIENT_VARIABLES = ("ROS_MASTER_URI", "ROS_HOSTNAME", "ROS_HOME", "ROS_LOG_DIR", isolation.TOKEN_VAR)
REMOVED_VARIABLES = ("ROS_IP",)


class MasterError(RuntimeError):
    """The private master did not come up."""


def system_state(uri: str) -> Optional[list]:
    """The master's [publishers, subscribers, services] at `uri`, or None when it does not answer."""
    try:
        code, _message, state = xmlrpc.client.ServerProxy(uri).getSystemState(CALLER_ID)
    except (OSError, xmlrpc.client.Error):
        return None
    return state if code == 1 else None


def rosout_registered(state: Optional[list]) -> bool:
    """True when rosout publishes /rosout_agg in a getSystemState answer."""
    return bool(state) and any(topic == "/rosout_agg" and "/rosout" in nodes for topic, nodes in state[0])


class PrivateMaster:
    """A master of our own on a free loopback port; see the module docstring."""

    def __init__(self, rosout: bool = False, home: Optional[Path] = None,
                 env: Optional[Mapping[str, str]] = None, timeout: float = STARTUP_TIMEOUT_S) -> None:
        """`home` (default: a fresh temporary folder, removed after a clean run) becomes ROS_HOME;
        `env` (default: ours) is the environment the master's processes start from."""
        self.rosout = rosout
        self.timeout = timeout
        self.port = isolation.free_port()
        self.uri = "http://%s:%d" % (HOSTNAME, self.port)
        self._owns_home = home is None
        self.home = Path(tempfile.mkdtemp(prefix="private-master-")) if home is None else Path(home)
        base = dict(os.environ if env is None else env)
        # Inside a run that already has a token (a rostest, a graded job, a test watching us), keep
        # it: that run sees and sweeps our processes. Otherwise the token is ours to sweep with.
        self._owns_token = isolation.TOKEN_VAR not in base
        self.token = isolation.new_token() if self._owns_token else base[isolation.TOKEN_VAR]
        self.env: Dict[str, str] = {k: v for k, v in base.items() if k not in REMOVED_VARIABLES}
        self.env.update({"ROS_MASTER_URI": self.uri, "ROS_HOSTNAME": HOSTNAME, "ROS_HOME": str(self.home),
                         "ROS_LOG_DIR": str(self.home / "log"), isolation.TOKEN_VAR: self.token})
        self.nodes: List[NodeProcess] = []
        self._master: Optional[NodeProcess] = None

    def export(self) -> None:
        """Point this process at the master too (rospy reads os.environ when it initialises)."""
        os.environ.update({name: self.env[name] for name in CLIENT_VARIABLES})
        for name in REMOVED_VARIABLES:
            os.environ.pop(name, None)

    def command(self) -> List[str]:
        if self.rosout:
            return ["roscore", "-p", str(self.port)]
        return ["rosmaster", "--core", "-p", str(self.port), "__log:=%s" % (self.home / "master.log")]

    def ready(self) -> bool:
        state = system_state(self.uri)
        return state is not None and (not self.rosout or rosout_registered(state))

    def start_master(self) -> None:
        """Start the master and wait until it answers (and rosout is up when asked for)."""
        self.home.mkdir(parents=True, exist_ok=True)
        name = self.command()[0]
        self._master = NodeProcess(self.command(), env=self.env, log_path=str(self.home / ("%s.out" % name)))
        master = self._master
        if not wait_for(lambda: self.ready() or not master.running(), self.timeout, POLL_INTERVAL_S) \
                or not self.ready():
            said = master.output().strip().splitlines()[-5:]
            raise MasterError("%s on port %d did not come up within %.0f s (logs in %s)%s" % (
                name, self.port, self.timeout, self.home, ": " + " | ".join(said) if said else ""))

    def start(self, command: Sequence[str], name: str, env: Optional[Mapping[str, str]] = None) -> NodeProcess:
        """Start a node (any command) against the master, its output in ROS_HOME/<name>.log;
        `env` replaces the master's environment for this one (start from `self.env`)."""
        node = NodeProcess(command, env=dict(self.env if env is None else env),
                           log_path=str(self.home / ("%s.log" % name)))
        self.nodes.append(node)
        return node

    def stop_node(self, node: NodeProcess, timeout: float = 10.0) -> Optional[int]:
        """Stop one node started here before the block ends."""
        if node in self.nodes:
            self.nodes.remove(node)
        return node.stop(timeout)

    def stop(self, keep_home: bool = False) -> None:
        """Stop the nodes (last started first), then the master, then anything left with our token."""
        for node in reversed(self.nodes):
            node.stop()
        self.nodes.clear()
        if self._master is not None:
            self._master.stop(STOP_TIMEOUT_S)
            self._master = None
        if self._owns_token:
            isolation.kill_run(self.token)
        if self._owns_home and not keep_home:
            shutil.rmtree(self.home, ignore_errors=True)

    def __enter__(self) -> "PrivateMaster":
        try:
            self.start_master()
        except BaseException:
            self.stop(keep_home=True)
            raise
        return self

    def __exit__(self, exc_type: Optional[Type[BaseException]], exc: Optional[BaseException],
                 tb: Optional[TracebackType]) -> None:
        self.stop(keep_home=exc_type is not None)
