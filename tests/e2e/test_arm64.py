"""`make image-arm64-check`: the arm64 course image under emulation (course_testkit.multiarch; built
before by `make image-multiarch`), root. An end-to-end suite (the `e2e` marker: `make test` leaves it out).

In a fresh container of the image: the demo (its CMD), then `make jupyter` answering over HTTP,
its desktop's VNC server through the websocket, and course-check typed in one of its terminals on
a correct chatter package. One line per check (PASS or FAIL); hours of emulated work on a small
machine. MULTIARCH_ARGS in the environment holds the options: `--arch amd64` checks the native
image instead, `--logs DIR` where each step's log goes.
"""
from __future__ import annotations

import argparse
import os
import shlex
from pathlib import Path

import pytest

from course_testkit.multiarch import ARCHES, LOGS, ensure_emulation, host_arch, run_demo, workbench_and_self_check
from course_testkit.podman import Steps, require_ok, run_steps

pytestmark = pytest.mark.e2e


def options(words: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="make image-arm64-check MULTIARCH_ARGS=")
    parser.add_argument("--arch", action="append", choices=ARCHES, help="the image to check (default arm64)")
    parser.add_argument("--logs", type=Path, default=LOGS, help="where each step's log goes")
    return parser.parse_args(shlex.split(words))


def test_the_arm64_image_under_emulation():
    opts = options(os.environ.get("MULTIARCH_ARGS", ""))
    arch = opts.arch[0] if opts.arch else "arm64"

    def check(steps: Steps, scratch: Path) -> bool:
        steps.run("emulation for %s" % arch, ensure_emulation, arch)
        lines = []
        code, seconds, summary = steps.run("demo in linux/%s" % arch, run_demo, arch,
                                           opts.logs / ("demo-%s.log" % arch))
        lines.append(("make demo", code == 0, "exit %d, %.0f s, %s" % (code, seconds, summary)))
        lines += steps.run("workbench and self-check in linux/%s" % arch, workbench_and_self_check, arch, scratch,
                           opts.logs / ("workbench-%s.log" % arch))
        for name, passed, seen in lines:
            print("%s %s (linux/%s%s): %s" % ("PASS" if passed else "FAIL", name, arch,
                                                "" if arch == host_arch() else ", emulated", seen), flush=True)
        return all(passed for _, passed, _ in lines)
    require_ok("the linux/%s image" % arch, run_steps("image-arm64-check", check, opts.logs))
