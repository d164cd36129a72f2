"""Bytes read from a raw terminal -> key names: the arrows by name, every other key as its character."""
from __future__ import annotations

from typing import List

from course_keyboard.arrows import ESC, INTRODUCERS, NAMES_BY_FINAL


class KeyDecoder:
    """Turns bytes read from a terminal into key names: 'up', 'down', 'left', 'right' or the character.

    Arrow keys arrive as ESC [ A..D (or ESC O A..D in application mode), possibly
    split across reads; an unfinished sequence waits for the next `feed`. Other escape
    sequences lose their introducer (ESC and '[' or 'O'); what follows comes out as characters.
    """

    def __init__(self) -> None:
        self._pending = b""

    def feed(self, data: bytes) -> List[str]:
        buf = self._pending + data
        keys: List[str] = []
        i = 0
        while i < len(buf):
            byte = buf[i]
            if byte != ESC:
                keys.append(chr(byte))
                i += 1
                continue
            if i + 1 >= len(buf) or (buf[i + 1] in INTRODUCERS and i + 2 >= len(buf)):
                break  # incomplete escape sequence: wait for more bytes
            if buf[i + 1] in INTRODUCERS and buf[i + 2] in NAMES_BY_FINAL:
                keys.append(NAMES_BY_FINAL[buf[i + 2]])
                i += 3
            else:
                i += 2 if buf[i + 1] in INTRODUCERS else 1  # unknown sequence: skip its introducer
        self._pending = buf[i:]
        return keys
