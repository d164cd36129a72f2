"""`make jupyter`: JupyterLab as the student's workbench.

    rosrun course_workbench workbench [--port 8888] [--address 127.0.0.1] [--url-host H]
                                      [--overlay ~/catkin_ws] [--prepare-only]

It checks the port, creates the student's overlay workspace (~/catkin_ws, its src/ on the
container's volume) and builds it once so that devel/setup.bash exists, writes JupyterLab's
settings (its own token, the terminals' shell, the lab page behind jupyter-server-proxy) and
becomes JupyterLab, run from its own venv (.venv-jupyter, see requirements-jupyter.txt).

JupyterLab starts from the environment of no catkin workspace (workbench_env): its terminals
source the course workspace and the overlay themselves (config/terminal.bashrc), so no entry of
another workspace (the reference solutions' overlay) is on any of their paths.

Spawned by JupyterHub (its spawner sets JUPYTERHUB_API_TOKEN), it becomes `jupyterhub-singleuser`
instead, with the same settings less the token and the address: the hub's login guards every path
and the hub tells the server where to listen (deploy/jupyterhub/, docs/hub.md).
"""
from __future__ import annotations

import argparse
import contextlib
import errno
import json
import os
import secrets
import shlex
import socket
import subprocess
import sys
from typing import Dict, List, Mapping, Optional, Sequence

import rospkg

from course_sandbox import env_paths

from course_workbench.names import DEFAULT_MASTER_URI, TOKEN_VAR

DEFAULT_PORT = 8888
DEFAULT_ADDRESS = "127.0.0.1"
TOKEN_BYTES = 24
PROXY_TIMEOUT_S = 60.0
# Variables a sourced workspace sets to one of its folders (the course's env hook sets ROS_ROOT).
FOLDER_VALUES = ("ROS_ROOT", "ROS_ETC_DIR")
# catkin's markers: a devel or install space holds `.catkin`, a workspace `.catkin_workspace`.
WORKSPACE_MARKERS = (".catkin", ".catkin_workspace")
# What reaches the terminals and the lab page: where the course's setup.bash and the overlay are.
SETUP_VAR = "COURSE_WORKBENCH_SETUP"
OVERLAY_VAR = "COURSE_WORKBENCH_OVERLAY"
# The desktop (jupyter-remote-desktop-proxy at <base>/desktop/): the X session its vncserver runs
# (the package reads this variable), and the file where that session writes its display, which
# the terminals read (config/terminal.bashrc).
XSTARTUP_VAR = "JUPYTER_REMOTE_DESKTOP_PROXY_XSTARTUP"
DISPLAY_FILE_VAR = "COURSE_WORKBENCH_DISPLAY_FILE"
STATE_FOLDER = os.path.join(".local", "share", "course-workbench")  # under the home: settings, display
HUB_VAR = "JUPYTERHUB_API_TOKEN"  # set by every JupyterHub spawner: this server is one of a hub's users'
# ~/milestones under a hub: the course's milestone pages, where a launch from the LMS naming a
# milestone opens the workbench (course_hub.lti: lab/tree/milestones/<id>.md). The course folder is
# $COURSE_WORKBENCH_COURSE (relative to the checkout), else the built-in course.
MILESTONES_LINK = "milestones"
COURSE_VAR = "COURSE_WORKBENCH_COURSE"
DEFAULT_COURSE = os.path.join("courses", "robotics_labs")


class StartError(Exception):
    """A reason not to start, said in one message (exit code 2)."""


def parse(argv: Sequence[str], env: Mapping[str, str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="workbench", description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", default=env.get("JUPYTER_PORT") or str(DEFAULT_PORT),
                        help="the port to listen on (default: $JUPYTER_PORT, else %d)" % DEFAULT_PORT)
    parser.add_argument("--address", default=env.get("JUPYTER_ADDRESS") or DEFAULT_ADDRESS,
                        help="where to listen (default: $JUPYTER_ADDRESS, else %s)" % DEFAULT_ADDRESS)
    parser.add_argument("--url-host", default=env.get("JUPYTER_URL_HOST", ""),
                        help="the host the printed URL names (in a container: where the host publishes the port)")
    parser.add_argument("--overlay", default=os.path.join(env.get("HOME") or os.path.expanduser("~"), "catkin_ws"),
                        help="the student's overlay workspace (default ~/catkin_ws)")
    parser.add_argument("--root-dir", default="", help="JupyterLab's file browser root (default: $HOME)")
    parser.add_argument("--jupyter", default="", help="JupyterLab's venv (default: the checkout's .venv-jupyter)")
    parser.add_argument("--prepare-only", action="store_true",
                        help="create and build the overlay, then exit (the image does it at build time)")
    return parser.parse_args(list(argv))


def port_number(text: str) -> int:
    try:
        port = int(str(text).strip())
    except ValueError:
        port = 0
    if not 1 <= port <= 65535:
        raise StartError("the port must be a number from 1 to 65535 (JUPYTER_PORT=%s)" % text)
    return port


def check_port(address: str, port: int) -> None:
    """StartError saying which port is taken and how to pick another, when `address:port` is busy."""
    family = socket.AF_INET6 if ":" in address else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as probe:
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as Jupyter's own server binds
        try:
            probe.bind((address, port))
        except OSError as err:
            if err.errno == errno.EADDRINUSE:
                raise StartError(
                    "port %d is already in use on %s (another JupyterLab, or another program, listens there): "
                    "pick another, e.g. JUPYTER_PORT=%d make jupyter (with docker: -p 127.0.0.1:%d:8888 "
                    "publishes the image's JupyterLab on your port %d instead)"
                    % (port, address, port + 1, port + 1, port + 1)) from None
            if err.errno == errno.EACCES:
                raise StartError("port %d needs privileges to listen on: pick one above 1023, e.g. "
                                 "JUPYTER_PORT=8888 make jupyter" % port) from None
            raise StartError("cannot listen on %s port %d: %s (JUPYTER_ADDRESS must be an address of this "
                             "machine, e.g. 127.0.0.1)" % (address, port, err.strerror)) from None


def in_workspace(path: str, extra: Sequence[str] = ()) -> bool:
    """True when `path` lies in a catkin workspace or space (a folder above it holds catkin's
    marker) or in one of `extra`."""
    real = os.path.realpath(path)
    if any(real == f or real.startswith(f.rstrip(os.sep) + os.sep) for f in map(os.path.realpath, extra)):
        return True
    folder = real
    while True:
        if any(os.path.exists(os.path.join(folder, marker)) for marker in WORKSPACE_MARKERS):
            return True
        parent = os.path.dirname(folder)
        if parent == folder:
            return False
        folder = parent


def workbench_env(env: Mapping[str, str], checkout: str) -> Dict[str, str]:
    """`env` as before any catkin workspace was sourced: every entry of its folder lists that lies
    in a workspace or in the course checkout (its venv) dropped, and the folders a workspace set."""
    clean = env_paths.drop_entries(env, lambda p: in_workspace(p, [checkout]))
    for var in FOLDER_VALUES:
        if var in clean and in_workspace(clean[var], [checkout]):
            del clean[var]
    clean.pop("JUPYTER_TOKEN", None)  # Jupyter's token goes into its settings file, not to every terminal
    return clean


class Course:
    """Where the course lives: its checkout, its workspace's setup.bash, this package's files."""

    def __init__(self, rospack: Optional[rospkg.RosPack] = None) -> None:
        package = (rospack or rospkg.RosPack()).get_path("course_workbench")
        self.package = os.path.realpath(package)
        self.checkout = os.path.dirname(os.path.dirname(self.package))  # <checkout>/src/course_workbench
        self.setup = os.path.join(self.checkout, "catkin_ws", "devel", "setup.bash")
        self.jupyter_venv = os.path.join(self.checkout, ".venv-jupyter")

    def config_file(self, name: str) -> str:
        return os.path.join(self.package, "config", name)

    def jupyter_command(self, hub: bool) -> List[str]:
        """What runs the student's JupyterLab, before its --config: `jupyter-lab`, or under a hub
        jupyterhub-singleuser through venv/singleuser.py (the hub's database layer loaded only if
        used, 28 MiB less in every student's container)."""
        if hub:
            return [os.path.join(self.jupyter_venv, "bin", "python3"),
                    os.path.join(self.package, "venv", "singleuser.py")]
        return [os.path.join(self.jupyter_venv, "bin", "jupyter-lab")]


def source_command(setup: str, then: str) -> List[str]:
    return ["bash", "-c", "source %s && %s" % (shlex.quote(setup), then)]


def prepare_overlay(overlay: str, setup: str, env: Mapping[str, str]) -> bool:
    """Create the overlay (its src/ may already be there, mounted) and build it once, chained on
    the course workspace, so that its devel/setup.bash exists. True when it was built now."""
    os.makedirs(os.path.join(overlay, "src"), exist_ok=True)
    if os.path.isfile(os.path.join(overlay, "devel", "setup.bash")):
        return False
    print("workbench: building your workspace %s once (catkin_make)" % overlay, flush=True)
    done = subprocess.run(
        source_command(setup, "cd %s && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3" % shlex.quote(overlay)),
        env=dict(env), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, text=True,
        check=False)
    if done.returncode != 0:
        tail = "\n".join(done.stdout.splitlines()[-30:])
        raise StartError("catkin_make failed in %s (exit code %d):\n%s" % (overlay, done.returncode, tail))
    return True


def page_url(address: str, port: int, token: str, url_host: str = "") -> str:
    host = url_host or (socket.gethostname() if address in ("0.0.0.0", "::", "") else address)
    if ":" in host:
        host = "[%s]" % host
    return "http://%s:%d/lab?token=%s" % (host, port, token)


def roslab_server(course: Course, overlay: str, token: str) -> Dict[str, object]:
    """jupyter-server-proxy's entry for the lab page: `roslab` (this package) on the port the proxy
    picks, in the course's environment and the overlay's. The proxy hands lab_view the token as
    its cookie, once Jupyter has authenticated the request; lab_view refuses any request without
    it, so the page's port is no way around Jupyter's login."""
    # The proxy fills in {port} with str.format: the script must hold no other braces.
    script = ('source "$0" && if [ -r "$1/devel/setup.bash" ]; then source "$1/devel/setup.bash"; fi '
              '&& exec rosrun course_workbench roslab --port "$2"')
    return {
        "command": ["/bin/bash", "-c", script, course.setup, overlay, "{port}"],
        "environment": {TOKEN_VAR: token},
        "timeout": PROXY_TIMEOUT_S,
        "absolute_url": False,
        "request_headers_override": {"Cookie": "course_web_token=%s" % token},
        "new_browser_tab": True,
        "launcher_entry": {"title": "ROS lab", "icon_path": course.config_file("roslab.svg"), "category": "Other"},
    }


def jupyter_settings(course: Course, args: argparse.Namespace, port: int, token: str, root_dir: str,
                     hub: bool = False) -> Dict:
    """JupyterLab's settings, as the JSON of a config file. Under a hub (`hub`) the hub's login
    replaces the token and the hub's spawner says where to listen; `token` then only guards the
    lab page's own port."""
    server: Dict[str, object] = {"ip": args.address, "port": port, "port_retries": 0} if not hub else {}
    server.update({
        "open_browser": False, "root_dir": root_dir, "allow_root": os.geteuid() == 0,
        "terminado_settings": {"shell_command": ["/bin/bash", "--rcfile", course.config_file("terminal.bashrc"),
                                                "-i"]},
    })
    settings: Dict[str, object] = {
        "ServerApp": server,
        "ServerProxy": {"servers": {"roslab": roslab_server(course, args.overlay, token)}},
        # No internet in a lab: no news feed, no update check.
        "LabApp": {"news_url": None, "check_for_updates_class": "jupyterlab.NeverCheckForUpdate",
                   "extension_manager": "readonly"},
    }
    if not hub:
        settings["IdentityProvider"] = {"token": token}
    return settings


def write_settings(settings: Dict, folder: str) -> str:
    """The settings file (0600: it holds the token) in `folder` (0700)."""
    os.makedirs(folder, mode=0o700, exist_ok=True)
    os.chmod(folder, 0o700)
    path = os.path.join(folder, "workbench_config.json")
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(fd, "w") as out:
        json.dump(settings, out, indent=1)
    return path


def desktop_env(course: Course, state: str, port: int) -> Dict[str, str]:
    """What JupyterLab's environment gives the desktop: our X session (desktop.xstartup) for
    jupyter-remote-desktop-proxy's vncserver, and where that session writes its display, one file
    per port (two workbenches of one user keep their desktops apart)."""
    return {XSTARTUP_VAR: course.config_file("desktop.xstartup"),
            DISPLAY_FILE_VAR: os.path.join(state, "display-%d" % port)}


def link_milestones(home: str, checkout: str, course: str = "") -> Optional[str]:
    """`home`/milestones, a link to the course's milestone pages (`<course>/milestones` in the
    checkout), made when missing; None when the course has none, or when the student has a file or
    folder of that name (theirs stays)."""
    pages = os.path.join(checkout, course or DEFAULT_COURSE, "milestones")
    link = os.path.join(home, MILESTONES_LINK)
    if not os.path.isdir(pages):
        return None
    if os.path.islink(link) and os.readlink(link) == pages:
        return link
    if os.path.lexists(link):
        return None
    os.symlink(pages, link)
    return link


def main(argv: Optional[Sequence[str]] = None, env: Optional[Mapping[str, str]] = None) -> int:
    env = dict(os.environ if env is None else env)
    args = parse(sys.argv[1:] if argv is None else argv, env)
    course = Course()
    hub = bool(env.get(HUB_VAR))
    if args.jupyter:
        course.jupyter_venv = args.jupyter
    try:
        port = port_number(args.port)
        args.overlay = os.path.abspath(os.path.expanduser(args.overlay))
        base = workbench_env(env, course.checkout)
        if not args.prepare_only and not hub:
            check_port(args.address, port)
        prepare_overlay(args.overlay, course.setup, base)
        if args.prepare_only:
            print("workbench: %s is ready" % args.overlay, flush=True)
            return 0
        jupyter_lab = course.jupyter_command(hub)
        needed = os.path.join(course.jupyter_venv, "bin", "jupyterhub-singleuser" if hub else "jupyter-lab")
        if not os.access(needed, os.X_OK):
            raise StartError("JupyterLab is not installed (%s is missing): run `make deps`" % needed)
    except StartError as err:
        print("workbench: %s" % err, file=sys.stderr, flush=True)
        return 2
    token = env.get("JUPYTER_TOKEN") or secrets.token_hex(TOKEN_BYTES)
    home = env.get("HOME") or os.path.expanduser("~")
    root_dir = os.path.abspath(args.root_dir or home)
    state = os.path.join(home, STATE_FOLDER)
    config = write_settings(jupyter_settings(course, args, port, token, root_dir, hub), state)
    base.update({SETUP_VAR: course.setup, OVERLAY_VAR: args.overlay, "SHELL": "/bin/bash"})
    base.update(desktop_env(course, state, port))
    with contextlib.suppress(FileNotFoundError):  # a display left by a desktop that was killed
        os.remove(base[DISPLAY_FILE_VAR])
    base.setdefault("ROS_MASTER_URI", DEFAULT_MASTER_URI)
    if "ROS_IP" not in base:
        base.setdefault("ROS_HOSTNAME", "localhost")
    if hub:
        try:  # the home is the container's own
            link_milestones(home, course.checkout, env.get(COURSE_VAR, ""))
        except OSError as err:  # the workbench starts all the same, without the milestone pages
            print("workbench: no ~/%s: %s" % (MILESTONES_LINK, err), file=sys.stderr, flush=True)
        print("workbench: jupyterhub-singleuser for %s, your files in %s, your workspace %s" % (
            env.get("JUPYTERHUB_USER", "?"), root_dir, args.overlay), flush=True)
    else:
        print("workbench: JupyterLab on %s port %d, your files in %s, your workspace %s" % (
            args.address, port, root_dir, args.overlay), flush=True)
        print("workbench: open %s" % page_url(args.address, port, token, args.url_host), flush=True)
    os.chdir(root_dir)  # where a terminal opened by the REST API starts (JupyterLab's own pass a folder)
    os.execve(jupyter_lab[0], jupyter_lab + ["--config=%s" % config], base)
    return 0  # not reached
