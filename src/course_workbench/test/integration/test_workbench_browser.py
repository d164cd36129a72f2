"""Headless chromium (course_testkit.browser) opens the workbench: JupyterLab's launcher shows the
lab page, and its card opens the page in a new tab, logged in by Jupyter's cookie alone (no token
in the page's URL), connected to its websocket and drawing turtlesim's canvas."""
from __future__ import annotations

from course_testkit.browser import chromium, require_browser
from course_testkit.waiting import wait_for
from course_testkit.workbench import Workbench

require_browser()

LAUNCHER_TITLE = "ROS lab"


def test_the_launcher_opens_the_lab_page():
    from selenium.webdriver.common.by import By

    with Workbench() as bench, chromium() as browser:
        browser.get("%s/lab?token=%s" % (bench.url, bench.token))

        def card():
            for element in browser.find_elements(By.CSS_SELECTOR, ".jp-LauncherCard"):
                if LAUNCHER_TITLE in (element.get_attribute("title") or "") + element.text:
                    return element
            return None
        found = wait_for(card, 60, 0.2)
        assert found, "no '%s' card in JupyterLab's launcher; the launcher shows: %s" % (
            LAUNCHER_TITLE, [e.text for e in browser.find_elements(By.CSS_SELECTOR, ".jp-LauncherCard")])
        lab_tab = browser.current_window_handle
        found.click()
        assert wait_for(lambda: len(browser.window_handles) == 2, 30, 0.1), "the card opened no tab"
        browser.switch_to.window([h for h in browser.window_handles if h != lab_tab][0])
        assert wait_for(lambda: browser.current_url.startswith(bench.url + "/roslab/"), 30, 0.1), browser.current_url
        assert "token=" not in browser.current_url  # Jupyter's login cookie is what lets it in

        def state():
            return browser.execute_script(
                "const c = document.getElementById('connection'), v = document.getElementById('turtle-canvas');"
                "return c && v ? [c.dataset.state, Number(v.dataset.frames || 0)] : null;")
        drawn = wait_for(lambda: (state() or [None, 0])[1] >= 10, 60, 0.2)
        assert drawn, "the page drew no turtlesim frames: %s; %s" % (state(), browser.title)
        assert state()[0] == "open"
        assert browser.title == "The lab in a browser"
