"""Turn the bytes a terminal sends into key names (arrows, s, q).

Arrow keys arrive as escape sequences (ESC [ A, or ESC O A in "application" cursor
mode); a sequence may be split across two reads, so the decoder keeps the unfinished
prefix until the rest arrives.
"""
from __future__ import annotations

from typing import Dict, List

UP, DOWN, LEFT, RIGHT, STOP, QUIT = "up", "down", "left", "right", "stop", "quit"

SEQUENCES: Dict[bytes, str] = {
    b"\x1b[A": UP, b"\x1b[B": DOWN, b"\x1b[C": RIGHT, b"\x1b[D": LEFT,
    b"\x1bOA": UP, b"\x1bOB": DOWN, b"\x1bOC": RIGHT, b"\x1bOD": LEFT,
    b"s": STOP, b"S": STOP, b"q": QUIT, b"Q": QUIT,
}

# Bytes a student can type to get the arrow escape sequences written to a terminal.
ARROW_BYTES: Dict[str, bytes] = {UP: b"\x1b[A", DOWN: b"\x1b[B", RIGHT: b"\x1b[C", LEFT: b"\x1b[D"}


class KeyDecoder:
    """Feed raw bytes, get the key names they complete; unknown bytes are skipped."""

    def __init__(self) -> None:
        self._pending = b""

    def feed(self, data: bytes) -> List[str]:
        buf = self._pending + data
        keys: List[str] = []
        i = 0
        while i < len(buf):
            if buf[i:i + 1] != b"\x1b":
                key = SEQUENCES.get(buf[i:i + 1])
                if key is not None:
                    keys.append(key)
                i += 1
                continue
            chunk = buf[i:i + 3]
            if len(chunk) < 3 and any(seq.startswith(chunk) for seq in SEQUENCES):
                break  # an unfinished escape sequence: wait for the rest
            key = SEQUENCES.get(chunk)
            if key is not None:
                keys.append(key)
                i += 3
            else:
                i += 1  # a lone ESC or an unknown sequence: drop the ESC, keep scanning
        self._pending = buf[i:]
        return keys
