"""The disk one student's code fills, in total: what a folder tree takes, measured.

RLIMIT_FSIZE bounds each file a student process writes (Limits.file_bytes), not how many: a
build or a node could write file after file until the grader's disk is full. So everything of
one student (the grader's `_work/<student>`: the unpacked submission, the overlay workspace and
its build, every run's home) is bounded together (Limits.disk_bytes): the sandbox's watcher
measures it every DISK_WATCH_INTERVAL_S and, past the bound, ends the sandbox's processes.

Measured, not mounted: the work folder must outlive every sandbox (the build's workspace is the
runs', and the trusted side reads it), so a size-limited tmpfs inside a sandbox cannot hold it;
a tmpfs or loop-mounted image on the host needs root (not at isolation `namespaces`, nor in a
container that refuses mounts, Gradescope's) and a grader killed with SIGKILL would leave it
mounted. The price: a writer can go past the bound by what it writes within one interval.
"""
from __future__ import annotations

import os
import threading
import time
from typing import Callable, Optional

# A full submission's work folder (12 packages, built: 1900 entries) takes 13 ms of CPU to measure.
DISK_WATCH_INTERVAL_S = 2.0


def used_bytes(folder: str) -> int:
    """The disk the files under `folder` take (allocated blocks: a sparse file counts what it
    fills), links not followed, entries that vanish meanwhile skipped."""
    total = 0
    todo = [folder]
    while todo:
        try:
            entries = os.scandir(todo.pop())
        except OSError:
            continue
        with entries:
            for entry in entries:
                try:
                    info = entry.stat(follow_symlinks=False)
                except OSError:
                    continue
                total += info.st_blocks * 512
                if entry.is_dir(follow_symlinks=False):
                    todo.append(entry.path)
    return total


def sentence(limit_bytes: int) -> str:
    """What the student reads when their code reached the bound."""
    return ("your build and runs wrote more than %d MiB to disk together (your workspace, its build and the "
            "files your nodes wrote); all your processes were ended" % (limit_bytes // 2**20))


class DiskMeter:
    """Whether `folder` has gone past `limit_bytes`, measured at most every `interval` s (the
    last answer in between); any thread may ask."""

    def __init__(self, folder: str, limit_bytes: int, interval: float = DISK_WATCH_INTERVAL_S) -> None:
        self.folder = folder
        self.limit_bytes = limit_bytes
        self.interval = interval
        self.peak = 0
        self._measured_at = -float("inf")
        self._lock = threading.Lock()

    def over(self, now: Optional[float] = None) -> bool:
        now = time.monotonic() if now is None else now
        with self._lock:
            if now - self._measured_at >= self.interval:
                self._measured_at = now
                self.peak = max(self.peak, used_bytes(self.folder))
            return self.peak > self.limit_bytes


def watch(meter: DiskMeter, stop: threading.Event, on_over: Callable[[], None]) -> threading.Thread:
    """A thread that asks `meter` every interval until `stop` is set, and calls `on_over` once
    (then ends) when the folder has gone past its bound."""
    def loop() -> None:
        while not stop.wait(meter.interval):
            if meter.over():
                on_over()
                return
    thread = threading.Thread(target=loop, name="sandbox-disk", daemon=True)
    thread.start()
    return thread
