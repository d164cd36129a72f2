"""The teleop's key names: arrows move, 's' stops, 'q' quits.

Bytes are decoded by course_keyboard's KeyDecoder (the workspace's one terminal-key decoder);
this module only names the letter keys the teleop understands.
"""
from __future__ import annotations

from typing import Dict, List

from course_keyboard import decoder
from course_keyboard.arrows import DOWN, LEFT, RIGHT, UP

STOP, QUIT = "stop", "quit"
LETTERS: Dict[str, str] = {"s": STOP, "S": STOP, "q": QUIT, "Q": QUIT}
KNOWN = (UP, DOWN, LEFT, RIGHT, STOP, QUIT)

__all__ = ["UP", "DOWN", "LEFT", "RIGHT", "STOP", "QUIT", "LETTERS", "KeyDecoder"]


class KeyDecoder(decoder.KeyDecoder):
    """course_keyboard's decoder, keeping only the keys the teleop acts on (arrows, s, q)."""

    def feed(self, data: bytes) -> List[str]:
        keys = (LETTERS.get(k, k) for k in super().feed(data))
        return [k for k in keys if k in KNOWN]
