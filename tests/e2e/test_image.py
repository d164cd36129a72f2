"""The course image and the Gradescope autograder tried in real OCI containers, built and run by
Debian's podman as root (course_testkit.podman, course_testkit.course_image). End-to-end suites
(the `e2e` marker: `make test` leaves them out):

    sudo make docker-check          # test_the_course_images: both images built, then the demo, no answers in
                                    # the student's, make lab and make jupyter through their published ports,
                                    # make grade and make test in the instructor's
    sudo make autograder-check      # test_the_autograder_as_gradescope_runs_it, on make autograder's zip
    sudo python3 -m pytest -m e2e -s tests/e2e/test_image.py -k workbench   # make jupyter in the student
                                    # image already built (no build): the lab through its published port
                                    # (a sourced workspace, or the Makefile's PYTHONPATH for Debian's python3)

DOCKER_CHECK_ARGS in the environment holds docker-check's options (course_image.options:
--rebuild, --skip-test, --grade-class DIR, --logs DIR); AUTOGRADER_ZIP names the zip (default
autograder.zip in the checkout); COURSE_IMAGE and INSTRUCTOR_IMAGE other tags. Each step's wall
time is printed at the end. Where podman cannot run (not root, podman missing and not
installable), the test fails and says why: there is no stand-in.
"""
from __future__ import annotations

import os
import re
import zipfile
from pathlib import Path

import pytest

from course_testkit.course_image import (AUTOGRADER_SAMPLES, LOGS, build_autograder_image, grade_class,
                                         grade_in_container, jupyter_check, lab_check, options, results_problems,
                                         student_image_has_no_answers)
from course_testkit.podman import (CHECKOUT, COURSE_IMAGE, INSTRUCTOR_IMAGE, Steps, build_course_image, import_base,
                                   last_line, require_ok, run_in_image, run_steps)

pytestmark = pytest.mark.e2e


def test_the_course_images():
    opts = options(os.environ.get("DOCKER_CHECK_ARGS", ""))

    def docker_check(steps: Steps, scratch: Path) -> bool:
        logs = opts.logs
        steps.run("base image import", import_base, logs / "import.log")
        steps.run("image build", build_course_image, scratch, logs / "build.log")
        if opts.rebuild:
            steps.run("image build, again (cached layers)", build_course_image, scratch, logs / "build-again.log")
        ok = True
        code = steps.run("demo (the image's CMD, as user student)", run_in_image, COURSE_IMAGE, [], logs / "demo.log")
        print("demo: exit %s; %s" % (code, last_line(logs / "demo.log", r"\S")), flush=True)
        ok &= code == 0
        ok &= steps.run("no reference solution in the student image", student_image_has_no_answers,
                        logs / "answers.log")
        ok &= steps.run("lab page through a published port", lab_check, logs / "lab.log")
        ok &= steps.run("make jupyter through a published port, as user student", jupyter_check, scratch,
                        logs / "jupyter.log")
        code = steps.run("make grade (the reference) in the instructor image, as user student", run_in_image,
                         INSTRUCTOR_IMAGE, ["make", "grade", "GRADES=/tmp/grades"], logs / "grade-reference.log")
        print("make grade: exit %s; %s" % (code, last_line(logs / "grade-reference.log", r"^\[1/1\] reference")),
              flush=True)
        ok &= code == 0
        if opts.grade_class:
            ok &= steps.run("make grade of %s in a container, as root" % opts.grade_class, grade_class,
                            Path(opts.grade_class).resolve(), scratch, logs / "grade.log")
        if not opts.skip_test:
            code = steps.run("make test in the instructor image, as user student", run_in_image, INSTRUCTOR_IMAGE,
                             ["make", "test"], logs / "test.log")
            print("make test: exit %s; %s" % (code, last_line(logs / "test.log", r"passed|failed|error")), flush=True)
            ok &= code == 0
        return ok
    require_ok("docker-check", run_steps("docker-check", docker_check, opts.logs))


def test_the_workbench_in_the_built_image():
    """make jupyter in the student image already built, through its published port."""
    def workbench(steps: Steps, scratch: Path) -> bool:
        return steps.run("make jupyter through a published port, as user student", jupyter_check, scratch,
                         LOGS / "jupyter.log")
    require_ok("the workbench in %s" % COURSE_IMAGE, run_steps("jupyter-check", workbench, LOGS))


def test_the_autograder_as_gradescope_runs_it():
    """Gradescope's setup.sh as root in a fresh container of the base image, then run_autograder on a
    correct, a buggy, a non-building and an attack submission, each results.json against
    Gradescope's format and the expected verdict."""
    zip_path = Path(os.environ.get("AUTOGRADER_ZIP") or CHECKOUT / "autograder.zip").resolve()
    if not zip_path.is_file():
        pytest.fail("no %s: make autograder MILESTONES=chatter first (make autograder-check does)" % zip_path,
                    pytrace=False)
    with zipfile.ZipFile(zip_path) as zf:
        milestones = zf.read("milestones.txt").decode().split() if "milestones.txt" in zf.namelist() else []
    if milestones != ["chatter"]:
        pytest.fail("%s must grade the milestone chatter alone (make autograder MILESTONES=chatter), not %s"
                    % (zip_path, milestones or "every milestone"), pytrace=False)

    def autograder_check(steps: Steps, scratch: Path) -> bool:
        steps.run("base image import", import_base, LOGS / "import.log")
        steps.run("setup.sh as root in a fresh container", build_autograder_image, zip_path, scratch,
                  LOGS / "setup.log")
        ok = True
        for sample, what, passed in AUTOGRADER_SAMPLES:
            results, problems = steps.run("run_autograder: %s (%s)" % (sample, what), grade_in_container, sample,
                                          scratch, LOGS / ("grade-%s.log" % sample))
            problems = problems or results_problems(results, passed)
            isolation = re.search(r"isolation: ([^:\n]+)", results.get("output", ""))
            print("%s: score %s, %s; isolation %s%s" % (
                sample, results.get("score"), ", ".join("%s %s" % (t.get("name", "?").split(":")[0], t.get("status"))
                                                        for t in results.get("tests", [])),
                isolation.group(1) if isolation else "?", "; PROBLEMS: " + "; ".join(problems) if problems else ""),
                flush=True)
            ok &= not problems
        return ok
    require_ok("autograder-check", run_steps("autograder-check", autograder_check, LOGS))
