"""Submissions too alike to be independent work: winnowed fingerprints (PyPI copydetect, the
approach of MOSS) of each student's Python, C++, launch and CMake files, package by package.
Never part of a verdict: a TA reads the pairs and the lines they share.

Each student's package of one name is one document per language (its files of that language
joined, in name order, so that moving code between files or reordering them changes little);
copydetect replaces names by one letter each, so renamed variables and functions still match.
What every submission holds anyway is boilerplate, whose fingerprints are dropped before
comparing: the course's reference solutions (when the checkout has them), what
`catkin_create_pkg` generates (every package.xml and CMakeLists.txt starts from it; made afresh
at each run, never stored) and any folder given (`grade --boilerplate DIR`). A pair's score for a
package is the larger of the two shares of a document's fingerprinted tokens found in the
other's, over the package's languages weighed by size.
"""
from __future__ import annotations

import csv
import html
import io
import itertools
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from typing import Dict, Iterable, List, NamedTuple, Optional, Sequence, Set, Tuple

from course_milestones.scripts import SKIPPED_DIRS

from course_grader import submissions

CSV_NAME = "similarity.csv"
# A pair is listed from this score up. Measured on the samples (docs/grading.md): a copy with its
# names changed and lines reordered scores 0.9-1.0; independent solutions of one exercise 0.0-0.3.
THRESHOLD = 0.6
# copydetect's noise threshold k (a match shorter than k filtered characters is ignored) and
# guarantee threshold (a match at least that long is always found): its defaults.
NOISE = 25
GUARANTEE = 30
MAX_FILE_BYTES = 256 * 1024  # larger files are data, not code a student wrote
# What of a package is compared, per language: a submission of many big files (its unpacked size is
# bounded by submissions.MAX_UNPACKED_BYTES only) costs the class no more than this.
MAX_DOCUMENT_BYTES = 1024 * 1024
# A package name catkin_create_pkg is given (REP 144): a student's package.xml may say anything.
_PACKAGE_NAME = re.compile(r"^[a-z][a-z0-9_]{0,63}$")
# pygments' lexer for each kind of file, and the comment a file's name is joined under.
LANGUAGES = {"python": "#", "cpp": "//", "xml": None, "cmake": "#"}
CPP_SUFFIXES = (".cpp", ".cc", ".cxx", ".h", ".hpp", ".hh")
# What catkin_create_pkg is given to make the boilerplate: the dependencies the course's texts name.
CREATE_PKG_DEPENDS = ("rospy", "roscpp", "std_msgs", "geometry_msgs", "turtlesim", "message_generation",
                      "message_runtime", "tf2_ros")
SHOWN_SLICES = 6  # shared passages shown per pair and language
SHOWN_OPEN = 5  # the pairs whose shared passages the report shows opened (the others: a click away)


def language_of(path: str) -> Optional[str]:
    """The language a file is compared as, None when it is not compared."""
    name = os.path.basename(path)
    if name == "CMakeLists.txt" or name.endswith(".cmake"):
        return "cmake"
    if name.endswith(".py"):
        return "python"
    if name.endswith(CPP_SUFFIXES):
        return "cpp"
    if name.endswith((".launch", ".launch.xml")):
        return "xml"
    try:
        with open(path, "rb") as f:
            first = f.readline(200)
    except OSError:
        return None
    return "python" if first.startswith(b"#!") and b"python" in first else None


def package_documents(package_dir: str) -> Dict[str, str]:
    """A package's files as one text per language (package.xml is left out: catkin_create_pkg's
    and the package's own names and dependencies, nothing a student writes)."""
    parts: Dict[str, List[str]] = {}
    for folder, dirs, files in os.walk(package_dir):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("."))
        for name in sorted(files):
            path = os.path.join(folder, name)
            language = language_of(path) if os.path.isfile(path) and not os.path.islink(path) else None
            if language is None or os.path.getsize(path) > MAX_FILE_BYTES:
                continue
            if sum(len(t) for t in parts.get(language, [])) >= MAX_DOCUMENT_BYTES:
                continue
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            comment = LANGUAGES[language]
            rel = os.path.relpath(path, os.path.dirname(package_dir))
            head = "%s %s\n" % (comment, rel) if comment else "<!-- %s -->\n" % rel
            parts.setdefault(language, []).append(head + text + "\n")
    return {language: "".join(texts) for language, texts in parts.items()}


def _fingerprint(text: str, language: str, boilerplate: Set[int] = frozenset()):
    """copydetect's fingerprint of `text`, without the fingerprints in `boilerplate` (dropped here:
    copydetect's own dropping assumes each fingerprint occurs once in a document)."""
    from copydetect import CodeFingerprint
    from copydetect.utils import get_token_coverage
    made = CodeFingerprint("document", NOISE, GUARANTEE - NOISE + 1, language=language, fp=io.StringIO(text))
    if boilerplate:
        made.hashes = made.hashes - boilerplate
        made.hash_idx = {h: i for h, i in made.hash_idx.items() if h not in boilerplate}
        made.token_coverage = get_token_coverage(made.hash_idx, NOISE, len(made.filtered_code))
    return made


def boilerplate_hashes(folders: Iterable[str]) -> Dict[str, Set[int]]:
    """The fingerprints of every compared file under `folders`, per language."""
    found: Dict[str, Set[int]] = {}
    for folder in folders:
        for package in submissions.find_packages(folder) if os.path.isdir(folder) else []:
            for language, text in package_documents(package.path).items():
                found.setdefault(language, set()).update(_fingerprint(text, language).hashes)
    return found


def created_package(names: Iterable[str], dest: str) -> str:
    """`dest` holding what catkin_create_pkg makes for each package name (the boilerplate every
    student's package starts from), for the names that are valid package names; nothing when
    catkin_create_pkg is missing."""
    for name in sorted(n for n in set(names) if _PACKAGE_NAME.match(n)):
        try:
            subprocess.run(["catkin_create_pkg", name] + list(CREATE_PKG_DEPENDS), cwd=dest, check=False,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=60)
        except (OSError, subprocess.TimeoutExpired):
            break
    return dest


class Shared(NamedTuple):
    language: str
    left: str  # the passage in student_a's package
    right: str  # the matching passages in student_b's


class Pair(NamedTuple):
    student_a: str
    student_b: str
    package: str
    score: float
    shared: Tuple[Shared, ...] = ()


def _passages(text: str, slices) -> str:
    """The whole lines the slices [starts, ends] of `text` cover, each passage once, in order."""
    chunks = []
    for start, end in sorted(zip(slices[0], slices[1]))[:SHOWN_SLICES]:
        first = text.rfind("\n", 0, int(start)) + 1
        last = text.find("\n", int(end))
        chunks.append(text[first:last if last >= 0 else len(text)])
    return "\n...\n".join(chunks)


def compare(a: Dict[str, object], b: Dict[str, object]) -> Tuple[float, Tuple[Shared, ...]]:
    """Two students' fingerprinted documents of one package (language -> CodeFingerprint): the
    score and the shared passages."""
    from copydetect import compare_files
    overlap = covered = 0.0
    shared = []
    for language in sorted(set(a) & set(b)):
        fa, fb = a[language], b[language]
        _, (share_a, share_b), (slices_a, slices_b) = compare_files(fa, fb)
        size = max(fa.token_coverage, fb.token_coverage)
        overlap += max(share_a, share_b) * size
        covered += size
        if len(slices_a) and len(slices_a[0]):
            shared.append(Shared(language, _passages(fa.raw_code, slices_a), _passages(fb.raw_code, slices_b)))
    for language in set(a) ^ set(b):  # a language only one of them wrote counts against the likeness
        covered += (a.get(language) or b.get(language)).token_coverage
    return (overlap / covered if covered else 0.0), tuple(shared)


def similar_pairs(students: Dict[str, str], boilerplate: Sequence[str] = (), threshold: float = THRESHOLD,
                  create_pkg: bool = True) -> List[Pair]:
    """The pairs of students (name -> their unpacked files) whose packages of one name score at
    least `threshold`, highest first."""
    packages: Dict[str, Dict[str, Dict[str, str]]] = {}  # package -> student -> language -> text
    for student, files in students.items():
        for package in submissions.find_packages(files) if os.path.isdir(files) else []:
            if package.name:
                packages.setdefault(package.name, {})[student] = package_documents(package.path)
    with tempfile.TemporaryDirectory(prefix="catkin-create-pkg-") as made:
        folders = list(boilerplate) + ([created_package(packages, made)] if create_pkg else [])
        common = boilerplate_hashes(folders)
    pairs = []
    for package, by_student in sorted(packages.items()):
        prints = {s: {lang: _fingerprint(text, lang, common.get(lang, set()))
                      for lang, text in docs.items()} for s, docs in by_student.items()}
        for a, b in itertools.combinations(sorted(prints), 2):
            score, shared = compare(prints[a], prints[b])
            if score >= threshold:
                pairs.append(Pair(a, b, package, round(score, 3), shared))
    return sorted(pairs, key=lambda p: (-p.score, p.package, p.student_a, p.student_b))


def find(students: Dict[str, str], boilerplate: Sequence[str] = (), threshold: float = THRESHOLD) -> List[Pair]:
    """similar_pairs, in this Python when it has copydetect, else in the first python3 on PATH: the
    course venv's, where setup/install.sh installs copydetect (course_env puts it first; the grader
    itself runs as catkin's relay, with Debian's /usr/bin/python3). ImportError when neither has it."""
    try:
        import copydetect  # noqa: F401
        return similar_pairs(students, boilerplate, threshold)
    except ImportError:
        pass
    python = shutil.which("python3")
    if not python or os.path.abspath(python) == os.path.abspath(sys.executable):  # a venv's is a link: not realpath
        raise ImportError("copydetect is not installed (setup/install.sh installs it into the course venv)")
    asked = json.dumps({"students": students, "boilerplate": list(boilerplate), "threshold": threshold})
    done = subprocess.run([python, "-m", "course_grader.similarity"], input=asked, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, check=False)
    if done.returncode != 0:
        raise ImportError("%s -m course_grader.similarity failed: %s" % (python, done.stderr.strip()[-500:]))
    return [Pair(a, b, package, score, tuple(Shared(*s) for s in shared))
            for a, b, package, score, shared in json.loads(done.stdout)]


def write_csv(path: str, pairs: Sequence[Pair]) -> None:
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["student_a", "student_b", "package", "score"])
        for p in pairs:
            w.writerow([p.student_a, p.student_b, p.package, "%.2f" % p.score])


def html_section(pairs: Sequence[Pair]) -> List[str]:
    """The report's section: each pair with the passages they share side by side."""
    out = ["<h2 id='similarity'>Similar submissions</h2>",
           "<p>Package by package, boilerplate left out; never part of a verdict (score: the share of a "
           "package's code found in the other's, listed from %.2f).</p>" % THRESHOLD]
    if not pairs:
        return out + ["<p>No pair above the threshold.</p>"]
    out.append("<table><tr><th class='sort'>score</th><th class='sort left'>student a</th>"
               "<th class='sort left'>student b</th><th class='sort left'>package</th></tr>")
    for i, p in enumerate(pairs):
        out.append("<tr><td><a href='#pair-%d'>%.2f</a></td><td class='left'>%s</td><td class='left'>%s</td>"
                   "<td class='left'>%s</td></tr>" % (i, p.score, html.escape(p.student_a),
                                                      html.escape(p.student_b), html.escape(p.package)))
    out.append("</table>")
    for i, p in enumerate(pairs):
        out.append("<details id='pair-%d'%s><summary>%s and %s, %s: %.2f</summary>" % (
            i, " open" if i < SHOWN_OPEN else "", html.escape(p.student_a), html.escape(p.student_b), html.escape(p.package), p.score))
        for s in p.shared:
            out.append("<p>%s</p><div class='side'><pre>%s</pre><pre>%s</pre></div>"
                       % (html.escape(s.language), html.escape(s.left), html.escape(s.right)))
        out.append("</details>")
    return out


if __name__ == "__main__":  # find() in the course venv's python: a JSON question on stdin, the pairs on stdout
    question = json.load(sys.stdin)
    json.dump(similar_pairs(question["students"], question["boilerplate"], question["threshold"]), sys.stdout)
