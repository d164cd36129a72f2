"""A real browser for tests: Debian's chromium, headless, driven by selenium through chromedriver.

`require_browser()` skips the calling test module, saying what to install, when python3-selenium,
chromium or chromium-driver is missing; `chromium()` is the driver, quit however the test ends.
"""
from __future__ import annotations

import contextlib
import shutil
from typing import Iterator, Tuple

import pytest

from course_checks.isolation import port_below_ephemeral_range

TIMEOUT_S = 60.0
WINDOW = (1280, 1400)
ARGUMENTS = ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
             "--no-first-run", "--disable-extensions")


def require_browser() -> None:
    pytest.importorskip("selenium.webdriver", reason="python3-selenium is not installed (setup/apt-packages.txt)")
    if shutil.which("chromium") is None or shutil.which("chromedriver") is None:
        pytest.skip("Debian's chromium and chromium-driver are not installed (setup/apt-packages.txt)",
                    allow_module_level=True)


@contextlib.contextmanager
def chromium(window: Tuple[int, int] = WINDOW, timeout: float = TIMEOUT_S,
             arguments: Tuple[str, ...] = ()) -> Iterator["object"]:
    """A headless chromium's selenium driver (page-load and script timeouts set), with these
    command-line arguments beside the usual ones."""
    require_browser()
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service as ChromeService
    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium")
    for argument in ARGUMENTS + ("--window-size=%d,%d" % window,) + tuple(arguments):
        options.add_argument(argument)
    # chromedriver binds the port it is given: one no ROS node of a test beside can take first.
    service = ChromeService(executable_path=shutil.which("chromedriver"), port=port_below_ephemeral_range())
    driver = webdriver.Chrome(service=service, options=options)
    try:
        driver.set_page_load_timeout(timeout)
        driver.set_script_timeout(timeout)
        yield driver
    finally:
        driver.quit()
