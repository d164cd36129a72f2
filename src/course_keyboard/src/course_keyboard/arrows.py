"""The arrow keys as a terminal sends them: the workspace's one table of their escape sequences.

A terminal sends an arrow as ESC [ A..D (CSI, the normal cursor mode), or as ESC O A..D (SS3,
the application cursor mode some terminals switch to); the final byte names the arrow.
Test keyboards type SEQUENCES; the decoder reads the same table backwards (NAMES_BY_FINAL).
"""
from __future__ import annotations

from typing import Dict

UP, DOWN, RIGHT, LEFT = "up", "down", "right", "left"
ESC = 0x1B
INTRODUCERS = b"[O"  # the byte after ESC in an arrow's sequence: '[' (CSI) or 'O' (SS3)

SEQUENCES: Dict[str, bytes] = {UP: b"\x1b[A", DOWN: b"\x1b[B", RIGHT: b"\x1b[C", LEFT: b"\x1b[D"}
NAMES_BY_FINAL: Dict[int, str] = {sequence[-1]: name for name, sequence in SEQUENCES.items()}
