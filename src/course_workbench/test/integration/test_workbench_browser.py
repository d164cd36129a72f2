"""Headless chromium (course_testkit.browser) opens the workbench: JupyterLab's launcher shows the
lab page, and its card opens the page in a new tab, logged in by Jupyter's cookie alone (no token
in the page's URL), connected to its websocket and drawing turtlesim's canvas. When the student
then starts their own master and a turtlesim (red, to tell it apart), the open page connects
again by itself and draws the student's turtle."""
from __future__ import annotations

from course_testkit.browser import chromium, require_browser
from course_checks.waiting import wait_for
from course_testkit.workbench import Workbench, open_from_launcher

require_browser()

LAUNCHER_TITLE = "ROS lab"
# The page's state: the websocket's, how often it closed, the frames drawn, the canvas's centre pixel.
PAGE_STATE = """
const c = document.getElementById('connection'), v = document.getElementById('turtle-canvas');
if (!c || !v || !v.width) return null;
if (window.closings === undefined) {
  window.closings = 0;
  new MutationObserver(() => { if (c.dataset.state === 'closed') window.closings += 1; })
    .observe(c, {attributes: true, attributeFilter: ['data-state']});
}
const pixel = v.getContext('2d').getImageData(Math.floor(v.width / 2), 20, 1, 1).data;
return {state: c.dataset.state, closings: window.closings, frames: Number(v.dataset.frames || 0),
        pixel: [pixel[0], pixel[1], pixel[2]]};
"""


# The header's words about the ROS side (course_web's health_panel.js): its state and its sentence.
HEALTH = """
const h = document.getElementById('ros-health');
return h ? [h.dataset.state, h.textContent] : [null, ''];
"""
STUDENT_ROS = ("roscore -p %s > ~/roscore.log 2>&1 & until rostopic list > /dev/null 2>&1; do sleep 0.1; done; "
               "rosrun turtlesim turtlesim_node _background_r:=255 _background_g:=0 _background_b:=0 "
               "> ~/turtlesim.log 2>&1 &")  # (a node given _params needs its master up: rospy sets them first)


def is_red(pixel) -> bool:
    """Red, give or take a few levels."""
    return bool(pixel) and pixel[0] > 200 and pixel[1] < 60 and pixel[2] < 60


def test_the_launcher_opens_the_lab_page_which_follows_the_students_master():
    with Workbench() as bench, chromium() as browser:
        open_from_launcher(browser, bench, LAUNCHER_TITLE, "roslab/")

        def state():
            return browser.execute_script(PAGE_STATE) or {"state": None, "closings": 0, "frames": 0, "pixel": None}
        assert wait_for(lambda: state()["frames"] >= 1, 60, 0.2), "the page drew no turtlesim canvas: %s" % state()
        first = state()
        assert first["state"] == "open" and browser.title == "The lab in a browser"
        assert first["pixel"][2] > 200 and first["pixel"][0] < 100, first  # turtlesim's blue

        # the student's own master and turtlesim, red: the open page moves to them by itself
        port = bench.master_uri.rsplit(":", 1)[1]
        with bench.terminal() as term:
            code, said = term.run(STUDENT_ROS % port)
            assert code == 0, said
            red = wait_for(lambda: is_red(state()["pixel"]) and state()["state"] == "open", 90, 0.25)
            now = state()
            assert red, "the page did not draw the student's turtlesim: %s; %s" % (
                now, term.run("rosnode list 2>&1; tail -n5 ~/roscore.log ~/turtlesim.log")[1])
            assert now["closings"] >= 1  # lab_view started again on the student's master ...
            # ... and draws what the student's turtle does (the page draws only when the canvas changes)
            code, said = term.run("rosservice call /turtle1/teleport_relative 1.0 0.5")
            assert code == 0, said
            assert wait_for(lambda: state()["frames"] > now["frames"], 30, 0.2), state()
            assert wait_for(lambda: browser.execute_script(HEALTH)[0] == "ok", 30, 0.2), browser.execute_script(HEALTH)

            # the student's turtlesim killed (SIGKILL: it stays registered, silent), then their master
            # stopped: the header says so, in words
            term.run("kill -KILL %2; wait %2")
            assert wait_for(lambda: browser.execute_script(HEALTH)[0] == "no-publisher", 30, 0.2), \
                browser.execute_script(HEALTH)
            assert "turtlesim is not running" in browser.execute_script(HEALTH)[1]
            term.run("kill -INT %1; wait")
            assert wait_for(lambda: browser.execute_script(HEALTH)[0] == "no-master", 30, 0.2), \
                browser.execute_script(HEALTH)
            assert "does not answer" in browser.execute_script(HEALTH)[1]
            # ... and when they start them again, the words go and the page draws again
            code, said = term.run(STUDENT_ROS % port)
            assert code == 0, said
            back = state()
            assert wait_for(lambda: browser.execute_script(HEALTH)[0] == "ok", 90, 0.25), (
                browser.execute_script(HEALTH), term.run("rosnode list 2>&1; tail -n5 ~/roscore.log")[1])
            assert browser.execute_script(HEALTH)[1] == ""
            assert wait_for(lambda: state()["frames"] > back["frames"] and is_red(state()["pixel"]), 30, 0.2), \
                state()
            term.run("kill %2; kill -INT %1; wait")
