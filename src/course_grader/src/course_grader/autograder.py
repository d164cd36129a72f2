"""Write the Gradescope autograder zip: setup.sh and run_autograder at its root (as Gradescope's
specs require), the course repository's tracked files beside them (setup.sh builds them as the
README's `make build` does), and milestones.txt when the assignment grades only some milestones.
Grading then scales past one machine: one container per submission on Gradescope's fleet."""
from __future__ import annotations

import argparse
import os
import stat
import subprocess
import zipfile
from typing import Iterable, List, Optional, Sequence

TEMPLATES = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "..", "autograder")
ENTRY_POINTS = ("setup.sh", "run_autograder")
# Not needed to grade: the sample submissions and build output.
EXCLUDED_PREFIXES = ("tests/submissions/", "catkin_ws/build/", "catkin_ws/devel/", ".venv/")


def repo_files(repo: str) -> List[str]:
    """The repository's files (paths relative to `repo`): tracked ones and new ones git does not ignore."""
    out = subprocess.run(["git", "-C", repo, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                         stdout=subprocess.PIPE, check=True).stdout
    return sorted({p for p in out.decode().split("\0") if p and not p.startswith(EXCLUDED_PREFIXES)})


def _add(zf: zipfile.ZipFile, path: str, name: str) -> None:
    if os.path.islink(path) or not os.path.isfile(path):
        return  # catkin_ws/src, a link: setup.sh makes it again
    info = zipfile.ZipInfo.from_file(path, name)
    info.external_attr = (stat.S_IFREG | (0o755 if os.access(path, os.X_OK) else 0o644)) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    with open(path, "rb") as f:
        zf.writestr(info, f.read())


def write_zip(repo: str, out: str, milestones: Sequence[str] = (), templates: str = TEMPLATES) -> None:
    with zipfile.ZipFile(out, "w") as zf:
        for name in ENTRY_POINTS:
            _add(zf, os.path.join(templates, name), name)
        for rel in repo_files(repo):
            if rel not in ENTRY_POINTS:
                _add(zf, os.path.join(repo, rel), rel)
        if milestones:
            zf.writestr("milestones.txt", "\n".join(milestones) + "\n")


def main(argv: Optional[Iterable[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="autograder.zip")
    parser.add_argument("--repo", default=os.path.realpath(os.path.join(TEMPLATES, "..", "..", "..")),
                        help="the course repository (default: the one this package is in)")
    parser.add_argument("--only", action="append", default=[], metavar="M", help="grade only milestone M")
    opts = parser.parse_args(list(argv) if argv is not None else None)
    write_zip(opts.repo, opts.out, opts.only)
    print("wrote %s (%d files)" % (opts.out, len(zipfile.ZipFile(opts.out).namelist())))
    return 0
