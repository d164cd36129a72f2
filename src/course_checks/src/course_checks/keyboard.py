"""Type on a node's keyboard: the node's stdin is the slave side of a pseudo-terminal
and the test writes key presses (arrow escape sequences: course_keyboard's table) to the master side.

A node that puts the terminal in raw mode only while it waits for a key (tty.setraw, which
flushes what was typed before) loses keys typed in between: with `raw_wait`, press() first
waits for the terminal to be in raw mode (polled every millisecond), as a person's key press
lands while the node listens.

A key can also be typed as a line (the key, then Enter) for nodes that read with input():
the line is started with the terminal's line-kill character (Ctrl+U), so that keys typed
before without Enter are dropped from the pending line instead of being glued to this one."""
from __future__ import annotations

import os
import pty
import select
import signal
import subprocess
import time
from typing import Callable, Optional, Sequence, TypeVar

from course_keyboard.arrows import SEQUENCES as ARROW_SEQUENCES
from course_checks.isolation import descendants, signal_all
from course_checks.nodes import NodeProcess, find_executable
from course_checks.waiting import wait_for

T = TypeVar("T")

LINE_KILL = b"\x15"  # Ctrl+U: VKILL, erases the pending line in canonical mode
ENTER = b"\n"


def key_bytes(key: str, enter: bool = False) -> bytes:
    """The bytes a terminal sends for `key` (an arrow name or literal characters), as a line if `enter`."""
    data = ARROW_SEQUENCES.get(key, key.encode())
    return LINE_KILL + data + ENTER if enter else data


class PtyKeyboard:
    """Runs a command with a pseudo-terminal as stdin; press() types into it."""

    def __init__(self, command: Sequence[str], log_path: Optional[str] = None, env: Optional[dict] = None,
                 output_on_pty: bool = False, raw_wait: float = 0.0, sandbox=None) -> None:
        """`output_on_pty`: the node also writes to the terminal, and read_until() reads what it printed.
        `raw_wait`: how long press() waits for raw mode before typing a single key (see above).
        `sandbox`: run the command in it (NodeProcess)."""
        self.raw_wait = raw_wait
        self.seen_raw = False
        self._start = (list(command), log_path, env, output_on_pty, sandbox)
        self._launch(log_path)

    def _launch(self, log_path: Optional[str]) -> None:
        command, _, env, output_on_pty, sandbox = self._start
        self.master, slave = pty.openpty()
        self.terminal_text = b""
        try:
            self.node = NodeProcess(command, stdin=slave, log_path=log_path, env=env,
                                    stdout=slave if output_on_pty else None, sandbox=sandbox)
        finally:
            os.close(slave)

    def restart(self) -> None:
        """Stop the node and start the same command again on a fresh terminal (nothing typed
        before is left in it); its output goes to `<log>-restarted.log`."""
        self.stop()
        log_path = self._start[1]
        if log_path:
            root, ext = os.path.splitext(log_path)
            log_path = root + "-restarted" + ext
        self._launch(log_path)

    def read_until(self, text: bytes, timeout: float = 10.0) -> bool:
        """Collect what the node printed on the terminal until `text` shows up (True) or `timeout` passes."""
        deadline = time.monotonic() + timeout
        while text not in self.terminal_text and time.monotonic() < deadline:
            ready, _, _ = select.select([self.master], [], [], 0.05)
            if not ready:
                continue
            try:
                chunk = os.read(self.master, 4096)
            except OSError:  # the node closed the terminal
                break
            if not chunk:
                break
            self.terminal_text += chunk
        return text in self.terminal_text

    def wait(self, timeout: float = 10.0) -> Optional[int]:
        """The node's exit code once it exits by itself, or None if it is still running after `timeout`."""
        return self.node.wait(timeout)

    @classmethod
    def rosrun(cls, pkg: str, node_type: str, args: Sequence[str] = (), **kwargs) -> "PtyKeyboard":
        return cls([find_executable(pkg, node_type)] + list(args), **kwargs)

    def raw_mode(self) -> bool:
        """Whether the terminal delivers keys one by one (canonical mode off), i.e. the node reads keys."""
        import termios
        try:
            return not termios.tcgetattr(self.master)[3] & termios.ICANON
        except termios.error:
            return False

    def wait_for_raw_mode(self, timeout: float) -> bool:
        """Wait up to `timeout` for raw mode; whether it came."""
        deadline = time.monotonic() + timeout
        while not self.raw_mode():
            if time.monotonic() > deadline:
                return False
            time.sleep(0.001)
        self.seen_raw = True
        return True

    def press(self, key: str, enter: bool = False) -> None:
        """Type an arrow ('up', 'down', 'left', 'right') or any literal characters; with `enter`,
        as a line of its own followed by Enter (for nodes reading with input()). A single key
        waits for raw mode first (up to `raw_wait`; 0.2 s while the node has never been seen in
        raw mode, as a node reading lines never is)."""
        if self.raw_wait and not enter:
            self.wait_for_raw_mode(self.raw_wait if self.seen_raw else min(self.raw_wait, 0.2))
        os.write(self.master, key_bytes(key, enter))

    def press_until(self, key: str, condition: Callable[[], T], tries: int = 20, interval: float = 1.0,
                    enter: bool = False) -> T:
        """Press `key` (as a line if `enter`), again every `interval` seconds (at most `tries`
        times), until condition() is truthy; return its last value. A node still starting, or
        whose subscribers are not all connected yet, can miss a press; stops early if the node exits."""
        value = condition()
        for _ in range(tries):
            if value or not self.node.running():
                break
            self.press(key, enter)
            value = wait_for(condition, interval)
        return value

    def terminal_settings_echo(self) -> bool:
        """Whether the terminal echoes input (the node should turn echo off while running)."""
        import termios
        return bool(termios.tcgetattr(self.master)[3] & termios.ECHO)

    def stop(self, timeout: float = 10.0, grace: float = 1.5) -> Optional[int]:
        """Ctrl+C; if the node is still running after `grace` seconds (a rospy node blocked in
        input() only notices Ctrl+C at the next Enter), hang up its terminal so the read returns
        end-of-file; then NodeProcess.stop (SIGKILL after `timeout`). Processes started below it
        in sessions of their own (roslaunch starts every node with setsid) and still alive then
        are killed too."""
        tree = descendants(self.node.proc.pid) if self.node.running() else []
        try:
            return self._stop(timeout, grace)
        finally:
            signal_all(tree, signal.SIGKILL)

    def end(self) -> Optional[int]:
        """SIGKILL to the node, its group and every process below it (NodeProcess.end), then
        its terminal closed: a check's clean-up once its verdict is in."""
        signal_all(descendants(self.node.proc.pid) if self.node.running() else [], signal.SIGKILL)
        code = self.node.end()
        try:
            os.close(self.master)
        except OSError:
            pass
        return code

    def _stop(self, timeout: float, grace: float) -> Optional[int]:
        if self.node.running():
            try:
                os.killpg(self.node.proc.pid, signal.SIGINT)
                self.node.proc.wait(grace)
            except (ProcessLookupError, subprocess.TimeoutExpired):
                pass
        try:
            os.close(self.master)
        except OSError:
            pass
        return self.node.stop(timeout)
