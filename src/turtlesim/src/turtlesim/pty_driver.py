"""Run a keyboard node on a real pseudo-terminal and type into it (for tests and graders)."""
from __future__ import annotations

import os
import select
import subprocess
import time
from typing import List, Optional

ARROW = {"up": b"\x1b[A", "down": b"\x1b[B", "right": b"\x1b[C", "left": b"\x1b[D"}


class PtyProcess:
    """A child process whose stdin/stdout/stderr are the slave side of a new pty."""

    def __init__(self, argv: List[str], env: Optional[dict] = None) -> None:
        self.master, slave = os.openpty()
        self.proc = subprocess.Popen(argv, stdin=slave, stdout=slave, stderr=slave, env=env,
                                     start_new_session=True, close_fds=True)
        os.close(slave)
        self.output = b""

    def read_until(self, text: bytes, timeout: float = 10.0) -> bool:
        """Collect output until `text` appears (True) or `timeout` passes (False)."""
        deadline = time.monotonic() + timeout
        while text not in self.output and time.monotonic() < deadline:
            ready, _, _ = select.select([self.master], [], [], 0.05)
            if ready:
                try:
                    chunk = os.read(self.master, 4096)
                except OSError:
                    break
                if not chunk:
                    break
                self.output += chunk
        return text in self.output

    def type(self, keys: bytes) -> None:
        os.write(self.master, keys)

    def wait(self, timeout: float = 10.0) -> Optional[int]:
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            return None

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            if self.wait(5.0) is None:
                self.proc.kill()
                self.proc.wait()
        os.close(self.master)
