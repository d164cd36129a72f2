#!/usr/bin/env python3
"""How long a grading takes to stop after Ctrl+C (figures, no assertions): ROUNDS times, grade a
class of 6 samples on `chatter` (--jobs 3), send SIGINT once RUNNING processes of its runs are up,
and print the seconds from the signal to the grader's exit, its exit code, and what is left
(processes of the grading).
    python3 bench/grader_interrupt_bench.py [ROUNDS]      (default 3)"""
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from course_testkit.gradings import processes_of
from course_testkit.samples import SAMPLES_DIR, materialise
from course_checks.waiting import wait_for

CLASS = ["lab2_chatter_scripts", "bad_ignore_sigint", "bad_hang", "bad_fork", "bad_crash", "attack_fill_tmp"]
RUNNING = 12  # processes of the grading: about two runs under way


def one_round() -> float:
    folder = Path(tempfile.mkdtemp(prefix="interrupt-bench-"))
    folder.chmod(0o755)
    out = folder / "grades"
    try:
        subs = [str(materialise(SAMPLES_DIR / s, folder / "derived")) for s in CLASS]
        grader = subprocess.Popen(["rosrun", "course_grader", "grade", *subs, "--only", "chatter", "--jobs", "3",
                                   "--out", str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                  start_new_session=True)
        wait_for(lambda: len(processes_of(str(out))) >= RUNNING, 300, 0.1)
        signalled = time.monotonic()
        os.kill(grader.pid, signal.SIGINT)
        code = grader.wait(120)
        took = time.monotonic() - signalled
        print("stopped in %.2f s, exit code %d, %d process(es) left" % (took, code, len(processes_of(str(out)))),
              flush=True)
        return took
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    times = [one_round() for _ in range(rounds)]
    print("SIGINT to exit: median %.2f s, max %.2f s over %d rounds" % (statistics.median(times), max(times), rounds))


if __name__ == "__main__":
    main()
