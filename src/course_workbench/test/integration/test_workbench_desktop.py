"""The workbench's desktop (jupyter-remote-desktop-proxy at /desktop/, TigerVNC, JWM), as a student
meets it: headless chromium opens JupyterLab, the launcher's Desktop card opens the desktop, whose
noVNC connects; a terminal opened before the desktop then has its DISPLAY, and 004's
`roslaunch turtle_tf2 turtle_tf2_demo.launch rviz:=true` typed there shows turtlesim's window and
rviz on the desktop: found by title on the VNC server's display (xwininfo), and seen in the
browser's screenshot of the desktop (turtlesim's blue canvas; rviz's view, not blank, with the
TF axes' red). The desktop's X session has the course and the overlay sourced, no reference
solution. Without Jupyter's token, /desktop/ and its websocket are refused.

One workbench for the module, one desktop."""
from __future__ import annotations

import io
import os
import re
import shutil
import tempfile
from typing import Dict

import pytest

from course_sandbox import env_paths
from course_testkit.browser import chromium, require_browser
from course_checks.isolation import pids_with_token
from course_testkit.jupyter import refused_websocket
from course_testkit.screen import colour_share, colour_stats
from course_checks.waiting import wait_for
from course_testkit.workbench import REFERENCE_MARKERS, Workbench, open_from_launcher
from course_testkit.xwindows import XWindow, largest_titled, shown_windows
from course_workbench.startup import DISPLAY_FILE_VAR
from turtlesim.constants import DEFAULT_BACKGROUND_RGB

require_browser()
for _tool, _package in (("vncserver", "tigervnc-standalone-server"), ("jwm", "jwm"), ("xwininfo", "x11-utils")):
    if shutil.which(_tool) is None:
        pytest.skip("%s is not installed (Debian's %s, setup/apt-packages.txt)" % (_tool, _package),
                    allow_module_level=True)

LAUNCHER_TITLE = "Desktop"  # jupyter-remote-desktop-proxy's launcher entry
PAGE_TITLE = "<title>Jupyter Remote Desktop Proxy</title>"
VIEWER_SCRIPT = "/desktop/static/dist/viewer.js"
# Wide and tall enough that the desktop (noVNC resizes it to the page) holds the xterm, turtlesim
# and rviz side by side: JWM places new windows where they overlap none.
WINDOW = (1800, 1500)
# rviz's TF display draws each frame's x axis red (turtle1, turtle2, world): a few hundred pixels;
# nothing else in rviz's window is red.
RVIZ_RED_PIXELS = 50
# rviz's death, as soon as roslaunch reports it: the first thing a flaky run's reader needs (see rviz_death)
RVIZ_DIED = "rviz died while starting; roslaunch's log:\n%s"
# Debian 12's Ogre/Mesa race (docs/workbench.md#rviz-can-close-itself-at-start-up): rviz aborts on
# glibc's heap check, or on the mutex it finds overwritten, within its first second.
HEAP_OVERRUN = ("malloc(): ", "free(): ", "corrupted ", "double free", "boost::lock_error")
# The page's state: noVNC's status line, and where its canvas is (page pixels per desktop pixel).
VIEWER_STATE = """
const s = document.getElementById('status'), c = document.querySelector('#screen canvas');
if (!s || !c || !c.width) return {status: s ? s.textContent : null};
const r = c.getBoundingClientRect();
return {status: s.textContent, left: r.left, top: r.top, scale: r.width / c.width, width: c.width, height: c.height};
"""


@pytest.fixture(scope="module")
def bench():
    with Workbench() as workbench:
        yield workbench


def test_the_desktop_and_its_websocket_are_behind_jupyters_login(bench):
    status, data, _ = bench.request("GET", "/desktop/")
    assert status == 200 and PAGE_TITLE in data.decode(errors="replace")
    for token in (None, "not-the-token"):
        status, data, headers = bench.request("GET", "/desktop/", token=token, follow=False)
        assert status in (302, 403) and PAGE_TITLE not in data.decode(errors="replace"), status
        if status == 302:
            assert "/login" in headers.get("Location", "")
    assert bench.status(VIEWER_SCRIPT) == 200  # noVNC itself, served by the package behind the login too
    assert bench.status(VIEWER_SCRIPT, token=None) in (302, 403)
    assert bench.status(VIEWER_SCRIPT, token="not-the-token") in (302, 403)
    ws = "ws://127.0.0.1:%d/desktop-websockify/" % bench.port
    assert refused_websocket(ws) == 403
    assert refused_websocket(ws + "?token=not-the-token") == 403


def window_manager_env(bench: Workbench) -> Dict[str, str]:
    """The environment of the desktop's window manager (the X session's): {} before it runs."""
    for pid in pids_with_token(bench.run_token):
        try:
            with open("/proc/%d/cmdline" % pid, "rb") as f:
                if os.path.basename(f.read().split(b"\0")[0]) != b"jwm":
                    continue
            with open("/proc/%d/environ" % pid, "rb") as f:
                return dict(e.decode(errors="replace").split("=", 1) for e in f.read().split(b"\0") if b"=" in e)
        except OSError:
            continue
    return {}


def overlap(a: XWindow, b: XWindow) -> bool:
    return a.x < b.x + b.width and b.x < a.x + a.width and a.y < b.y + b.height and b.y < a.y + a.height


def rviz_death(bench: Workbench) -> str:
    """roslaunch's line for rviz's death in ~/demo.log with the 8 lines before it (rviz's last words,
    e.g. glibc's heap check), '' while rviz runs. Debian 12's rviz can die so at start-up under load:
    Ogre creates its render window on one X connection and Mesa's software GLX asks its size on
    another; when the X server answers the second first, Mesa renders into buffers sized from an
    uninitialised width and height and overruns the heap (Debian's Ogre and Mesa, not the course)."""
    try:
        with open(os.path.join(bench.home, "demo.log"), errors="replace") as f:
            lines = re.sub(r"\x1b\[[0-9;]*m", "", f.read()).splitlines()  # without roslaunch's colours
    except OSError:
        return ""
    for i, line in enumerate(lines):
        if line.startswith("[rviz-") and "process has died" in line:
            return "\n".join(lines[max(0, i - 8):i + 1])
    return ""


def check_rviz_alive(bench: Workbench) -> None:
    """Fail at once when rviz died; an expected failure (xfail) when it died of the Debian 12
    Ogre/Mesa race, told by its words (HEAP_OVERRUN, then an abort): outside the course, seen in
    1 to 5 of 20 starts under load, and no verdict on the desktop either way."""
    death = rviz_death(bench)
    if not death:
        return
    if any(words in death for words in HEAP_OVERRUN) and "exit code -6" in death:
        pytest.xfail("rviz aborted at start-up on Debian's Ogre/Mesa window-size race:\n%s" % death)
    pytest.fail(RVIZ_DIED % death)


def desktop_display(bench: Workbench) -> str:
    """The display the desktop's X session wrote for the terminals ('' before it runs)."""
    path = os.path.join(bench.home, ".local", "share", "course-workbench", "display-%d" % bench.port)
    try:
        with open(path) as f:
            return f.read().strip()
    except OSError:
        return ""


def test_the_launchers_desktop_shows_turtlesim_and_rviz_started_in_a_terminal(bench):
    from PIL import Image

    with bench.terminal() as term, chromium(window=WINDOW) as browser:
        code, said = term.run('echo "[${DISPLAY:-none}] $%s"' % DISPLAY_FILE_VAR)
        assert code == 0 and "[none]" in said, said  # no desktop yet: no DISPLAY (turtlesim runs offscreen)

        open_from_launcher(browser, bench, LAUNCHER_TITLE, "desktop/")
        state = lambda: browser.execute_script(VIEWER_STATE) or {}  # noqa: E731
        assert wait_for(lambda: state().get("status") == "Connected", 60, 0.2), (state(), bench.output()[-3000:])
        assert wait_for(lambda: desktop_display(bench), 30, 0.1), "the X session wrote no display"
        display = desktop_display(bench)
        xauthority = os.path.join(bench.home, ".Xauthority")

        # the terminal, opened before the desktop, now shows its windows there
        code, said = term.run('echo "[$DISPLAY]"')
        assert "[%s]" % display in said, (display, said)

        # the X session: the course and the student's overlay sourced, no reference solution
        session = wait_for(lambda: window_manager_env(bench), 30, 0.1)
        assert session, "no window manager on the desktop: %s" % bench.processes("")
        package_path = session.get("ROS_PACKAGE_PATH", "").split(":")
        assert os.path.join(bench.home, "catkin_ws", "src") in package_path, package_path
        paths = "".join(session.get(var, "") + ":" for var in env_paths.FOLDER_LISTS)
        assert not [m for m in REFERENCE_MARKERS if m in paths], paths
        # beside the browser, a websocket with the token reaches the same VNC server, which speaks first
        assert bench.desktop_greeting().startswith(b"RFB 003."), "no VNC server behind /desktop-websockify/"

        code, said = term.run("roslaunch turtle_tf2 turtle_tf2_demo.launch rviz:=true > ~/demo.log 2>&1 &")
        assert code == 0, said

        def windows():
            """turtlesim's and rviz's windows, once both are on the screen (rviz's main window
            shows after its splash)."""
            shown = shown_windows(display, xauthority)
            turtlesim, rviz = largest_titled(shown, "TurtleSim"), largest_titled(shown, "RViz")
            return (turtlesim, rviz) if turtlesim and rviz and rviz.width > 300 else None
        try:
            found = wait_for(lambda: rviz_death(bench) or windows(), 120, 0.5)
            check_rviz_alive(bench)
            assert found, "windows on %s: %s; %s" % (display, shown_windows(display, xauthority),
                                                     term.run("tail -n 20 ~/demo.log")[1])
            assert (found[0].width, found[0].height) == (500, 500)
            shots = []

            def seen():
                """The desktop as the browser shows it, the windows where they are now: the share
                of turtlesim's blue in turtlesim's part of the screenshot, the colours of rviz's part."""
                turtlesim, rviz = windows() or found
                assert not overlap(turtlesim, rviz), (turtlesim, rviz)  # each part is its window's own
                where = state()
                shots[:] = [browser.get_screenshot_as_png()]
                shot = Image.open(io.BytesIO(shots[0])).convert("RGB")

                def part(window):
                    left, top, scale = where["left"], where["top"], where["scale"]
                    box = (left + scale * window.x, top + scale * window.y,
                           left + scale * (window.x + window.width), top + scale * (window.y + window.height))
                    return list(shot.crop(tuple(round(v) for v in box)).getdata())
                return colour_share(part(turtlesim), DEFAULT_BACKGROUND_RGB), colour_stats(part(rviz))

            def drawn(blue_and_rviz) -> bool:
                blue, rviz_colours = blue_and_rviz
                return blue > 0.9 and not rviz_colours.looks_blank() and rviz_colours.reddish >= RVIZ_RED_PIXELS
            # rviz draws the TF axes (x red) once it has the frames; turtlesim its canvas from the first frame
            drawn_or_dead = wait_for(lambda: rviz_death(bench) or drawn(seen()), 60, 0.5)
            check_rviz_alive(bench)
            if not drawn_or_dead:
                fd, path = tempfile.mkstemp(prefix="workbench-desktop-", suffix=".png")
                with os.fdopen(fd, "wb") as out:
                    out.write(shots[0])
                blue, rviz_colours = seen()
                # roslaunch's own words (a node that died, rviz's last lines): what a flaky run needs
                pytest.fail("turtlesim's window: %.2f of it turtlesim's blue; rviz's: %s (windows %s, screenshot %s);"
                            " the demo's log ends: %s; rviz's: %s"
                            % (blue, rviz_colours, windows(), path, term.run("tail -n 30 ~/demo.log")[1],
                               term.run("tail -n 30 $(ls -t ~/.ros/log/latest/rviz*.log 2>/dev/null | head -1)"
                                        " 2>/dev/null")[1]))
        finally:
            term.run("kill %1; wait")
