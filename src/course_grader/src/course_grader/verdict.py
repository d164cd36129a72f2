"""One student's result on one milestone, and its reasons in words a student can act on.

Which milestones a submission is graded on: a milestone with `packages` is graded for a
submission holding at least one of them; a submission holding none of any milestone's packages
is graded on those whose names look misspelled in it (`mychatter` for `my_chatter`), else on all
of them, each failing with what was expected and what was found; milestones
without packages (they check the course workspace itself) are graded for the reference only;
`--only` always grades what it names.
"""
from __future__ import annotations

import difflib
import glob
import json
import os
import re
import stat
from typing import Dict, Iterable, List, NamedTuple, Optional, Sequence, Tuple

from course_format import causes
from course_milestones import scripts
from course_format.milestone import Milestone
from course_checks.isolation import MAX_FILE_BYTES

from course_grader.submissions import Package

# What is kept of a big file once a run is over: its last part.
KEEP_BYTES = 1024 * 1024
LOG_TAIL_LINES = 20
# Terminal control sequences (colours, window titles) that roslaunch and rospy print.
_ANSI = re.compile(r"\x1b(\[[0-9;?]*[A-Za-z]|\][^\x07\x1b]*(\x07|\x1b\\)?)")
LOG_TAIL_BYTES = 16 * 1024
# How alike a found package name must be to the text's to count as a misspelling of it.
CLOSE_NAME_RATIO = 0.75
MAX_LOGS = 6
# What a failed milestone's output starts with, before its reason.
FAILED = "FAILED: "


class Verdict(NamedTuple):
    student: str
    milestone: Milestone
    passed: bool
    reason: str  # why it failed, in words ("" when passed)
    logs: str = ""  # the last lines of the student's node logs
    elapsed: float = 0.0
    artifacts_dir: str = ""
    notes: str = ""  # what the sandbox saw (a limit the student's code hit), shown pass or fail
    cause: str = ""  # why it failed, as a course_format.causes key ("": not known, see cause_key)

    @property
    def points(self) -> float:
        return self.milestone.points if self.passed else 0.0

    @property
    def cause_key(self) -> str:
        """The failure's cause for the class view ("" when passed; CHECK_FAILED when not known)."""
        if self.passed:
            return ""
        return self.cause if self.cause in causes.BY_KEY else causes.of(self.reason, causes.CHECK_FAILED)

    def output(self) -> str:
        """What the student reads for this milestone: the verdict, then the logs' last lines."""
        head = "passed" if self.passed else FAILED + self.reason
        return head + ("\n" + self.notes if self.notes else "") + ("\n\n" + self.logs if self.logs else "")

    def canvases(self) -> List[str]:
        """The PNG pictures the check saved (turtlesim canvases)."""
        if not self.artifacts_dir:
            return []
        return sorted(glob.glob(os.path.join(self.artifacts_dir, "*.png")))


def select(milestones: Sequence[Milestone], packages: Iterable[str], only: Optional[Iterable[str]],
           reference: bool) -> List[Milestone]:
    """The milestones to grade for a submission holding `packages` (see the module docstring)."""
    if only:
        wanted = set(only)
        return [m for m in milestones if m.name in wanted]
    if reference:
        return list(milestones)
    held = set(packages)
    own = [m for m in milestones if m.packages and held & set(m.packages)]
    near = [m for m in milestones if any(_close(p, held) for p in m.packages)]
    return own or near or [m for m in milestones if m.packages]


def _close(name: str, candidates: Iterable[str]) -> List[str]:
    """The candidates that look like a misspelling of `name` (mychatter, chatter_pkg for chatter)."""
    return difflib.get_close_matches(name, list(candidates), 1, CLOSE_NAME_RATIO)


def rosbuild_packages(root: str) -> List[str]:
    """Folders under `root` (relative) that are rosbuild packages: a manifest.xml and no package.xml."""
    found = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in scripts.SKIPPED_DIRS)
        if "manifest.xml" in files and "package.xml" not in files:
            found.append(os.path.relpath(folder, root))
    return found


def missing_package(milestone: Milestone, found: Sequence[Package], root: str = "") -> Optional[str]:
    """Why the submission cannot be graded on `milestone` because the package the text names is
    not in it, or None when it is there (or the milestone needs none). `root`: the submission's
    files, where a rosbuild package of the expected name is looked for."""
    if not milestone.packages:
        return None
    names = [p.name for p in found if p.name]
    if set(names) & set(milestone.packages):
        return None
    old = [f for f in (rosbuild_packages(root) if root else []) if os.path.basename(f) in milestone.packages]
    if old:
        return causes.finding("rosbuild", (
            "%s is a rosbuild package (manifest.xml, no package.xml), from before catkin: Noetic builds catkin "
            "packages only. Make it one: a package.xml (catkin_create_pkg %s rospy std_msgs writes one) naming its "
            "dependencies, and a catkin CMakeLists.txt (find_package(catkin ...), catkin_package()) in place of "
            "rosbuild's (rosbuild_init)") % (old[0], os.path.basename(old[0])))
    expected = " or ".join("'%s'" % n for n in milestone.packages)
    unreadable = ["%s (%s)" % (os.path.basename(p.path), p.problem) for p in found if not p.name]
    if not names and not unreadable:
        return ("no catkin package found: expected a package named %s (a folder with a package.xml whose "
                "<name> is %s)" % (expected, expected))
    text = "expected a catkin package named %s, found: %s" % (expected, ", ".join(names + unreadable))
    close = [c for n in milestone.packages for c in _close(n, names)]
    if close:
        text += " (the package name comes from package.xml's <name>: rename '%s' to %s, as the text names it)" \
                % (close[0], expected)
    return text


# The verdict of a milestone the grading did not reach, or whose run it ended, when the TA stopped it.
INTERRUPTED = causes.finding("interrupted", "not graded (interrupted)")


def build_failed(summary: str) -> str:
    return "the submission does not build (catkin_make failed):\n%s" % summary


def _tail(path: str, nbytes: int) -> Optional[Tuple[int, str]]:
    """(the size of the file `path`, its last `nbytes` decoded); None when it cannot be read."""
    try:
        size = os.path.getsize(path)
        with open(path, "rb") as f:
            f.seek(max(0, size - nbytes))
            return size, f.read().decode("utf-8", errors="replace")
    except OSError:
        return None


def log_tails(folder: str, lines: int = LOG_TAIL_LINES) -> str:
    """The last lines of each student log (`*.log`) a check wrote in `folder`."""
    paths = sorted(glob.glob(os.path.join(folder, "*.log")), key=os.path.getmtime)[-MAX_LOGS:]
    parts = []
    for path in paths:
        read = _tail(path, LOG_TAIL_BYTES)
        if read is None:
            continue
        size, text = read[0], _ANSI.sub("", read[1])
        tail = [line[:300] for line in text.splitlines()[-lines:]]
        big = " (%d bytes)" % size if size > LOG_TAIL_BYTES else ""
        title = "--- last lines of %s%s ---" % (os.path.basename(path), big)
        parts.append("\n".join([title] + (tail or ["(empty)"])))
    return "\n".join(parts)


def output_hints(folder: str, known: Iterable[str] = ()) -> List[str]:
    """The causes the student logs of a run show (course_milestones.scripts.output_problems:
    a script run by sh, Python 2 in Python 3, ...), each once, less those whose cause a hint in
    `known` (found from the student's files) already names: the files say where, the output only
    that it happened."""
    said = {causes.of(k) for k in known}
    seen: List[str] = []
    for path in sorted(glob.glob(os.path.join(folder, "*.log"))):
        read = _tail(path, 4 * LOG_TAIL_BYTES)
        if read is not None:
            seen.extend(h for h in scripts.output_problems(read[1]) if h not in seen and causes.of(h) not in said)
    return seen


# What a student reads in place of a folder of the grader's their node printed.
GRADER_FOLDER = "<grader's folder>"


def without_grader_paths(text: str, folders: Sequence[str]) -> str:
    """`text` for a student: each of the grader's `folders` (the work folder's src first) cut out of
    the paths it quotes, so `<work>/ws/src/chatter/scripts/talker.py` reads chatter/scripts/talker.py.
    A path a check quoted cut at its start (`...k/alice/ws/src/chatter/...`) loses its fragment too:
    whatever ends with the folder's last three parts. A folder quoted by itself (what a node printed
    of its environment) reads GRADER_FOLDER."""
    for folder in folders:
        parts = [p for p in folder.rstrip("/").split("/") if p]
        if parts:
            tail = re.escape("/".join(parts[-3:]))
            text = re.sub(r"[^\s'\"(]*" + tail + "/", "", text)
            text = re.sub(r"[^\s'\"(]*" + tail + r"(?![\w.-])", GRADER_FOLDER, text)
    return text


def output_capped(folder: str) -> List[str]:
    """A sentence for each student log that reached the file-size cap (the node was stopped there)."""
    return ["%s: the node printed more than %d MB, where the grader stops it (print less)"
            % (os.path.basename(p), MAX_FILE_BYTES // 2**20)
            for p in sorted(glob.glob(os.path.join(folder, "*.log"))) if os.path.getsize(p) >= MAX_FILE_BYTES]


def trim_files(folder: str, keep: int = KEEP_BYTES, skip: str = "") -> None:
    """Keep only the last `keep` bytes of every file bigger than that under `folder`, except
    below `skip`."""
    for root, dirs, files in os.walk(folder):
        dirs[:] = [d for d in dirs if not skip or os.path.join(root, d) != skip]
        for name in files:
            path = os.path.join(root, name)
            try:  # never through a link: the student's run folder is under `folder`
                fd = os.open(path, os.O_RDWR | os.O_NOFOLLOW | os.O_NONBLOCK)
            except OSError:
                continue
            with os.fdopen(fd, "r+b") as f:
                info = os.fstat(f.fileno())
                if not stat.S_ISREG(info.st_mode) or info.st_size <= keep:
                    continue
                f.seek(info.st_size - keep)
                tail = f.read()
                f.seek(0)
                f.write(b"[... first %d bytes left out ...]\n" % (info.st_size - keep) + tail)
                f.truncate()


# The limits at which the sandbox's watcher ends a run's processes. A run whose code reached one
# fails whatever its check saw before: otherwise the verdict of a fork bomb beside a correct node
# would hang on which came first, the check or the limit.
ENDING_LIMITS = ("memory", "processes", "disk")
ENDED_BY_LIMIT = ("the checks passed, but your code reached a sandbox limit and all its processes were "
                  "ended (a solution must stay within the limits: see the sandbox note below)")


def sandbox_hits(report_path: str) -> Dict[str, str]:
    """The limits the student's code hit in a run, each with its sentence, from the sandbox's
    report (written by the trusted check, never by student code); empty when none or no report."""
    try:
        with open(report_path) as f:
            hits = json.load(f).get("hits", {})
    except (OSError, ValueError, AttributeError):
        return {}
    return {str(k): v for k, v in hits.items() if isinstance(v, str)} if isinstance(hits, dict) else {}


def sandbox_notes(hits: Dict[str, str]) -> str:
    """The hits in words ("" when none)."""
    return "\n".join("sandbox limit: %s" % sentence for _, sentence in sorted(hits.items()))


def ended_by_limit(hits: Dict[str, str]) -> bool:
    return any(limit in hits for limit in ENDING_LIMITS)
