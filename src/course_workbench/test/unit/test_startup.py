"""The workbench's start-up as data: the environment JupyterLab starts from (no catkin
workspace's entries), and the settings it is given (its token, bash terminals with the course's
rcfile, the lab page behind jupyter-server-proxy)."""
from __future__ import annotations

import argparse
import os
import shutil
import socket
import subprocess

from course_workbench import startup


def workspace(tmp_path, name: str, marker: str = ".catkin") -> str:
    space = tmp_path / name / "devel"
    (space / "lib").mkdir(parents=True)
    (space / marker).write_text("")
    return str(space)


def test_the_environment_keeps_no_entry_of_a_catkin_workspace_or_the_checkout(tmp_path):
    course = workspace(tmp_path, "course")
    reference = workspace(tmp_path, "solutions_ws")
    checkout = tmp_path / "checkout"
    (checkout / ".venv" / "bin").mkdir(parents=True)
    env = {
        "PATH": os.pathsep.join([str(checkout / ".venv" / "bin"), course + "/lib", "/usr/bin", "/bin"]),
        "PYTHONPATH": reference + "/lib/python3/dist-packages",
        "CMAKE_PREFIX_PATH": os.pathsep.join([reference, course]),
        "LD_LIBRARY_PATH": "/opt/mine/lib" + os.pathsep + course + "/lib",
        "ROS_ROOT": course + "/lib/course_env/ros",
        "ROS_MASTER_URI": "http://localhost:11311",
        "JUPYTER_TOKEN": "secret",
        "HOME": "/home/student",
    }
    clean = startup.workbench_env(env, str(checkout))
    assert clean["PATH"] == os.pathsep.join(["/usr/bin", "/bin"])
    assert clean["LD_LIBRARY_PATH"] == "/opt/mine/lib"
    for gone in ("PYTHONPATH", "CMAKE_PREFIX_PATH", "ROS_ROOT", "JUPYTER_TOKEN"):
        assert gone not in clean
    assert clean["ROS_MASTER_URI"] == "http://localhost:11311" and clean["HOME"] == "/home/student"


def test_a_workspace_source_folder_counts_as_the_workspace(tmp_path):
    ws = tmp_path / "ws"
    (ws / "src" / "pkg").mkdir(parents=True)
    (ws / ".catkin_workspace").write_text("")
    assert startup.in_workspace(str(ws / "src" / "pkg"))
    assert not startup.in_workspace(str(tmp_path))


class FakeCourse:
    checkout = "/course"
    setup = "/course/catkin_ws/devel/setup.bash"

    @staticmethod
    def config_file(name: str) -> str:
        return "/course/src/course_workbench/config/" + name


def settings(address: str = "127.0.0.1"):
    args = argparse.Namespace(address=address, overlay="/home/student/catkin_ws")
    return startup.jupyter_settings(FakeCourse(), args, 8888, "tok", "/home/student")


def test_the_settings_give_jupyters_token_bash_terminals_and_the_lab_page():
    given = settings()
    server = given["ServerApp"]
    assert (server["ip"], server["port"], server["port_retries"]) == ("127.0.0.1", 8888, 0)
    assert server["root_dir"] == "/home/student"
    assert given["IdentityProvider"]["token"] == "tok"
    assert server["terminado_settings"]["shell_command"] == [
        "/bin/bash", "--rcfile", "/course/src/course_workbench/config/terminal.bashrc", "-i"]
    roslab = given["ServerProxy"]["servers"]["roslab"]
    # jupyter-server-proxy formats each word with str.format: only {port} may be in them
    command = [word.format(port=4321, base_url="/", unix_socket="") for word in roslab["command"]]
    assert command[-1] == "4321" and FakeCourse.setup in command and "/home/student/catkin_ws" in command
    assert roslab["request_headers_override"] == {"Cookie": "course_web_token=tok"}
    assert roslab["environment"] == {startup.TOKEN_VAR: "tok"}
    assert roslab["launcher_entry"]["title"] == "ROS lab"


def test_the_printed_url_names_the_host_given():
    assert startup.page_url("0.0.0.0", 8888, "t", "127.0.0.1") == "http://127.0.0.1:8888/lab?token=t"
    assert startup.page_url("127.0.0.1", 9000, "t") == "http://127.0.0.1:9000/lab?token=t"


def test_the_settings_file_is_the_users_alone(tmp_path):
    path = startup.write_settings(settings(), str(tmp_path / "conf"))
    assert os.stat(path).st_mode & 0o777 == 0o600
    assert os.stat(str(tmp_path / "conf")).st_mode & 0o777 == 0o700


def test_the_desktop_gets_the_courses_x_session_and_a_display_file_per_port():
    env = startup.desktop_env(FakeCourse(), "/home/student/.local/share/course-workbench", 8888)
    assert env[startup.XSTARTUP_VAR] == "/course/src/course_workbench/config/desktop.xstartup"
    assert env[startup.DISPLAY_FILE_VAR] == "/home/student/.local/share/course-workbench/display-8888"


def test_the_desktops_files_are_there_and_well_formed():
    course = startup.Course()
    xstartup = course.config_file("desktop.xstartup")
    assert os.access(xstartup, os.X_OK)  # vncserver runs it as a program
    for script in (xstartup, course.config_file("terminal.bashrc"), course.config_file("workspace.bash")):
        assert subprocess.run(["bash", "-n", script]).returncode == 0, script
    if shutil.which("jwm"):
        assert subprocess.run(["jwm", "-p", "-f", course.config_file("desktop.jwmrc")]).returncode == 0


def test_a_terminal_has_the_desktops_display_exactly_while_the_desktop_runs(tmp_path):
    """terminal.bashrc's DEBUG trap, before each command: DISPLAY from the file the desktop's X
    session writes, while that display's socket exists; unset when the desktop is gone; a DISPLAY
    of the student's own is left alone."""
    display_file, empty = tmp_path / "display-8888", tmp_path / "setup.bash"
    empty.write_text("")
    with socket.socket(socket.AF_UNIX) as server:  # an X server's socket, on a number nobody uses
        number = next(n for n in range(7000, 8000) if not os.path.exists("/tmp/.X11-unix/X%d" % n))
        x_socket = "/tmp/.X11-unix/X%d" % number
        os.makedirs("/tmp/.X11-unix", exist_ok=True)
        server.bind(x_socket)
        try:
            script = """
source %(rc)s
echo "1[${DISPLAY:-none}]"
echo :%(n)d > %(file)s
echo "2[${DISPLAY:-none}]"
rm %(file)s
echo "3[${DISPLAY:-none}]"
export DISPLAY=:0
echo "4[${DISPLAY:-none}]"
""" % {"rc": startup.Course().config_file("terminal.bashrc"), "n": number, "file": display_file}
            env = {"HOME": str(tmp_path), "PATH": os.environ["PATH"], startup.DISPLAY_FILE_VAR: str(display_file),
                   startup.SETUP_VAR: str(empty), startup.OVERLAY_VAR: str(tmp_path / "none")}
            said = subprocess.run(["bash", "-c", script], env=env, stdout=subprocess.PIPE, text=True).stdout
        finally:
            os.unlink(x_socket)
    assert said.split() == ["1[none]", "2[:%d]" % number, "3[none]", "4[:0]"], said


def test_under_a_hub_the_hubs_login_replaces_the_token_and_the_hub_says_where_to_listen():
    args = argparse.Namespace(address="0.0.0.0", overlay="/home/student/catkin_ws")
    given = startup.jupyter_settings(FakeCourse(), args, 8888, "tok", "/home/student", hub=True)
    assert "IdentityProvider" not in given
    assert not {"ip", "port", "port_retries"} & set(given["ServerApp"])
    assert given["ServerApp"]["terminado_settings"] == settings()["ServerApp"]["terminado_settings"]
    assert given["ServerProxy"]["servers"]["roslab"]["request_headers_override"] == {"Cookie": "course_web_token=tok"}
