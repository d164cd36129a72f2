"""Write the Gradescope autograder zip: setup.sh and run_autograder at its root (as Gradescope's
specs require), the course repository's tracked files beside them (setup.sh builds them as the
`make build` does (docs/setup.md)), milestones.txt when the assignment grades only some milestones,
and course.txt naming the course folder when it is not the built-in one (`make autograder COURSE=DIR`).
Grading then scales past one machine: one container per submission on Gradescope's fleet."""
from __future__ import annotations

import argparse
import fnmatch
import os
import shutil
import stat
import subprocess
import zipfile
from typing import Iterable, List, Optional, Sequence

from course_checks.gitignore import not_ignored_files

TEMPLATES = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "..", "autograder")
ENTRY_POINTS = ("setup.sh", "run_autograder")
# Not needed to grade: the sample submissions and build output.
EXCLUDED_PREFIXES = ("catkin_ws/build/", "catkin_ws/devel/", ".venv/",
                     "solutions_ws/")  # the built-in course's reference overlay: answers, never graded there
# A course folder's answers (docs/course_format.md).
EXCLUDED_PATTERNS = ("courses/*/solution/*", "courses/*/samples/*")
COURSE_NOTE = "course.txt"


def answer(rel: str) -> bool:
    """Whether `rel` (a path in the repository) is an answer the zip must not hold."""
    return rel.startswith(EXCLUDED_PREFIXES) or any(fnmatch.fnmatch(rel, p) for p in EXCLUDED_PATTERNS)


def repo_files(repo: str) -> List[str]:
    """The repository's files (paths relative to `repo`): tracked ones and new ones git does not
    ignore; in a copy without git (the course image leaves .git out) every file its .gitignore
    does not ignore."""
    listed = subprocess.run(["git", "-C", repo, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=False) \
        if shutil.which("git") and os.path.exists(os.path.join(repo, ".git")) else None
    if listed is not None and listed.returncode == 0:
        found = listed.stdout.decode().split("\0")
    else:
        found = not_ignored_files(repo)
    return sorted({p for p in found if p and not answer(p)})


def _add(zf: zipfile.ZipFile, path: str, name: str) -> None:
    if os.path.islink(path) or not os.path.isfile(path):
        return  # catkin_ws/src, a link: setup.sh makes it again
    info = zipfile.ZipInfo.from_file(path, name)
    info.external_attr = (stat.S_IFREG | (0o755 if os.access(path, os.X_OK) else 0o644)) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    with open(path, "rb") as f:
        zf.writestr(info, f.read())


def course_files(course: str) -> List[str]:
    """A course folder's files (relative to it) less its answers (solution/, samples/)."""
    found = []
    for folder, dirs, files in os.walk(course):
        rel = os.path.relpath(folder, course)
        if rel == ".":
            dirs[:] = [d for d in dirs if d not in ("solution", "samples")]
        found += [os.path.normpath(os.path.join(rel, name)) for name in files]
    return sorted(found)


def write_zip(repo: str, out: str, milestones: Sequence[str] = (), templates: str = TEMPLATES,
              course: str = "") -> None:
    """The zip of `repo` (its answers left out) with Gradescope's entry points; `course`, a course
    folder other than the built-in one, is graded (copied in under courses/ when outside `repo`)."""
    with zipfile.ZipFile(out, "w") as zf:
        for name in ENTRY_POINTS:
            _add(zf, os.path.join(templates, name), name)
        for rel in repo_files(repo):
            if rel not in ENTRY_POINTS:
                _add(zf, os.path.join(repo, rel), rel)
        if milestones:
            zf.writestr("milestones.txt", "\n".join(milestones) + "\n")
        if course:
            course = os.path.realpath(course)
            inside = os.path.relpath(course, os.path.realpath(repo))
            if inside.startswith(".."):
                inside = "courses/%s" % os.path.basename(course)
                for rel in course_files(course):
                    _add(zf, os.path.join(course, rel), "%s/%s" % (inside, rel))
            zf.writestr(COURSE_NOTE, inside + "\n")


def main(argv: Optional[Iterable[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="autograder.zip")
    parser.add_argument("--repo", default=os.path.realpath(os.path.join(TEMPLATES, "..", "..", "..")),
                        help="the course repository (default: the one this package is in)")
    parser.add_argument("--only", action="append", default=[], metavar="M", help="grade only milestone M")
    parser.add_argument("--course", default="", metavar="DIR", help="grade this course folder (default: the built-in one)")
    opts = parser.parse_args(list(argv) if argv is not None else None)
    write_zip(opts.repo, opts.out, opts.only, course=opts.course)
    print("wrote %s (%d files)" % (opts.out, len(zipfile.ZipFile(opts.out).namelist())))
    return 0
