#!/usr/bin/env python3
"""The course image for linux/amd64 and linux/arm64, built here by podman from docker/Dockerfile and
joined in one manifest list (course_testkit.multiarch; docs/images.md). Root; Debian's python3
with the Makefile's PYTHONPATH, as the make targets run it:

    sudo make image-multiarch    # tools/multiarch.py image: both images + the manifest list
    sudo make image-figures      # tools/multiarch.py figures: sizes, and the demo's time emulated against native
    tools/multiarch.py manifest  # the manifest list again, from both images built before

The arm64 image's end-to-end suite (`make image-arm64-check`) is tests/e2e/test_arm64.py.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path
from typing import Optional, Sequence

from course_testkit.multiarch import (ARCHES, BUILD_TIMES, LOGS, MANIFEST, build_image, ensure_emulation, host_arch,
                                      image_exists_or_fail, import_base, make_manifest, probe_emulation, run_demo)
from course_testkit.podman import Steps, podman, run_steps


def image_action(opts: argparse.Namespace, steps: Steps, scratch: Path, logs: Path) -> bool:
    for arch in opts.arch:
        steps.run("emulation for %s" % arch, ensure_emulation, arch)
        steps.run("base image for %s" % arch, import_base, arch, logs / ("import-%s.log" % arch))
        steps.run("a linux/%s container" % arch, probe_emulation, arch)
    times_path = logs / BUILD_TIMES
    times = json.loads(times_path.read_text()) if times_path.exists() else {}
    for arch in opts.arch:
        steps.run("image build for linux/%s%s" % (arch, "" if arch == host_arch() else " (emulated)"),
                  build_image, arch, scratch, logs / ("build-%s.log" % arch))
        times[arch] = round(steps.times[-1][1], 1)
        times_path.write_text(json.dumps(times, indent=1) + "\n")
    return manifest_action(opts, steps, scratch, logs)


def manifest_action(opts: argparse.Namespace, steps: Steps, scratch: Path, logs: Path) -> bool:
    """The manifest list made anew from the images of opts.arch, built before."""
    for arch in opts.arch:
        image_exists_or_fail(arch)
    platforms = steps.run("manifest list %s" % MANIFEST, make_manifest, opts.arch, logs / "manifest.log")
    wanted = sorted("linux/%s" % a for a in opts.arch)
    print("%s holds %s" % (MANIFEST, ", ".join(platforms)), flush=True)
    return platforms == wanted


def figures_action(opts: argparse.Namespace, steps: Steps, scratch: Path, logs: Path) -> bool:
    """Each image's size, its build time (recorded by the last `image`), the demo's wall time in each."""
    times = json.loads((logs / BUILD_TIMES).read_text()) if (logs / BUILD_TIMES).exists() else {}
    rows = ["| image | platform | size | build | make demo (the image's CMD) |", "| --- | --- | --- | --- | --- |"]
    ok = True
    for arch in opts.arch or list(ARCHES):
        name = image_exists_or_fail(arch)
        size = podman("image", "inspect", "--format", "{{.Size}}", name, stdout=subprocess.PIPE, text=True).stdout
        demos = []
        for run in range(opts.runs):
            code, seconds, _ = steps.run("demo %d in linux/%s" % (run + 1, arch), run_demo, arch,
                                         logs / ("figures-demo-%s.log" % arch))
            ok &= code == 0
            demos.append(seconds)
        emulated = "" if arch == host_arch() else ", emulated"
        rows.append("| %s | linux/%s%s | %.2f GB | %s | %s |" % (
            name, arch, emulated, int(size) / 1e9, "%.0f s" % times[arch] if arch in times else "?",
            ", ".join("%.0f s" % s for s in demos)))
    print("\n".join(rows), flush=True)
    return ok


ACTIONS = {"image": image_action, "manifest": manifest_action, "figures": figures_action}


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="action", required=True)
    image = sub.add_parser("image", help="both images from docker/Dockerfile, and the manifest list")
    image.add_argument("--arch", action="append", choices=ARCHES,
                       help="build only this architecture (repeatable; default both)")
    joined = sub.add_parser("manifest", help="only the manifest list, from images built before")
    joined.add_argument("--arch", action="append", choices=ARCHES, help="only this image (default both)")
    figures = sub.add_parser("figures", help="sizes, build times, the demo's time in each image")
    figures.add_argument("--arch", action="append", choices=ARCHES, help="only this image (default both)")
    figures.add_argument("--runs", type=int, default=1, help="demo runs per image (default 1)")
    parser.add_argument("--logs", default=str(LOGS), help="where each step's log goes")
    opts = parser.parse_args(argv)
    if opts.action in ("image", "manifest") and opts.arch is None:
        opts.arch = list(ARCHES)
    logs = Path(opts.logs)
    return run_steps("multiarch %s" % opts.action, lambda steps, scratch: ACTIONS[opts.action](opts, steps, scratch, logs),
                     logs)


if __name__ == "__main__":
    sys.exit(main())
