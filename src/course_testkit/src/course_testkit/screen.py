"""A private X display for tests (Xvfb on a free display number) and screenshot statistics.

Xvfb picks the number itself (-displayfd), so tests never collide with a display in use, and
runs with -noreset: by default an X server resets itself whenever its last client leaves, and a
client that connects during the reset is refused ("could not connect to display"). A test's
display often has one client at a time (the window under test, a screenshot), so without
-noreset about 1 connection in 16 failed when two clients came and went at once.
`colour_stats` is plain Python over RGB triples, so "is this screenshot blank?" is unit-tested.
"""
from __future__ import annotations

import os
import sys
import subprocess
import tempfile
import time
from collections import Counter
from dataclasses import dataclass
from typing import Iterable, Optional, Tuple

RGB = Tuple[int, int, int]


class VirtualDisplay:
    """Start Xvfb on a free display; stop() (or leaving the `with` block) kills it."""

    def __init__(self, size: Tuple[int, int] = (1024, 768), timeout_s: float = 20.0) -> None:
        self.size = size
        self.timeout_s = timeout_s
        self.process: Optional[subprocess.Popen] = None
        self.display: Optional[str] = None

    def start(self) -> str:
        read_fd, write_fd = os.pipe()
        self.process = subprocess.Popen(
            ["Xvfb", "-displayfd", str(write_fd), "-screen", "0", "%dx%dx24" % self.size, "-nolisten", "tcp",
             "-noreset"],
            pass_fds=(write_fd,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(write_fd)
        number = b""
        deadline = time.monotonic() + self.timeout_s
        with os.fdopen(read_fd, "rb") as pipe:
            while not number.endswith(b"\n") and time.monotonic() < deadline:
                chunk = pipe.read(1)  # Xvfb writes "N\n" once it accepts clients
                if not chunk:
                    break
                number += chunk
        if not number.strip().isdigit():
            self.stop()
            raise RuntimeError("Xvfb did not report a display number (is the package xvfb installed?)")
        self.display = ":" + number.strip().decode()
        return self.display

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.process = None

    def __enter__(self) -> "VirtualDisplay":
        self.start()
        return self

    def __exit__(self, *exc) -> None:
        self.stop()


@dataclass(frozen=True)
class ColourStats:
    pixels: int
    distinct: int
    dominant_share: float  # fraction of pixels with the most common colour
    reddish: int  # pixels that are clearly red (rviz draws the x axis of a TF frame red)

    def looks_blank(self, min_distinct: int = 16, max_dominant_share: float = 0.98) -> bool:
        return self.distinct < min_distinct or self.dominant_share > max_dominant_share


def colour_stats(pixels: Iterable[RGB]) -> ColourStats:
    counts: Counter = Counter()
    reddish = 0
    for r, g, b in pixels:
        counts[(r, g, b)] += 1
        if r >= 150 and g <= 90 and b <= 90:
            reddish += 1
    total = sum(counts.values())
    if total == 0:
        return ColourStats(0, 0, 1.0, 0)
    return ColourStats(total, len(counts), counts.most_common(1)[0][1] / total, reddish)


def colour_share(pixels: Iterable[RGB], colour: RGB, tolerance: int = 16) -> float:
    """The fraction of `pixels` within `tolerance` of `colour` in each channel (a picture sent as
    JPEG, as VNC's Tight encoding does, comes back a few units off)."""
    total = near = 0
    for pixel in pixels:
        total += 1
        if all(abs(a - b) <= tolerance for a, b in zip(pixel, colour)):
            near += 1
    return near / total if total else 0.0


def grab_screen(display: str, path: str, timeout_s: float = 30.0) -> str:
    """Screenshot of the whole `display` to a PNG at `path` (in a child process: Qt binds one display).

    Returns the capture's last output line: JSON colour statistics (see qt_capture)."""
    env = dict(os.environ, DISPLAY=display, QT_QPA_PLATFORM="xcb")
    env.setdefault("XDG_RUNTIME_DIR", tempfile.mkdtemp(prefix="xdg-"))
    out = subprocess.run([sys.executable, "-m", "course_testkit.qt_capture", path], env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout_s)
    if out.returncode != 0:
        raise RuntimeError("screen capture failed: %s" % out.stdout)
    return out.stdout.strip().splitlines()[-1]
