"""The windows on an X display, by title, as `xwininfo -root -tree` lists them: how tests find
turtlesim's or rviz's window on the workbench's desktop (a VNC server's display) and where it is.

`parse_tree` and `is_viewable` are plain Python over xwininfo's text (unit-tested); `x_windows` and
`shown_windows` run xwininfo on a display.
"""
from __future__ import annotations

import os
import re
import subprocess
from dataclasses import dataclass
from typing import Iterable, List, Optional, Sequence

# One window of the tree: id "title": ("instance" "class")  WxH+relX+relY  +absX+absY
_LINE = re.compile(r'^\s*(?P<id>0x[0-9a-fA-F]+) "(?P<title>.*)": \(.*\)\s+(?P<w>\d+)x(?P<h>\d+)'
                   r'[+-]-?\d+[+-]-?\d+\s+\+(?P<x>-?\d+)\+(?P<y>-?\d+)\s*$')
TIMEOUT_S = 20.0


@dataclass(frozen=True)
class XWindow:
    """A named window and its place on the screen (absolute coordinates of its inside)."""
    id: str
    title: str
    x: int
    y: int
    width: int
    height: int

    @property
    def box(self):
        """(left, top, right, bottom), as PIL's crop takes it."""
        return (self.x, self.y, self.x + self.width, self.y + self.height)


def parse_tree(text: str) -> List[XWindow]:
    """The named windows of `xwininfo -root -tree`'s output (unnamed ones are left out)."""
    windows = []
    for line in text.splitlines():
        found = _LINE.match(line)
        if found:
            windows.append(XWindow(found["id"], found["title"], int(found["x"]), int(found["y"]),
                                   int(found["w"]), int(found["h"])))
    return windows


def largest_titled(windows: Iterable[XWindow], part: str) -> Optional[XWindow]:
    """The largest window whose title holds `part` (a toolkit's helper windows share an
    application's name but are a few pixels big)."""
    named = [w for w in windows if part in w.title]
    return max(named, key=lambda w: w.width * w.height) if named else None


def _xwininfo(arguments: Sequence[str], display: str, xauthority: Optional[str]) -> Optional[str]:
    """xwininfo's output on `display` (x11-utils), None when it does not answer."""
    env = dict(os.environ, DISPLAY=display)
    if xauthority:
        env["XAUTHORITY"] = xauthority
    try:
        done = subprocess.run(["xwininfo", *arguments], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True, timeout=TIMEOUT_S, check=False)
    except subprocess.TimeoutExpired:
        return None
    return done.stdout if done.returncode == 0 else None


def x_windows(display: str, xauthority: Optional[str] = None) -> List[XWindow]:
    """The named windows on `display` now; [] when it does not answer."""
    return parse_tree(_xwininfo(["-root", "-tree"], display, xauthority) or "")


def is_viewable(text: str) -> bool:
    """True when `xwininfo -id W`'s output says W and its parents are mapped (on the screen: a
    window created but not shown yet, as rviz's main window behind its splash, is not)."""
    return re.search(r"^\s*Map State:\s*IsViewable\s*$", text, re.MULTILINE) is not None


def shown_windows(display: str, xauthority: Optional[str] = None) -> List[XWindow]:
    """The named windows on `display` that are on the screen now."""
    return [w for w in x_windows(display, xauthority)
            if w.width > 1 and is_viewable(_xwininfo(["-id", w.id], display, xauthority) or "")]
