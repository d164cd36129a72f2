"""Where a colour appears in a PNG: how tests check that rqt_plot's picture holds its lines.

A line drawn in matplotlib's C0 is antialiased, but its middle pixels keep the exact colour,
so "rows holding pixels within a small tolerance of C0" tells whether the line is there and
whether it is flat (a few rows, with its legend sample) or moves (many distinct rows).
"""
from __future__ import annotations

from typing import List, NamedTuple, Tuple

RGB = Tuple[float, float, float]
TOLERANCE = 0.06


class ColourRows(NamedTuple):
    """How many pixels have the colour and on which rows (top row 0)."""
    pixels: int
    rows: List[int]


def png_size(path: str) -> Tuple[int, int]:
    """(width, height) in pixels."""
    import matplotlib.image
    height, width = matplotlib.image.imread(path).shape[:2]
    return width, height


def colour_rows(path: str, colour: str, tolerance: float = TOLERANCE) -> ColourRows:
    """The pixels of `colour` (any matplotlib colour: 'C0', '#ff7f0e') in the PNG at `path`."""
    import matplotlib.colors
    import matplotlib.image
    import numpy
    pixels = matplotlib.image.imread(path)[:, :, :3]
    target = numpy.array(matplotlib.colors.to_rgb(colour))
    close = numpy.all(numpy.abs(pixels - target) <= tolerance, axis=2)
    return ColourRows(int(close.sum()), [int(r) for r in numpy.flatnonzero(close.any(axis=1))])
