"""The page in a real browser: headless Debian chromium, driven by selenium through chromedriver.

It loads; its canvas follows turtlesim (pixels change when the turtle moves, a red pen draws a red
line: the page draws them from turtlesim's ~scene); a hidden page takes no updates and is whole
again when shown; arrow keys pressed
in the page move the turtle; the console shows turtlesim's warning and the level filter hides
INFO; the plot draws /turtle1/pose/x:y (both lines, in rqt_plot's colours), says why a path
cannot be plotted, and drops a late answer to an older path; the node graph shows turtlesim and
the page's own node and follows nodes that come and go (test_lab_view_steady: what the page asks
while nothing changes, and the header's words); the TF tree nests a static and a moving
frame. Screenshots are saved to the artifact folder and checked for content. The simulator's
panels are in test_lab_view_simulator.
"""
from __future__ import annotations

import asyncio
import math
import os

import pytest

from course_checks.artifacts import artifact_path
from course_testkit.browser import require_browser
from course_checks.nodes import find_executable
from course_testkit.master import system_state
from course_testkit.pictures import load_png
from course_checks.waiting import wait_for

require_browser()
from PIL import Image  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402
import numpy as np  # noqa: E402

BACKGROUND = (69, 86, 255)
TIMEOUT_S = 60.0
CANVAS_STATS = """
const canvas = document.getElementById('turtle-canvas');
const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
const bg = arguments[0];
let background = 0, other = 0, sum = 0;
for (let i = 0; i < data.length; i += 4) {
  const near = Math.abs(data[i] - bg[0]) + Math.abs(data[i + 1] - bg[1]) + Math.abs(data[i + 2] - bg[2]) < 30;
  if (near) background += 1; else { other += 1; sum = (sum + i * (data[i] + 2 * data[i + 1] + 3 * data[i + 2])) % 1000000007; }
}
return {background: background, other: other, digest: sum, frames: Number(canvas.dataset.frames || 0)};
"""


def call(lab, client_class, service, args):
    """Call a service through the bridge from the test (the test is no ROS node)."""
    async def scenario():
        client = await client_class.connect(lab.ws_url())
        client.send(op="call_service", id="call", service=service, args=args)
        reply = await client.expect(lambda m: m.get("id") == "call", timeout=TIMEOUT_S)
        client.close()
        return reply
    reply = asyncio.run(scenario())
    assert reply["result"], reply
    return reply["values"]


def pose(lab, client_class):
    async def scenario():
        client = await client_class.connect(lab.ws_url())
        client.send(op="subscribe", topic="/turtle1/pose")
        message = await client.expect(lambda m: m.get("topic") == "/turtle1/pose", timeout=TIMEOUT_S)
        client.close()
        return message["msg"]
    return asyncio.run(scenario())


def canvas_stats(driver):
    return driver.execute_script(CANVAS_STATS, list(BACKGROUND))


def canvas_colour_count(driver, colour):
    """How many pixels of the page's canvas are `colour` (give or take the lines' antialiased edges)."""
    return driver.execute_script("""
const canvas = document.getElementById('turtle-canvas');
const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
const c = arguments[0];
let count = 0;
for (let i = 0; i < data.length; i += 4) {
  if (Math.abs(data[i] - c[0]) + Math.abs(data[i + 1] - c[1]) + Math.abs(data[i + 2] - c[2]) < 30) count += 1;
}
return count;""", list(colour))


def test_the_page_loads_with_its_panels(browser, lab, open_page):
    open_page(browser, lab)
    panels = [element.get_attribute("data-panel") for element in browser.find_elements(By.CSS_SELECTOR, "[data-panel]")]
    assert {"canvas", "teleop", "console", "graph", "tf", "plot", "camera", "view3d", "health"} <= set(panels)
    assert browser.title == "The lab in a browser"


def test_the_canvas_follows_the_turtle(browser, lab, client_class, open_page):
    open_page(browser, lab)
    call(lab, client_class, "/turtle1/teleport_absolute", {"x": 5.5, "y": 5.5, "theta": 0.0})
    call(lab, client_class, "/clear", {})
    assert wait_for(lambda: canvas_stats(browser)["frames"] >= 1, TIMEOUT_S), "no canvas frames were drawn"
    # Wait for a frame drawn after the clear: only the turtle differs from the background.
    assert wait_for(lambda: canvas_stats(browser)["other"] < 2000, TIMEOUT_S), canvas_stats(browser)
    before = canvas_stats(browser)
    assert before["background"] > 0.9 * 500 * 500, before
    call(lab, client_class, "/turtle1/teleport_absolute", {"x": 2.0, "y": 2.0, "theta": 1.0})
    changed = wait_for(lambda: (lambda now: now if now["digest"] != before["digest"] and now["other"] > before["other"] + 200
                                else None)(canvas_stats(browser)), TIMEOUT_S)
    assert changed, "the canvas did not change after the teleport (a pen line and a moved turtle): %s -> %s" % (
        before, canvas_stats(browser))
    save_and_check(browser, "lab_view_canvas_after_teleport")
    # The page draws the lines itself from turtlesim's ~scene: a red pen's line comes out red.
    call(lab, client_class, "/turtle1/set_pen", {"r": 255, "g": 0, "b": 0, "width": 5, "off": 0})
    call(lab, client_class, "/turtle1/teleport_absolute", {"x": 8.0, "y": 2.0, "theta": 0.0})
    assert wait_for(lambda: canvas_colour_count(browser, (255, 0, 0)) > 1000, TIMEOUT_S), \
        "no red line of 6 m (270 px, 5 px wide) on the canvas: %d red pixels" % canvas_colour_count(browser, (255, 0, 0))
    call(lab, client_class, "/turtle1/set_pen", {"r": 179, "g": 184, "b": 255, "width": 3, "off": 0})


# Out of sight and back, as a browser says when the tab changes (document.hidden, visibilitychange).
SET_HIDDEN = """
Object.defineProperty(document, 'hidden', {value: arguments[0], configurable: true});
document.dispatchEvent(new Event('visibilitychange'));
"""


def lab_view_subscribes(lab, topic):
    return "/lab_view" in dict(system_state(lab.master.uri)[1]).get(topic, [])


def test_a_hidden_page_takes_no_canvas_updates_nor_plot_samples(browser, lab, client_class, open_page):
    open_page(browser, lab)
    assert not lab_view_subscribes(lab, "/turtle1/pose"), "the plot streams the pose before it was asked for"
    browser.find_element(By.ID, "plot-path").send_keys(Keys.ENTER)  # plot the field's suggestion
    streams = ("/turtlesim/scene", "/turtle1/pose")  # the canvas's updates, the plot's samples
    assert wait_for(lambda: all(lab_view_subscribes(lab, t) for t in streams), TIMEOUT_S)
    call(lab, client_class, "/turtle1/set_pen", {"r": 0, "g": 0, "b": 0, "width": 0, "off": 1})
    call(lab, client_class, "/turtle1/teleport_absolute", {"x": 2.0, "y": 9.0, "theta": 0.0})
    browser.execute_script(SET_HIDDEN, True)
    assert wait_for(lambda: not any(lab_view_subscribes(lab, t) for t in streams), TIMEOUT_S), \
        "lab_view still takes %s for a hidden page" % [t for t in streams if lab_view_subscribes(lab, t)]
    call(lab, client_class, "/turtle1/set_pen", {"r": 0, "g": 255, "b": 0, "width": 5, "off": 0})
    call(lab, client_class, "/turtle1/teleport_absolute", {"x": 9.0, "y": 9.0, "theta": 0.0})  # 7 m, while hidden
    browser.execute_script(SET_HIDDEN, False)
    assert wait_for(lambda: all(lab_view_subscribes(lab, t) for t in streams), TIMEOUT_S)
    # back in sight, the canvas is whole again: the green line drawn while it was hidden is on it
    assert wait_for(lambda: canvas_colour_count(browser, (0, 255, 0)) > 1000, TIMEOUT_S), \
        "the line drawn while the page was hidden is missing: %d green pixels" % canvas_colour_count(browser, (0, 255, 0))
    call(lab, client_class, "/turtle1/set_pen", {"r": 179, "g": 184, "b": 255, "width": 3, "off": 0})


def test_arrow_keys_in_the_page_move_the_turtle(browser, lab, client_class, open_page):
    open_page(browser, lab)
    call(lab, client_class, "/turtle1/teleport_absolute", {"x": 3.0, "y": 5.5, "theta": 0.0})
    start = pose(lab, client_class)
    body = browser.find_element(By.TAG_NAME, "body")

    def moved():
        body.send_keys(Keys.ARROW_UP)
        return pose(lab, client_class)["x"] > start["x"] + 0.5
    assert wait_for(moved, TIMEOUT_S, interval=0.2), "ArrowUp in the page did not drive the turtle forward"
    assert int(browser.find_element(By.ID, "teleop-count").text) > 0
    turned_from = pose(lab, client_class)

    def turned():
        body.send_keys(Keys.ARROW_LEFT)
        return abs(pose(lab, client_class)["theta"] - turned_from["theta"]) > 0.3
    assert wait_for(turned, TIMEOUT_S, interval=0.2), "ArrowLeft in the page did not turn the turtle"


def test_the_console_shows_turtlesims_warning_and_filters_by_level(browser, lab, client_class, open_page):
    open_page(browser, lab)
    # A linear speed beyond float32's range: turtlesim clamps it and warns on /rosout.
    async def bad_command():
        client = await client_class.connect(lab.ws_url())
        client.send(op="publish", topic="/turtle1/cmd_vel", msg={"linear": {"x": 1e39}})
        await client.receive(1.0)
        client.close()

    def warned():
        asyncio.run(bad_command())
        return browser.execute_script(
            "return [...document.querySelectorAll('#console-table tr[data-level=\"4\"]')]"
            ".some(tr => !tr.hidden && tr.textContent.includes(\"beyond float32's range\"))")
    assert wait_for(warned, TIMEOUT_S, interval=1.0), "turtlesim's warning did not reach the console"
    info_rows = "return [...document.querySelectorAll('#console-table tr[data-level=\"2\"]')].filter(tr => !tr.hidden).length"
    call(lab, client_class, "/clear", {})  # turtlesim says "Clearing turtlesim." at INFO
    assert wait_for(lambda: browser.execute_script(info_rows) > 0, TIMEOUT_S), "turtlesim's INFO line did not show"
    browser.find_element(By.CSS_SELECTOR, "#console-level option[value='4']").click()
    assert browser.execute_script(info_rows) == 0
    save_and_check(browser, "lab_view_console_warning")


PLOT_COLOURS = {"C0": (0x1f, 0x77, 0xb4), "C1": (0xff, 0x7f, 0x0e)}


def colour_rows(image, colour, tolerance=40):
    """The rows of `image` with at least one pixel of `colour`."""
    return np.nonzero((np.abs(image.astype(int) - np.array(colour)).sum(axis=2) < tolerance).any(axis=1))[0]


def element_png(driver, element_id, name):
    """A screenshot of one element, kept in the artifact folder, as an RGB array."""
    path = artifact_path(name, ".png")
    with open(path, "wb") as out:
        out.write(driver.find_element(By.ID, element_id).screenshot_as_png)
    return load_png(path)


def test_the_plot_draws_the_turtles_pose(browser, lab, client_class, open_page):
    open_page(browser, lab)
    path = browser.find_element(By.ID, "plot-path")
    path.clear()
    path.send_keys("/turtle1/pose/x:y", Keys.ENTER)
    assert wait_for(lambda: browser.execute_script(
        "return document.getElementById('plot-legend').textContent"), TIMEOUT_S), "the plot named no fields"
    legend = browser.find_element(By.ID, "plot-legend").text
    assert "/turtle1/pose/x" in legend and "/turtle1/pose/y" in legend, legend
    for x, y in ((2.0, 8.0), (8.0, 2.0), (5.0, 5.0)):  # steps, so both lines span the height
        call(lab, client_class, "/turtle1/teleport_absolute", {"x": x, "y": y, "theta": 0.0})
        samples = int(browser.find_element(By.CSS_SELECTOR, "[data-panel=plot]").get_attribute("data-samples") or 0)
        assert wait_for(lambda: int(browser.find_element(By.CSS_SELECTOR, "[data-panel=plot]")
                                    .get_attribute("data-samples") or 0) > samples + 20, TIMEOUT_S), "no new samples"
    plot = element_png(browser, "plot-canvas", "lab_view_plot")
    for name, colour in PLOT_COLOURS.items():
        rows = colour_rows(plot, colour)
        assert len(rows) > 40, "the %s line (%s) spans only %d rows of the plot" % (name, colour, len(rows))


def test_a_plot_path_that_cannot_be_plotted_says_why(browser, lab, open_page):
    open_page(browser, lab)
    path = browser.find_element(By.ID, "plot-path")
    for typed, said in (("/turtle1/pose/z", "has no field z"), ("/turtle9/pose/x:y", "does not exist"),
                        ("/rosout/msg", "not numeric")):
        path.clear()
        path.send_keys(typed, Keys.ENTER)
        assert wait_for(lambda: said in browser.find_element(By.ID, "plot-message").text, TIMEOUT_S), \
            "%s: the page said %r" % (typed, browser.find_element(By.ID, "plot-message").text)


# Before the page's own scripts: the first /api/plot answer (the default plot the page asks for
# when it opens) is held until window.heldPlot.release() is called.
HOLD_FIRST_PLOT_ANSWER = """
(() => {
  const realFetch = window.fetch.bind(window);
  let held = false;
  window.heldPlot = {release: null};
  window.fetch = (url, options) => {
    const answer = realFetch(url, options);
    if (held || !String(url).includes('/api/plot')) return answer;
    held = true;
    return new Promise((resolve, reject) => {
      window.heldPlot.release = () => answer.then(resolve, reject);
    });
  };
})();
"""


def test_a_late_answer_to_an_older_plot_is_dropped(browser, lab, open_page):
    """A path typed before the answer for the one asked before it comes back must win. The answer for the old path was applied when it came last: it wiped the new
    path's error (the flake this test makes certain: "the page said ''")."""
    script = browser.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument", {"source": HOLD_FIRST_PLOT_ANSWER})
    try:
        open_page(browser, lab)
        path = browser.find_element(By.ID, "plot-path")
        path.send_keys(Keys.ENTER)  # the field's suggestion, /turtle1/pose/x:y: its answer is held
        assert wait_for(lambda: browser.execute_script("return window.heldPlot.release !== null"), TIMEOUT_S)
        path.clear()
        path.send_keys("/turtle1/pose/z", Keys.ENTER)
        plot_panel = browser.find_element(By.CSS_SELECTOR, "[data-panel=plot]")
        assert wait_for(lambda: plot_panel.get_attribute("data-answers") == "1", TIMEOUT_S)
        browser.execute_script("window.heldPlot.release()")
        assert wait_for(lambda: plot_panel.get_attribute("data-answers") == "2", TIMEOUT_S), \
            "the held answer never came back"
        assert "has no field z" in browser.find_element(By.ID, "plot-message").text
        assert browser.find_element(By.ID, "plot-legend").text == "", "the old plot's fields came back"
    finally:
        browser.execute_cdp_cmd("Page.removeScriptToEvaluateOnNewDocument", script)


def graph_names(driver):
    return set(driver.execute_script(
        "return [...document.querySelectorAll('#graph-svg g.vertex')].map(g => g.dataset.name)"))


def graph_edges(driver):
    return set(driver.execute_script(
        "return [...document.querySelectorAll('#graph-svg path.edge')].map(p => p.dataset.from + ' ' + p.dataset.to)"))


def test_the_graph_shows_the_nodes_and_refreshes(browser, lab, open_page):
    open_page(browser, lab)
    browser.execute_script("document.getElementById('graph-svg').scrollIntoView()")  # told only while on screen
    assert wait_for(lambda: {"/turtlesim", "/turtle1/cmd_vel", "/turtle1/pose", "/lab_view"} <= graph_names(browser),
                    TIMEOUT_S), graph_names(browser)
    # The page's teleop publishes cmd_vel through lab_view: publisher -> topic -> subscriber.
    wanted = {"/lab_view /turtle1/cmd_vel", "/turtle1/cmd_vel /turtlesim", "/turtlesim /turtle1/pose"}
    assert wait_for(lambda: wanted <= graph_edges(browser), TIMEOUT_S), graph_edges(browser)
    assert "/rosout" not in graph_names(browser)  # hidden, as in rqt_graph
    extra = lab.master.start([find_executable("topic_tools", "relay"), "/turtle1/pose", "/pose_copy",
                              "__name:=pose_relay"], "pose_relay")
    try:
        assert wait_for(lambda: {"/pose_relay", "/pose_copy"} <= graph_names(browser), TIMEOUT_S), \
            "a new node did not appear: %s" % graph_names(browser)
    finally:
        lab.master.stop_node(extra)
    assert wait_for(lambda: "/pose_relay" not in graph_names(browser), TIMEOUT_S), "a stopped node stayed"
    picture = element_png(browser, "graph-svg", "lab_view_graph")
    ink = int((picture.astype(int).sum(axis=2) < 500).sum())  # the outlines, arrows and names
    assert ink > 1500 and picture.shape[1] > 400, "the graph picture is nearly empty: %d dark pixels, %s" % (
        ink, picture.shape)


def test_the_tf_tree_shows_static_and_moving_frames(browser, lab, client_class, open_page):
    static = lab.master.start([find_executable("tf2_ros", "static_transform_publisher"),
                               "1", "0", "0", "0", "0", "0", "world", "turtle_base"], "static_tf")
    moving = lab.master.start(["rostopic", "pub", "-r", "20", "/tf", "tf2_msgs/TFMessage",
                               "transforms: [{header: {frame_id: turtle_base}, child_frame_id: turtle_head, "
                               "transform: {rotation: {w: 1.0}}}]"], "moving_tf")
    try:
        open_page(browser, lab)
        nested = ("return !!document.querySelector('#tf-tree li[data-frame=\"world\"] > ul > "
                  "li[data-frame=\"turtle_base\"] > ul > li[data-frame=\"turtle_head\"]')")
        assert wait_for(lambda: browser.execute_script(nested), TIMEOUT_S), \
            "world > turtle_base > turtle_head not shown: %s" % browser.find_element(By.ID, "tf-tree").text
        text = browser.find_element(By.ID, "tf-tree").text
        assert "turtle_base (static)" in text, text
        assert wait_for(lambda: " Hz" in browser.find_element(By.ID, "tf-tree").text, TIMEOUT_S), text
    finally:
        lab.master.stop_node(moving)
        lab.master.stop_node(static)


PAGE_LOGIC = """
const done = arguments[arguments.length - 1];
Promise.all([import('/js/plot_panel.js'), import('/js/graph_panel.js'), import('/js/view3d_panel.js'),
             import('/js/canvas_panel.js')])
  .then(([plot, graph, view3d, canvas]) => {
    const v = {target: {x: 1, y: 2, z: 0}, azimuth: 0, elevation: 0.2, distance: 4};
    const ranks = graph.layers(['a', 'b', 'c', 'd'],
      [{from: 'a', to: 'b'}, {from: 'b', to: 'c'}, {from: 'c', to: 'a'}, {from: 'c', to: 'd'}, {from: 'x', to: 'a'}]);
    done({
      values: [plot.valueAt({x: 1.5}, [['x', null]]), plot.valueAt({p: [1, 2, 3]}, [['p', 2]]),
               plot.valueAt({p: [1]}, [['p', 5]]), plot.valueAt({d: 'AQID'}, [['d', 1]]),
               plot.valueAt({t: {secs: 3, nsecs: 500000000}}, [['t', null]]), plot.valueAt({b: true}, [['b', null]]),
               plot.valueAt({x: null}, [['x', null]]), plot.valueAt({x: 'text'}, [['x', null]]),
               plot.valueAt({}, [['a', null], ['b', null]])],
      ranks: Object.fromEntries(ranks),
      orbit: view3d.dragged(v, 100, 0, false), tilt: view3d.dragged(v, 0, 1e6, false),
      pan: view3d.dragged(v, 100, 0, true), zoom: view3d.zoomed(v, -1), original: v,
      moved: [canvas.movedOn(['t', 100, 100, 0, 0, 45, 0, 0], 2), canvas.movedOn(['t', 250, 250, 0, 0, 45, 0, 0.8], Math.PI / 0.8),
              canvas.movedOn(['t', 100, 100, 0, 0, 0, 45, 0], 1), canvas.movedOn(['t', 1, 2, 0.5, 3], 1)],
    });
  }).catch((error) => done({error: String(error)}));
"""


def test_the_pages_own_logic(browser, lab, open_page):
    """The page's pure functions, run in the browser: field values as rqt_plot reads them, the graph's
    layers with a cycle, and the orbit maths of the 3-D view."""
    open_page(browser, lab)
    result = browser.execute_async_script(PAGE_LOGIC)
    assert "error" not in result, result
    assert result["values"] == [1.5, 3, None, 2, 3.5, 1, None, None, None]
    ranks = result["ranks"]
    assert sorted(ranks) == ["a", "b", "c", "d"] and all(0 <= r <= 3 for r in ranks.values())
    assert ranks["b"] == ranks["a"] + 1 and ranks["c"] == ranks["b"] + 1 and ranks["d"] == ranks["c"] + 1
    assert result["orbit"]["azimuth"] == pytest.approx(-1.0) and result["orbit"]["target"] == result["original"]["target"]
    assert result["tilt"]["elevation"] == pytest.approx(1.5)  # clamped, never over the top
    pan = result["pan"]
    assert pan["target"]["x"] == pytest.approx(1.0) and pan["target"]["y"] < 2.0  # the ground follows the pointer
    assert pan["azimuth"] == 0 and result["zoom"]["distance"] == pytest.approx(4 / 1.15)
    assert result["original"]["target"] == {"x": 1, "y": 2, "z": 0}  # the functions do not change their input
    # a turtle moved on between ~scene updates (canvas pixels, y down; theta and w counter-clockwise)
    straight, half_circle, sideways, still = result["moved"]
    assert straight[1:4] == pytest.approx([190, 100, 0])
    assert half_circle[1:4] == pytest.approx([250, 250 - 2 * 45 / 0.8, math.pi], abs=1e-6)  # up the canvas, facing west
    assert sideways[1:3] == pytest.approx([100, 55])  # to its left: up the canvas
    assert still == ["t", 1, 2, 0.5, 3]  # an update without velocities: where it was


def save_and_check(driver, name):
    """A screenshot of the page and one of the canvas in the artifact folder, checked for content:
    not blank, and the canvas mostly turtlesim's background colour."""
    page_path = artifact_path(name, ".png")
    assert driver.save_screenshot(page_path)
    canvas_path = artifact_path(name + "_canvas", ".png")
    with open(canvas_path, "wb") as out:
        out.write(driver.find_element(By.ID, "turtle-canvas").screenshot_as_png)
    page = Image.open(page_path).convert("RGB")
    assert len(page.getcolors(1 << 24)) > 20, "%s is nearly blank" % page_path
    canvas = Image.open(canvas_path).convert("RGB")
    pixels = canvas.getdata()
    background = sum(1 for p in pixels if sum(abs(a - b) for a, b in zip(p, BACKGROUND)) < 30)
    assert background > 0.5 * len(pixels), "%s: only %d of %d pixels are turtlesim's background" % (
        canvas_path, background, len(pixels))
    assert os.path.getsize(page_path) > 10000
