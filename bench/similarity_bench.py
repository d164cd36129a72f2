#!/usr/bin/env python3
"""Time of the similarity check (course_grader.similarity) on a class, as a figure, never an
assertion (issue 30, "Its time for a class of 30").

The class: N students, each holding every package of the reference solutions (13 packages: the
whole course handed in) with their own names (every identifier the student could choose, suffixed
per student) and one package of a sample submission of this checkout (courses/robotics_labs/samples, in turn),
compared against the reference solutions and catkin_create_pkg's output as boilerplate, as
`grade` does. Prints the class, the packages and pairs compared, the pairs listed and the seconds
(median of --rounds).

    python3 bench/similarity_bench.py [--students 30] [--rounds 3]
"""
from __future__ import annotations

import argparse
import re
import shutil
import statistics
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
from course_grader import similarity, submissions

SOLUTIONS = ROOT / "courses" / "robotics_labs" / "solution"
# Names a student chooses: a function, a variable, a class (not ROS's API, which all share).
_OWN_NAME = re.compile(r"\b(def|class)\s+([A-Za-z_]\w*)")


def renamed(folder: Path, suffix: str) -> None:
    """Every function and class the student's Python files define, renamed with `suffix`."""
    for path in folder.rglob("*.py"):
        text = path.read_text(errors="replace")
        names = {m.group(2) for m in _OWN_NAME.finditer(text) if not m.group(2).startswith("__")}
        for name in names:
            text = re.sub(r"\b%s\b" % re.escape(name), name + suffix, text)
        path.write_text(text)


def make_class(dest: Path, size: int) -> dict:
    samples = sorted(p for p in (ROOT / "courses" / "robotics_labs" / "samples").iterdir()
                     if (p / "expected.json").is_file() and not (p / "derive.json").exists())
    students = {}
    for i in range(size):
        student = dest / ("student%02d" % i)
        shutil.copytree(SOLUTIONS, student / "src", ignore=shutil.ignore_patterns("CMakeLists.txt", "test"))
        sample = samples[i % len(samples)]
        for package in submissions.find_packages(str(sample))[:1]:
            shutil.copytree(package.path, student / "extra" / Path(package.path).name, dirs_exist_ok=True)
        renamed(student, "_s%02d" % i)
        students[student.name] = str(student)
    return students


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--students", type=int, default=30)
    parser.add_argument("--rounds", type=int, default=3)
    opts = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="similarity-bench-") as tmp:
        students = make_class(Path(tmp), opts.students)
        found = [p.name for s in students.values() for p in submissions.find_packages(s)]
        times, pairs = [], []
        for _ in range(opts.rounds):
            started = time.monotonic()
            pairs = similarity.similar_pairs(students, [str(SOLUTIONS)])
            times.append(time.monotonic() - started)
    print("class: %d students, %d packages in all (%d names), %d pairs of students"
          % (len(students), len(found), len(set(found)), len(students) * (len(students) - 1) // 2))
    print("similar pairs listed (score >= %.2f): %d" % (similarity.THRESHOLD, len(pairs)))
    print("similarity check: median %.1f s of %d rounds (%s)" % (statistics.median(times), len(times),
                                                                 ", ".join("%.1f" % t for t in times)))


if __name__ == "__main__":
    main()
