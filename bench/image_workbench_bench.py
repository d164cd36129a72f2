#!/usr/bin/env python3
"""`make jupyter`'s start-up in the student image already built (podman, root), as figures, never a
verdict (the workbench in the image is checked by `make docker-check`, tests/e2e/test_image.py):
RUNS fresh containers, each with an empty folder mounted, from `podman run` to REST answering and
to a terminal's first command, the load average before and the CPU seconds the container's
processes used; then the median and the worst.

    sudo python3 bench/image_workbench_bench.py [--runs 5]    # a sourced workspace; COURSE_IMAGE names another tag
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Optional, Sequence

from course_testkit.course_image import LOGS, jupyter_starts
from course_testkit.podman import COURSE_IMAGE, Steps, run_steps


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5, help="start-ups to time (default 5)")
    parser.add_argument("--logs", type=Path, default=LOGS, help="where the containers' logs go")
    opts = parser.parse_args(argv)

    def starts(steps: Steps, scratch: Path) -> bool:
        return steps.run("make jupyter's start-up in %s, %d times" % (COURSE_IMAGE, opts.runs), jupyter_starts,
                         opts.runs, scratch, opts.logs / "jupyter-starts.log")
    return run_steps("image-workbench-bench", starts, opts.logs)


if __name__ == "__main__":
    sys.exit(main())
