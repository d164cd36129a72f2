"""Capture the X root window to a PNG with PyQt5 and print its colour statistics as JSON.

Run as `python3 -m course_testkit.qt_capture OUT.png [--region X Y W H]` with DISPLAY set
(QT_QPA_PLATFORM=xcb); no ImageMagick or xwd needed. Pixels are sampled every 2nd row/column.
"""
from __future__ import annotations

import argparse
import json
import sys
from typing import Iterator, List, Optional

from course_testkit.screen import RGB, colour_stats


def pixels_of(image, region: Optional[List[int]] = None, step: int = 2) -> Iterator[RGB]:
    x0, y0, w, h = region or (0, 0, image.width(), image.height())
    for y in range(max(0, y0), min(image.height(), y0 + h), step):
        for x in range(max(0, x0), min(image.width(), x0 + w), step):
            rgb = image.pixel(x, y)
            yield (rgb >> 16) & 0xFF, (rgb >> 8) & 0xFF, rgb & 0xFF


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m course_testkit.qt_capture", description=__doc__.splitlines()[0])
    parser.add_argument("output")
    parser.add_argument("--region", type=int, nargs=4, metavar=("X", "Y", "W", "H"),
                        help="only count colours inside this rectangle (the whole screen is saved)")
    args = parser.parse_args(argv)
    from PyQt5.QtWidgets import QApplication  # imported here: needs a display
    app = QApplication(sys.argv[:1])
    image = app.primaryScreen().grabWindow(0).toImage()
    if not image.save(args.output):
        print("qt_capture: could not write %s" % args.output, file=sys.stderr)
        return 1
    stats = colour_stats(pixels_of(image, args.region))
    print(args.output)
    print(json.dumps({"width": image.width(), "height": image.height(), "distinct": stats.distinct,
                      "dominant_share": round(stats.dominant_share, 4), "reddish": stats.reddish,
                      "blank": stats.looks_blank()}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
