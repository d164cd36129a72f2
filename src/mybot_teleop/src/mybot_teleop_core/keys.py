"""The teleop's key names: arrows move, 's' stops, 'q' quits.

Bytes are decoded by turtlesim's KeyDecoder (the workspace's one terminal-key decoder);
this module only names the letter keys the teleop understands.
"""
from __future__ import annotations

from typing import Dict, List

from turtlesim import keyboard

UP, DOWN, LEFT, RIGHT, STOP, QUIT = "up", "down", "left", "right", "stop", "quit"
LETTERS: Dict[str, str] = {"s": STOP, "S": STOP, "q": QUIT, "Q": QUIT}
ARROW_BYTES: Dict[str, bytes] = {UP: b"\x1b[A", DOWN: b"\x1b[B", RIGHT: b"\x1b[C", LEFT: b"\x1b[D"}


class KeyDecoder(keyboard.KeyDecoder):
    """turtlesim's decoder, keeping only the keys the teleop acts on (arrows, s, q)."""

    def feed(self, data: bytes) -> List[str]:
        keys = (LETTERS.get(k, k) for k in super().feed(data))
        return [k for k in keys if k in (UP, DOWN, LEFT, RIGHT, STOP, QUIT)]
