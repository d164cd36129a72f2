"""The page's simulator panels in a real browser, in 003 Part II's world (RRBot and a coke can).

The 3-D view streams the simulator's free camera: gzclient's default view shows RRBot; the wheel
zooms in until RRBot's orange and the coke can's red both show; dragging orbits the camera (the
simulator applies the new view, and the picture changes); the camera panel picks RRBot's own camera by itself. Screenshots of
both panels are kept in the artifact folder and checked for content.
"""
from __future__ import annotations

import asyncio
import math

import numpy as np
import pytest

from course_checks.artifacts import artifact_path
from course_testkit.browser import require_browser
from course_testkit.pictures import changed_pixels, load_png, orange_pixels, red_pixels
from course_checks.waiting import wait_for

require_browser()
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402

TIMEOUT_S = 90.0  # MuJoCo's first render and the world's start on a loaded 2-core machine
VIEW = "/gazebo/free_camera/view"
EMPTY_CANVAS = (0x22, 0x22, 0x33)  # lab.css: an image canvas before its first picture


def frames(driver, canvas_id):
    return int(driver.find_element(By.ID, canvas_id).get_attribute("data-frames") or 0)


def canvas_png(driver, canvas_id, name):
    path = artifact_path(name, ".png")
    element = driver.find_element(By.ID, canvas_id)
    driver.execute_script("arguments[0].scrollIntoView()", element)
    with open(path, "wb") as out:
        out.write(element.screenshot_as_png)
    return load_png(path)


def simulator_view(lab, client_class):
    """The view the simulator says it applies (its latched topic), read through the bridge."""
    async def scenario():
        client = await client_class.connect(lab.ws_url())
        client.send(op="subscribe", topic=VIEW, type="gazebo_msgs/OrbitView")
        message = await client.expect(lambda m: m.get("topic") == VIEW, timeout=TIMEOUT_S)
        client.close()
        return message["msg"]
    return asyncio.run(scenario())


def test_the_3d_view_shows_rrbot_and_the_can_and_orbits(browser, sim_lab, client_class, open_page):
    open_page(browser, sim_lab)
    assert wait_for(lambda: frames(browser, "view3d-canvas") >= 10, TIMEOUT_S), \
        "the 3-D view drew no pictures: %s" % browser.find_element(By.ID, "view3d-note").text
    seen = {}

    def shows(name, orange, red=0):
        def check():
            seen["picture"] = canvas_png(browser, "view3d-canvas", name)
            return orange_pixels(seen["picture"]).sum() > orange and red_pixels(seen["picture"]).sum() > red
        return wait_for(check, TIMEOUT_S, interval=1.0)

    def counts():
        return "RRBot's orange %d px, the can's red %d px" % (orange_pixels(seen["picture"]).sum(),
                                                            red_pixels(seen["picture"]).sum())
    assert shows("lab_view_3d_default", orange=300), "RRBot is not in gzclient's default view: " + counts()
    start = simulator_view(sim_lab, client_class)
    canvas = browser.find_element(By.ID, "view3d-canvas")
    for _ in range(6):  # the wheel zooms in towards the origin, where the robot stands and the can fell
        browser.execute_script("arguments[0].dispatchEvent(new WheelEvent('wheel', "
                               "{deltaY: -100, bubbles: true, cancelable: true}))", canvas)
    assert wait_for(lambda: simulator_view(sim_lab, client_class)["distance"] < start["distance"] * 0.6, TIMEOUT_S), \
        "the wheel did not zoom in: %s" % simulator_view(sim_lab, client_class)
    assert shows("lab_view_3d_zoomed", orange=300, red=60), "zoomed in, RRBot and the can should show: " + counts()
    before = seen["picture"]
    start = simulator_view(sim_lab, client_class)

    ActionChains(browser).move_to_element(canvas).click_and_hold().move_by_offset(120, 0).move_by_offset(60, 40) \
        .release().perform()
    assert wait_for(lambda: abs(simulator_view(sim_lab, client_class)["azimuth"] - start["azimuth"]) > 1.0,
                    TIMEOUT_S), "dragging on the 3-D view did not orbit the simulator's camera"
    after = simulator_view(sim_lab, client_class)
    assert after["elevation"] != pytest.approx(start["elevation"])
    orbited = {}

    def picture_changed():
        orbited["picture"] = canvas_png(browser, "view3d-canvas", "lab_view_3d_orbited")
        return changed_pixels(before, orbited["picture"]) > 0.05 * before.shape[0] * before.shape[1]
    assert wait_for(picture_changed, TIMEOUT_S, interval=1.0), "the picture did not change when orbiting"
    assert orange_pixels(orbited["picture"]).sum() > 100, "RRBot left the picture when orbiting"

    readout = browser.find_element(By.ID, "view3d-readout").text
    assert "azimuth" in readout and "distance" in readout, readout
    assert math.isfinite(simulator_view(sim_lab, client_class)["azimuth"])


def test_the_camera_panel_picks_rrbots_camera(browser, sim_lab, open_page):
    open_page(browser, sim_lab)
    assert wait_for(lambda: browser.find_element(By.CSS_SELECTOR, "[data-panel=camera]").get_attribute("data-topic"),
                    TIMEOUT_S), "the camera panel picked no topic"
    topic = browser.find_element(By.CSS_SELECTOR, "[data-panel=camera]").get_attribute("data-topic")
    assert topic.startswith("/rrbot/") and topic.endswith("image_raw"), topic
    assert wait_for(lambda: frames(browser, "camera-canvas") >= 5, TIMEOUT_S), "the camera panel drew no pictures"
    picture = canvas_png(browser, "camera-canvas", "lab_view_rrbot_camera")
    # The arm has collapsed, so the camera looks at the grey ground: drawn, not the empty canvas.
    empty = (np.abs(picture.astype(int) - np.array(EMPTY_CANVAS)).sum(axis=2) < 20).mean()
    assert empty < 0.1, "%.0f%% of the camera panel is still the empty canvas" % (100 * empty)
    assert 60 < picture.mean() < 220, "RRBot's camera picture is not the lit ground (mean %.0f)" % picture.mean()
