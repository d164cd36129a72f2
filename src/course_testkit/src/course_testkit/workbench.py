"""The student's workbench (`make jupyter`) for tests and benchmarks, driven as JupyterLab's own
page drives it: Jupyter's REST API and its terminal websocket (course_testkit.jupyter).

`Workbench` starts the real start-up (`rosrun course_workbench workbench`, what `make jupyter`
runs) on a free port, with a fresh HOME (the student's home: their overlay ~/catkin_ws is made
there) and a student master URI on a free port nobody else uses, and waits until JupyterLab
answers. Stopping it stops JupyterLab (SIGTERM: it ends its terminals and the proxied lab page),
then anything left that carries its run token (course_checks.isolation), and removes the home.
"""
from __future__ import annotations

import os
import secrets
import shutil
import signal
import subprocess
import tempfile
import time
from typing import Any, List, Mapping, Optional, Sequence

from course_sandbox import procs

from course_checks import isolation
from course_testkit.jupyter import STOP_TIMEOUT_S, JupyterError, JupyterServer, Terminal
from course_checks.nodes import find_executable
from course_checks.waiting import wait_for

START_TIMEOUT_S = 60.0
# The reference solutions' folders: never on a path of the student's terminals or desktop.
REFERENCE_MARKERS = ("/solutions/", "/solutions_ws/", "/solutions:", "/solutions_ws:")
TAB_TIMEOUT_S = 30.0  # a launcher card's new tab, at its page
SPLASH_ID = "jupyterlab-splash"  # JupyterLab's loading screen
WorkbenchError = JupyterError
__all__ = ["Workbench", "WorkbenchError", "Terminal", "open_from_launcher"]


class Workbench(JupyterServer):
    """A running workbench; use as a context manager (see the module docstring)."""

    def __init__(self, env: Optional[Mapping[str, str]] = None, home: Optional[str] = None,
                 token: Optional[str] = None, command: Optional[Sequence[str]] = None) -> None:
        """`command` (default: the start-up itself) may be another way to it, e.g. `make jupyter`."""
        self.command = list(command) if command else None
        super().__init__(isolation.free_port(), token or secrets.token_hex(16))
        self._owns_home = home is None
        # A home others may pass (0755, as /home/<user>): a root grader's sandbox user must reach
        # the self-check's output folder under it.
        self.home = home or tempfile.mkdtemp(prefix="workbench-home-")
        os.chmod(self.home, 0o755)
        self.run_token = isolation.new_token()
        self.master_uri = "http://localhost:%d" % isolation.free_port()
        base = dict(os.environ if env is None else env)
        base.update({"HOME": self.home, "JUPYTER_TOKEN": self.token, "JUPYTER_PORT": str(self.port),
                     "ROS_MASTER_URI": self.master_uri, "ROS_HOSTNAME": "localhost", "PYTHONUNBUFFERED": "1",
                     isolation.TOKEN_VAR: self.run_token})
        # as a student's shell: no display and no Qt platform of the suite's (offscreen would keep
        # turtlesim's and rviz's windows off the desktop)
        for name in ("ROS_IP", "ROS_HOME", "ROS_LOG_DIR", "JUPYTER_ADDRESS", "JUPYTER_URL_HOST", "DISPLAY",
                     "QT_QPA_PLATFORM"):
            base.pop(name, None)
        self.env = base
        self.log_path = os.path.join(self.home, "workbench.log")
        self.proc: Optional[subprocess.Popen] = None
        self.started_s: Optional[float] = None  # from the command to JupyterLab answering

    def output(self) -> str:
        try:
            with open(self.log_path, errors="replace") as log:
                return log.read()
        except OSError:
            return ""

    def start(self) -> "Workbench":
        command = self.command or [find_executable("course_workbench", "workbench")]
        began = time.monotonic()
        with open(self.log_path, "wb") as log:
            self.proc = subprocess.Popen(command, env=self.env, stdin=subprocess.DEVNULL, stdout=log,
                                         stderr=subprocess.STDOUT, start_new_session=True)
        proc = self.proc
        if not wait_for(lambda: proc.poll() is not None or self.status("/api/status") == 200, START_TIMEOUT_S, 0.05) \
                or proc.poll() is not None:
            output = self.output()
            self.stop()
            raise WorkbenchError("the workbench did not start on port %d (exit code %s):\n%s"
                                 % (self.port, proc.poll(), output[-4000:]))
        self.started_s = time.monotonic() - began
        return self

    def stop(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            try:  # JupyterLab (and a `make` above it) ends its terminals and its proxied servers
                os.killpg(self.proc.pid, signal.SIGTERM)
                self.proc.wait(STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        # JupyterLab does not wait for the lab page's processes: they end theirs within seconds.
        wait_for(lambda: not isolation.pids_with_token(self.run_token), STOP_TIMEOUT_S, 0.1)
        isolation.kill_run(self.run_token)
        if self._owns_home:
            shutil.rmtree(self.home, ignore_errors=True)

    def processes(self, word: str) -> List[List[str]]:
        """The command lines of the workbench's processes (those with its run token) naming `word`."""
        return [c for c in map(procs.cmdline, isolation.pids_with_token(self.run_token)) if any(word in p for p in c)]

    def lab_view_port(self) -> Optional[int]:
        """The port of the lab page's lab_view (behind /roslab/), once roslab started it."""
        for command in self.processes("lab_view"):
            if "--port" in command:
                return int(command[command.index("--port") + 1])
        return None

    def __enter__(self) -> "Workbench":
        return self.start()

    def __exit__(self, *exc: Any) -> None:
        self.stop()


def open_from_launcher(browser: Any, bench: Workbench, title: str, path: str) -> None:
    """In `browser` (selenium), open JupyterLab, click the launcher's card named `title` and go to
    the tab it opens, which must show `<base>/<path>` logged in by Jupyter's cookie alone (no token
    in its URL). AssertionError saying what the launcher shows when there is no such card."""
    from selenium.webdriver.common.by import By
    browser.get("%s/lab?token=%s" % (bench.url, bench.token))

    def card() -> Any:
        # JupyterLab's splash screen covers the launcher until the page has loaded: a click on a
        # card behind it lands on the splash (ElementClickInterceptedException)
        if browser.find_elements(By.ID, SPLASH_ID):
            return None
        for element in browser.find_elements(By.CSS_SELECTOR, ".jp-LauncherCard"):
            if title in (element.get_attribute("title") or "") + element.text:
                return element
        return None
    found = wait_for(card, START_TIMEOUT_S, 0.2)
    assert found, "no '%s' card in JupyterLab's launcher; the launcher shows: %s" % (
        title, [e.text for e in browser.find_elements(By.CSS_SELECTOR, ".jp-LauncherCard")])
    lab_tab = browser.current_window_handle
    found.click()
    assert wait_for(lambda: len(browser.window_handles) == 2, TAB_TIMEOUT_S, 0.1), "the card opened no tab"
    browser.switch_to.window([h for h in browser.window_handles if h != lab_tab][0])
    assert wait_for(lambda: browser.current_url.startswith("%s/%s" % (bench.url, path)), TAB_TIMEOUT_S, 0.1), \
        browser.current_url
    assert "token=" not in browser.current_url  # Jupyter's login cookie is what lets it in
