"""The page in a real browser: headless Debian chromium, driven by selenium through chromedriver.

It loads; its canvas follows turtlesim (pixels change when the turtle moves); arrow keys pressed
in the page move the turtle; the console shows turtlesim's warning and the level filter hides
INFO; screenshots are saved to the artifact folder and checked for content.
"""
from __future__ import annotations

import asyncio
import os
import shutil

import pytest

from course_testkit.artifacts import artifact_path
from course_testkit.waiting import wait_for

webdriver = pytest.importorskip("selenium.webdriver", reason="python3-selenium is not installed (tools/apt-packages.txt)")
CHROMIUM = shutil.which("chromium")
CHROMEDRIVER = shutil.which("chromedriver")
if CHROMIUM is None or CHROMEDRIVER is None:
    pytest.skip("Debian's chromium and chromium-driver are not installed (tools/apt-packages.txt)",
                allow_module_level=True)

from PIL import Image  # noqa: E402
from selenium.webdriver.chrome.service import Service as ChromeService  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402

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


@pytest.fixture(scope="module")
def browser():
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=1280,1400", "--no-first-run", "--disable-extensions"):
        options.add_argument(argument)
    driver = webdriver.Chrome(service=ChromeService(executable_path=CHROMEDRIVER), options=options)
    driver.set_page_load_timeout(TIMEOUT_S)
    driver.set_script_timeout(TIMEOUT_S)
    try:
        yield driver
    finally:
        driver.quit()


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


def open_page(driver, lab):
    driver.get(lab.url("/"))
    assert wait_for(lambda: driver.execute_script(
        "return document.body.dataset.ready === 'true' && "
        "document.getElementById('connection').dataset.state === 'open'"), TIMEOUT_S), \
        "the page did not connect: %s" % driver.find_element(By.ID, "connection").text


def test_the_page_loads_with_its_panels(browser, lab):
    open_page(browser, lab)
    panels = [element.get_attribute("data-panel") for element in browser.find_elements(By.CSS_SELECTOR, "[data-panel]")]
    assert {"canvas", "teleop", "console", "graph", "tf", "plot", "camera", "view3d"} <= set(panels)
    assert browser.title == "The lab in a browser"


def test_the_canvas_follows_the_turtle(browser, lab, client_class):
    open_page(browser, lab)
    call(lab, client_class, "/turtle1/teleport_absolute", {"x": 5.5, "y": 5.5, "theta": 0.0})
    call(lab, client_class, "/clear", {})
    assert wait_for(lambda: canvas_stats(browser)["frames"] >= 5, TIMEOUT_S), "no canvas frames were drawn"
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


def test_arrow_keys_in_the_page_move_the_turtle(browser, lab, client_class):
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


def test_the_console_shows_turtlesims_warning_and_filters_by_level(browser, lab, client_class):
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
