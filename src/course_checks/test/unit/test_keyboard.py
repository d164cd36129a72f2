"""PtyKeyboard against small programs (no ROS): lines with Enter, raw-mode waiting for a reader that
flushes what was typed between keys, and a restart on a fresh terminal."""
import os
import sys
import time

from course_checks.keyboard import LINE_KILL, PtyKeyboard, key_bytes

# Reads one key at a time like teleop_twist_keyboard: tty.setraw (which flushes pending input) only
# while waiting, cooked mode in between; writes each key it got to a file.
TOGGLING_READER = r"""
import os, select, sys, termios, time, tty
out = open(sys.argv[1], "w", buffering=1)
fd = sys.stdin.fileno()
while True:
    old = termios.tcgetattr(fd)
    tty.setraw(fd)
    ready = select.select([fd], [], [], 0.03)[0]
    key = os.read(fd, 1).decode() if ready else ""
    termios.tcsetattr(fd, termios.TCSADRAIN, old)
    if key:
        out.write(key + "\n")
    time.sleep(0.07)
"""

LINE_READER = r"""
import sys
out = open(sys.argv[1], "w", buffering=1)
while True:
    out.write(input() + "\n")
"""


def lines(path):
    with open(path) as f:
        return f.read().split()


def wait_lines(path, n, timeout=5.0):
    deadline = time.monotonic() + timeout
    while len(lines(path)) < n and time.monotonic() < deadline:
        time.sleep(0.02)
    return lines(path)


def test_key_bytes():
    assert key_bytes("up") == b"\x1b[A"
    assert key_bytes("w", enter=True) == LINE_KILL + b"w\n"


def test_raw_wait_lands_every_key_on_a_toggling_reader(tmp_path):
    out = tmp_path / "keys"
    out.write_text("")
    keyboard = PtyKeyboard([sys.executable, "-c", TOGGLING_READER, str(out)], raw_wait=1.0)
    try:
        # The reader first has to start (seconds on a loaded machine): raw_wait covers its toggling,
        # not its start-up, as a check presses keys only once the node has registered.
        assert keyboard.wait_for_raw_mode(60.0)
        for key in "wasd" * 3:
            keyboard.press(key)
            time.sleep(0.05)
        assert "".join(wait_lines(out, 12)) == "wasd" * 3
        assert keyboard.seen_raw
    finally:
        keyboard.stop()


def test_a_line_drops_what_was_typed_before_it(tmp_path):
    out = tmp_path / "lines"
    out.write_text("")
    keyboard = PtyKeyboard([sys.executable, "-c", LINE_READER, str(out)], raw_wait=1.0)
    try:
        keyboard.press("x")  # never seen raw: waits 0.2 s at most, then types 'x' without Enter
        keyboard.press("w", enter=True)
        assert wait_lines(out, 1) == ["w"]
        assert not keyboard.raw_mode() and not keyboard.seen_raw
    finally:
        started = time.monotonic()
        keyboard.stop()  # blocked in input(): Ctrl+C is not enough, the hang-up ends it
        assert time.monotonic() - started < 5


def test_restart_runs_the_command_again(tmp_path):
    out = tmp_path / "lines"
    out.write_text("")
    keyboard = PtyKeyboard([sys.executable, "-c", LINE_READER, str(out)], log_path=str(tmp_path / "node.log"))
    try:
        first = keyboard.node.proc.pid
        keyboard.restart()
        assert keyboard.node.proc.pid != first and keyboard.node.running()
        assert (tmp_path / "node-restarted.log").exists()
        keyboard.press("hello", enter=True)
        assert wait_lines(out, 1) == ["hello"]
    finally:
        keyboard.stop()


def test_stop_ends_children_in_sessions_of_their_own(tmp_path):
    pid_file = tmp_path / "child.pid"
    spawner = ("import subprocess, sys, time\n"
               "child = subprocess.Popen(['sleep', '300'], start_new_session=True)\n"
               "open(sys.argv[1], 'w').write(str(child.pid))\n"
               "time.sleep(300)\n")
    keyboard = PtyKeyboard([sys.executable, "-c", spawner, str(pid_file)])
    deadline = time.monotonic() + 10
    while not (pid_file.exists() and pid_file.read_text()) and time.monotonic() < deadline:
        time.sleep(0.02)
    child = int(pid_file.read_text())
    keyboard.stop()
    deadline = time.monotonic() + 5
    while os.path.exists("/proc/%d" % child) and time.monotonic() < deadline:
        with open("/proc/%d/stat" % child) as f:
            if f.read().rsplit(")", 1)[1].split()[0] == "Z":  # killed, waiting for init to reap it
                break
        time.sleep(0.02)
    else:
        assert not os.path.exists("/proc/%d" % child), "the setsid child outlived stop()"
