"""`make hub`: the container engine's Docker API, then JupyterHub, until Ctrl-C.

    hub --config deploy/jupyterhub/jupyterhub_config.py --jupyterhub .venv-hub/bin/jupyterhub
        [--socket /run/ros-course-hub/podman.sock]

DockerSpawner speaks the Docker API. When DOCKER_HOST names an engine that answers, the hub uses
it; otherwise this starts podman's Docker-compatible service on a socket of the hub's own
(`podman --runtime runc --cgroup-manager=cgroupfs --network-backend netavark system service
--time=0 unix://SOCK`: the runtime and cgroup manager podman needs on this kind of machine,
tools/podman_check.py, and the network stack whose internal networks have a gateway) and
stops it when the hub stops. JupyterHub stops the students' servers when it stops
(their files stay in the hub's data folder). While the hub runs, its API port is closed to all
but loopback and the containers' bridges (course_hub.firewall).
"""
from __future__ import annotations

import argparse
import os
import signal
import socket
import subprocess
import sys
import time
from typing import Dict, List, Mapping, Optional, Sequence

from course_hub import firewall
from course_hub.hubconfig import DEFAULT_HUB_PORT

# netavark, not CNI: podman installed without its recommends picks CNI, whose internal networks
# have no gateway the containers could reach the hub on
PODMAN = ["podman", "--runtime", "runc", "--cgroup-manager=cgroupfs", "--network-backend", "netavark"]
DEFAULT_SOCKET = "/run/ros-course-hub/podman.sock"
API_PORT_VAR = "HUB_API_PORT"  # the hub's config reads it too (deploy/jupyterhub/jupyterhub_config.py)
SOCKET_TIMEOUT_S = 120.0  # podman takes seconds to start, minutes on a loaded machine
STOP_TIMEOUT_S = 60.0


def socket_path(docker_host: str) -> Optional[str]:
    """The file of a `unix://` DOCKER_HOST; None for another kind (tcp://, ssh://)."""
    return docker_host[len("unix://"):] if docker_host.startswith("unix://") else None


def answers(path: str) -> bool:
    """True when something accepts connections on the unix socket `path`."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as probe:
        probe.settimeout(2.0)
        try:
            probe.connect(path)
            return True
        except OSError:
            return False


def engine_command(path: str) -> List[str]:
    return PODMAN + ["system", "service", "--time=0", "unix://" + path]


def start_engine(path: str) -> subprocess.Popen:
    """podman's Docker API on `path`, answering; RuntimeError when it does not within the timeout."""
    os.makedirs(os.path.dirname(path), mode=0o700, exist_ok=True)
    proc = subprocess.Popen(engine_command(path), stdin=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + SOCKET_TIMEOUT_S
    while not answers(path):
        if proc.poll() is not None or time.monotonic() > deadline:
            ended = proc.poll()
            stop(proc)
            raise RuntimeError("podman's Docker API did not come up on %s within %.0f s (%s)%s" % (
                path, SOCKET_TIMEOUT_S, " ".join(engine_command(path)),
                "" if ended is None else ": podman ended with exit code %d" % ended))
        time.sleep(0.1)
    return proc


def stop(proc: Optional[subprocess.Popen]) -> None:
    if proc is None or proc.poll() is not None:
        return
    os.killpg(proc.pid, signal.SIGTERM)
    try:
        proc.wait(STOP_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()


def hub_env(env: Mapping[str, str], docker_host: str, api_port: int = DEFAULT_HUB_PORT) -> Dict[str, str]:
    """The hub's environment: DOCKER_HOST and its API port set, and no ROS workspace's Python on
    its path (the hub runs from its own venv)."""
    clean = {k: v for k, v in env.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    clean["DOCKER_HOST"] = docker_host
    clean[API_PORT_VAR] = str(api_port)
    return clean


def parse(argv: Sequence[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="hub", description=__doc__.split("\n\n")[0])
    parser.add_argument("--config", required=True, help="JupyterHub's config file (deploy/jupyterhub/jupyterhub_config.py)")
    parser.add_argument("--jupyterhub", required=True, help="the jupyterhub executable (.venv-hub/bin/jupyterhub)")
    parser.add_argument("--api-port", type=int, default=int(os.environ.get(API_PORT_VAR) or DEFAULT_HUB_PORT),
                        help="the hub's API port, which the containers call (default $%s or %d); it is closed to "
                        "everything but loopback and the containers' bridges while the hub runs (course_hub.firewall)"
                        % (API_PORT_VAR, DEFAULT_HUB_PORT))
    parser.add_argument("--socket", default=DEFAULT_SOCKET, help="where podman's Docker API listens when DOCKER_HOST "
                        "does not answer (default %s)" % DEFAULT_SOCKET)
    return parser.parse_args(list(argv))


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = parse(sys.argv[1:] if argv is None else argv)
    if os.geteuid() != 0:
        print("hub: run it as root (sudo make hub): podman runs the students' containers as root here", file=sys.stderr)
        return 2
    given = socket_path(os.environ.get("DOCKER_HOST", ""))
    engine = None
    docker_host = os.environ.get("DOCKER_HOST", "")
    if not (given and answers(given)) and not (docker_host and given is None):
        try:
            engine = start_engine(args.socket)
        except RuntimeError as err:
            print("hub: %s" % err, file=sys.stderr)
            return 2
        docker_host = "unix://" + args.socket
        print("hub: podman's Docker API on %s" % docker_host, flush=True)
    try:
        firewall.guard(args.api_port)
    except RuntimeError as err:
        print("hub: %s" % err, file=sys.stderr)
        stop(engine)
        return 2
    # umask 077: the hub's database, proxy pid file and the students' folders are nobody else's
    # (hubconfig sets the modes that must be wider explicitly)
    hub = subprocess.Popen([args.jupyterhub, "-f", os.path.abspath(args.config)],
                           env=hub_env(os.environ, docker_host, args.api_port), start_new_session=True, umask=0o077)

    def forward(signum: int, _frame: object) -> None:
        if hub.poll() is None:
            os.killpg(hub.pid, signal.SIGTERM)

    signal.signal(signal.SIGINT, forward)
    signal.signal(signal.SIGTERM, forward)
    try:
        code = hub.wait()
    finally:
        stop(hub)
        stop(engine)
        firewall.remove(args.api_port)
    return code
