"""What the open page costs while nothing changes, and that it still hears of every change: a real
master, turtlesim, lab_view and headless chromium.

lab_view is pointed at a relay of the master's XML-RPC API that counts every call, and the page's
HTTP requests are read from the browser's resource timings. With the page open (the graph on
screen) and nothing changing, over WINDOW_S: no HTTP request at all (the page polled /api/health
every second and /api/graph every 2 s, about 26 requests in 12 s, each through JupyterLab's proxy
in the workbench), and only the watch's getSystemState of the master, once a period (about 44
calls before: getSystemState, getTopicTypes and lookupNode for every question). Then, still
without a request: a node that comes and goes shows in the graph (only once the graph is on
screen), turtlesim killed by SIGKILL (registered, silent) and started again changes the header's
words, and the master stopped and started again.
"""
from __future__ import annotations

import time

from course_checks.nodes import find_executable
from course_checks.waiting import wait_for
from course_testkit.browser import require_browser
from course_testkit.master import PrivateMaster, system_state
from course_web.lab_status import STATE_PERIOD_S

require_browser()

WINDOW_S = 12.0
TIMEOUT_S = 60.0
HEALTH = "const h = document.getElementById('ros-health'); return [h.dataset.state, h.textContent];"
REQUESTS = "return performance.getEntriesByType('resource').map((entry) => entry.name);"
GRAPH = """
const names = [...document.querySelectorAll('#graph-svg g.vertex')].map((g) => g.dataset.name);
const edges = [...document.querySelectorAll('#graph-svg path.edge')].map((p) => p.dataset.from + ' ' + p.dataset.to);
return [names, edges, document.getElementById('panel-graph').dataset.watching];
"""
# What lab_view registers for the page (the canvas, teleop, TF tree): once the graph shows them,
# the page's start (subscriptions, the canvas's service call) is over.
PAGE_EDGES = {"/turtlesim/scene /lab_view", "/lab_view /turtle1/cmd_vel", "/tf /lab_view", "/tf_static /lab_view"}


def health(driver):
    return driver.execute_script(HEALTH)


def graph(driver):
    """(vertex names, edges as 'from to', whether the graph panel is told the graph)."""
    names, edges, watching = driver.execute_script(GRAPH)
    return set(names), set(edges), watching


def show_graph(driver, shown: bool) -> None:
    """Scroll the graph panel into view, or the page back to its top (the graph out of sight)."""
    driver.execute_script("document.getElementById('panel-graph').scrollIntoView()" if shown
                          else "window.scrollTo(0, 0)")
    assert wait_for(lambda: graph(driver)[2] == str(shown).lower(), TIMEOUT_S), graph(driver)


def settled(driver) -> bool:
    frames = driver.execute_script("return Number(document.getElementById('turtle-canvas').dataset.frames || 0)")
    return health(driver)[0] == "ok" and PAGE_EDGES <= graph(driver)[1] and frames >= 1


def test_the_open_page_asks_nothing_while_nothing_changes(browser, counted_lab, open_page):
    open_page(browser, counted_lab)
    show_graph(browser, True)
    assert wait_for(lambda: settled(browser), TIMEOUT_S), (health(browser), graph(browser))
    browser.execute_script("performance.clearResourceTimings()")
    before = counted_lab.relay.counted()
    time.sleep(WINDOW_S)  # the window observed, not a wait for anything
    asked = counted_lab.relay.counted() - before
    requests = browser.execute_script(REQUESTS)
    print("in %.0f s with the page open: %d HTTP requests, lab_view asked the master %s"
          % (WINDOW_S, len(requests), dict(asked)))
    assert requests == [], "the page polled its server: %s" % requests
    assert asked["getSystemState"] <= WINDOW_S / STATE_PERIOD_S + 1, asked
    others = sum(asked.values()) - asked["getSystemState"]
    assert others <= 1, "lab_view asked the master more than its system state: %s" % asked
    assert settled(browser), "the page lost what it showed"


def test_the_page_hears_of_each_change_without_asking(browser, counted_lab, open_page, turtlesim):
    open_page(browser, counted_lab)
    assert wait_for(lambda: health(browser)[0] == "ok", TIMEOUT_S), health(browser)
    browser.execute_script("performance.clearResourceTimings()")
    # a node comes while the graph is out of sight; once in sight, the graph shows it
    show_graph(browser, False)
    extra = counted_lab.master.start([find_executable("topic_tools", "relay"), "/turtle1/pose", "/pose_copy",
                                  "__name:=pose_relay"], "pose_relay")
    try:
        assert wait_for(lambda: "/pose_relay" in dict(system_state(counted_lab.master.uri)[0]).get("/pose_copy", []),
                        TIMEOUT_S)
        assert "/pose_relay" not in graph(browser)[0]
        show_graph(browser, True)
        assert wait_for(lambda: {"/pose_relay", "/pose_copy"} <= graph(browser)[0], TIMEOUT_S), graph(browser)
    finally:
        counted_lab.master.stop_node(extra)
    assert wait_for(lambda: "/pose_relay" not in graph(browser)[0], TIMEOUT_S), "a stopped node stayed"
    # turtlesim killed by SIGKILL stays registered, silent: only asking it tells
    counted_lab.turtlesim.end()
    counted_lab.master.stop_node(counted_lab.turtlesim)
    assert wait_for(lambda: health(browser)[0] == "no-publisher", TIMEOUT_S), health(browser)
    assert "/turtlesim is still registered, but does not answer" in health(browser)[1]
    counted_lab.turtlesim = counted_lab.master.start(turtlesim, "turtlesim-again")
    assert wait_for(lambda: health(browser)[0] == "ok", TIMEOUT_S), health(browser)
    assert health(browser)[1] == ""
    assert browser.execute_script(REQUESTS) == [], "the page polled its server"


def test_the_page_says_when_the_master_stops_and_follows_it_back(browser, open_page, lab_on, turtlesim):
    master = PrivateMaster()  # not entered: the test stops and starts the master itself
    try:
        core = master.start(master.command(), "rosmaster")
        assert wait_for(master.ready, TIMEOUT_S), "the master did not start"
        lab = lab_on(master)
        open_page(browser, lab)
        assert wait_for(lambda: health(browser)[0] == "ok", TIMEOUT_S), health(browser)
        master.stop_node(core)  # the student stops roscore: lab_view and turtlesim stay
        assert wait_for(lambda: health(browser)[0] == "no-master", TIMEOUT_S), health(browser)
        said = health(browser)[1]
        assert said.startswith("The ROS master at %s does not answer" % master.uri) and "roscore" in said, said
        master.start(master.command(), "rosmaster-again")
        assert wait_for(master.ready, TIMEOUT_S), "the master did not start again"
        # a new master knows no turtlesim (nodes do not register again by themselves) ...
        assert wait_for(lambda: health(browser)[0] == "no-publisher", TIMEOUT_S), health(browser)
        master.start(turtlesim, "turtlesim-again")  # ... until the student starts one
        assert wait_for(lambda: health(browser)[0] == "ok", TIMEOUT_S), health(browser)
    finally:
        master.stop()
