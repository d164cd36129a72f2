"""`make hub` (`course-hub`, in the hub's venv): the hub's start, then JupyterHub until Ctrl-C.

    course-hub --config deploy/jupyterhub/jupyterhub_config.py [--jupyterhub .venv-hub/bin/jupyterhub]
        [--socket /run/ros-course-hub/podman.sock] [--api-port 8081]

In this order, each step explicit and none a side effect of loading JupyterHub's configuration:

1. **The data folder and the initial passwords** (`prepare`): the config file is read as
   JupyterHub reads it, and the course's authenticator (course_hub.auth.CourseAuthenticator)
   made from it says where the class list and the data folder are. The folder's layout and
   modes are set (course_hub.layout), and every listed user without a password gets an initial
   one (course_hub.passwords: the hand-out sheet). A bad class list stops here, with its line.
2. **The container engine:** DockerSpawner speaks the Docker API. When DOCKER_HOST names an engine
   that answers, the hub uses it; otherwise this starts podman's Docker-compatible service on a
   socket of the hub's own (`podman --runtime runc --cgroup-manager=cgroupfs --network-backend
   netavark system service --time=0 unix://SOCK`: the runtime and cgroup manager podman needs on
   this kind of machine, course_testkit.podman, and the network stack whose internal networks
   have a gateway) and stops it when the hub stops.
3. **The API port closed** to all but loopback and the containers' bridges while the hub runs
   (course_hub.firewall).
4. **JupyterHub** with the config file, from the same venv; it stops the students' servers when
   it stops (their files stay on their disks).
"""
from __future__ import annotations

import argparse
import os
import signal
import socket
import subprocess
import sys
import time
from typing import Any, Dict, List, Mapping, Optional, Sequence

from course_hub import firewall, layout, passwords
from course_hub.defaults import HUB_API_PORT

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


def hub_env(env: Mapping[str, str], docker_host: str, api_port: int = HUB_API_PORT) -> Dict[str, str]:
    """The hub's environment: DOCKER_HOST and its API port set, and no ROS workspace's Python on
    its path (the hub runs from its own venv)."""
    clean = {k: v for k, v in env.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    clean["DOCKER_HOST"] = docker_host
    clean[API_PORT_VAR] = str(api_port)
    return clean


def load_config(path: str) -> Any:
    """JupyterHub's configuration from the file `path`, read as JupyterHub reads it (traitlets)."""
    from traitlets.config.loader import PyFileConfigLoader  # the hub's venv
    path = os.path.abspath(path)
    return PyFileConfigLoader(os.path.basename(path), os.path.dirname(path)).load_config()


def authenticator_class(config: Any) -> Any:
    """The class `JupyterHub.authenticator_class` names in `config`: a class, a dotted name, or an
    entry point's name (group jupyterhub.authenticators); None when the config names none."""
    chosen = config.JupyterHub.get("authenticator_class", None)
    if chosen is None or isinstance(chosen, type):
        return chosen
    if "." not in chosen:
        from importlib.metadata import entry_points
        found = [point for point in entry_points(group="jupyterhub.authenticators") if point.name == chosen]
        if not found:
            raise ValueError("JupyterHub.authenticator_class %r: no such entry point" % chosen)
        return found[0].load()
    from traitlets.utils.importstring import import_item
    return import_item(chosen)


def prepare(config_path: str, rounds: int = passwords.DEFAULT_ROUNDS) -> List[str]:
    """The hub's start before JupyterHub, from its config file: the data folder laid out and, when
    the hub's authenticator keeps FirstUseAuthenticator's password file (the course's does), an
    initial password for every listed user without one, in the file that authenticator reads.
    Lines saying what was done. ValueError (ClassListError among them) with what is wrong when
    the class list or the config is."""
    # the hub's venv (firstuseauthenticator); the course's authenticator says where the class
    # list and the data folder are, whichever authenticator the hub runs
    from firstuseauthenticator import FirstUseAuthenticator
    from course_hub.auth import CourseAuthenticator
    config = load_config(config_path)
    # made to read their traits: the password file is checked by JupyterHub's own instance
    course = CourseAuthenticator(config=config, check_passwords_on_startup=False)
    layout.lay_out(course.data_dir)
    done = "data folder %s laid out" % course.data_dir
    chosen = authenticator_class(config) or CourseAuthenticator
    if not (isinstance(chosen, type) and issubclass(chosen, FirstUseAuthenticator)):
        return ["%s; no initial passwords: the hub's authenticator is %s" % (done, chosen)]
    hub_auth = course if chosen is CourseAuthenticator else chosen(config=config, check_passwords_on_startup=False)
    given = passwords.seed(hub_auth.dbm_path, course.roster, course.sheet, rounds)
    return ["%s; class list %s: %d users" % (done, course.class_list, len(course.roster.users)),
            "initial passwords: %s%s" % (passwords.summary(given, course.sheet), ": hand them out" if given else "")]


def parse(argv: Sequence[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="course-hub", description=__doc__.split("\n\n")[0])
    parser.add_argument("--config", required=True, help="JupyterHub's config file (deploy/jupyterhub/jupyterhub_config.py)")
    parser.add_argument("--jupyterhub", default=os.path.join(os.path.dirname(sys.executable), "jupyterhub"),
                        help="the jupyterhub executable (default: this venv's, %(default)s)")
    parser.add_argument("--api-port", type=int, default=int(os.environ.get(API_PORT_VAR) or HUB_API_PORT),
                        help="the hub's API port, which the containers call (default $%s or %d); it is closed to "
                        "everything but loopback and the containers' bridges while the hub runs (course_hub.firewall)"
                        % (API_PORT_VAR, HUB_API_PORT))
    parser.add_argument("--socket", default=DEFAULT_SOCKET, help="where podman's Docker API listens when DOCKER_HOST "
                        "does not answer (default %s)" % DEFAULT_SOCKET)
    return parser.parse_args(list(argv))


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = parse(sys.argv[1:] if argv is None else argv)
    if os.geteuid() != 0:
        print("hub: run it as root (sudo make hub): podman runs the students' containers as root here", file=sys.stderr)
        return 2
    try:
        for line in prepare(args.config):
            print("hub: %s" % line, flush=True)
    except (ValueError, OSError, ImportError) as err:  # ClassListError is a ValueError
        print("hub: %s" % err, file=sys.stderr)
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
    # (course_hub.layout sets the modes that must be wider explicitly)
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
