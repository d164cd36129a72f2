"""Grade every sample submission under courses/robotics_labs/samples/ in one grader run, and check each
verdict against the sample's expected.json:
  {"<milestone>": {"passed": true}} or {"<milestone>": {"passed": false, "reason": "<regex>"}}
The regex must match the milestone's output in the sample's Gradescope results.json (the
failing check in words plus the student's log tails); a failure's "cause" (a course_format.causes
key), when given, must be the one its results.json carries, and the class's failure_groups.csv must
group the sample under it. Only the listed milestones are graded.
A sample with a `derive.json` is a variant of another folder of this checkout (a reference
solution, another sample), so that neither code nor answers are written twice: it is made in a
temporary folder before grading, from {"copy": [[source, target], ...]} (folders of the checkout,
copied into the sample, one over another), then the sample's own files over them, then {"remove": [path, ...]} and
{"replace": [[path, old, new], ...]} (each `old` must be there).
`"needs_isolation": true` (the attack samples): the verdict holds only where the sandbox isolates
student code; where it would run with the grader's rights (isolation `none`: not root and no
namespaces, e.g. `make test` as a user in a container), the sample is not graded and its test is
skipped, saying so.
Afterwards no process of any run may be left (bad samples fork, setsid, ignore SIGINT).
The same grading gives the class's similarity.csv (the sim_chatter_* samples: carol is alice's
copy with its names changed and lines reordered, bob wrote his own) and a folder to regrade one
student in (grade --regrade).

The grading starts as soon as the session knows these tests will run (start_early, called by
the root conftest.py), so its ~270 s, mostly spent waiting on the students' nodes, overlap the
rest of the suite; the first test here waits for it.
"""
from __future__ import annotations

import csv
import json
import re
import shutil
import subprocess
from pathlib import Path
from typing import Dict, List, Tuple

import pytest

from course_sandbox import levels
from course_sandbox.policy import DEFAULT_USER
from course_testkit.gradings import processes_of
from course_testkit import sample_grading
from course_testkit.sample_grading import BackgroundGrading
from course_testkit.samples import materialise

ROOT = Path(__file__).resolve().parents[1]
ALL_SAMPLES = sorted(p.parent for p in ROOT.glob("courses/robotics_labs/samples/*/expected.json"))


def needs_isolation(sample: Path) -> bool:
    return any(e.get("needs_isolation") for e in json.loads((sample / "expected.json").read_text()).values())


# Where student code would run with the grader's rights (isolation none: not root, no namespaces,
# e.g. `make test` as a user in a container), an attack sample is not graded at all: its fork bomb
# would spend this user's process limit under every other run, the test's own included.
ISOLATION = levels.detect(DEFAULT_USER)
SAMPLES = [s for s in ALL_SAMPLES if not (ISOLATION == levels.NONE and needs_isolation(s))]
JOBS = 3  # 20 reference gradings at 3 gave 0 wrong verdicts, and at the default 6 (bench/grade_bench.py)
GRADER_TIMEOUT_S = 3600


class SampleGrading(BackgroundGrading):
    """`rosrun course_grader grade` on every sample (derived ones made first), in the background."""

    def __init__(self) -> None:
        super().__init__([], "grader-samples-")
        self.checkout_before = checkout_state()
        handed_in = [materialise(s, self.folder / "derived") for s in SAMPLES]
        self.args = [str(s) for s in handed_in] + ["--only-from", "expected.json", "--jobs", str(JOBS)]
        self.start()


def checkout_state() -> str:
    """What `git status` and `git diff` say of the course checkout (a sample must change neither),
    or its files where there is no checkout (sample_grading.git_state)."""
    return sample_grading.git_state(ROOT)


GRADING = pytest.StashKey[SampleGrading]()


def start_early(config: pytest.Config) -> None:
    grading = SampleGrading()
    config.stash[GRADING] = grading
    config.add_cleanup(grading.stop)


def expectations() -> List[Tuple[str, str, Dict]]:
    return sample_grading.expectations(ALL_SAMPLES)


@pytest.fixture(scope="module")
def graded(request: pytest.FixtureRequest) -> Path:
    if GRADING not in request.config.stash:  # this module was not known to be selected at collection
        start_early(request.config)
    return request.config.stash[GRADING].graded(GRADER_TIMEOUT_S)


def _tests_of(graded: Path, sample: str) -> Dict[str, Dict]:
    return sample_grading.tests_of(graded, sample)


@pytest.mark.parametrize("sample,milestone,expected", expectations(), ids=lambda v: v if isinstance(v, str) else "")
def test_verdict(graded: Path, sample: str, milestone: str, expected: Dict) -> None:
    if ROOT / "courses" / "robotics_labs" / "samples" / sample not in SAMPLES:
        pytest.skip("not graded: student code would run with the grader's rights here (isolation %s)" % ISOLATION)
    problem = sample_grading.verdict_problem(graded, sample, milestone, expected)
    assert not problem, problem


def _csv(path: Path) -> List[Dict[str, str]]:
    with path.open(newline="") as f:
        return list(csv.DictReader(f))


def test_the_class_failures_group_by_cause(graded: Path) -> None:
    """Every sample with an expected cause is in that group; groups come largest first."""
    groups = _csv(graded / "failure_groups.csv")
    students = {(g["milestone"], g["cause"]): g["students"].split() for g in groups}
    for sample, milestone, expected in expectations():
        if "cause" in expected and ROOT / "courses" / "robotics_labs" / "samples" / sample in SAMPLES:
            assert sample in students.get((milestone, expected["cause"]), []), \
                "%s is not in the group %s/%s: %s" % (sample, milestone, expected["cause"], groups)
    counts = [int(g["count"]) for g in groups]
    assert counts == sorted(counts, reverse=True) and all(int(g["count"]) == len(g["students"].split()) for g in groups)
    milestones = {m["milestone"]: m for m in _csv(graded / "milestones.csv")}
    assert int(milestones["chatter"]["passed"]) >= 3 and float(milestones["chatter"]["median_seconds"]) > 0
    page = (graded / "report.html").read_text()
    assert page.index("The class at a glance") < page.index("Failures by cause") < page.index("id='verdicts'")


def test_the_copied_pair_is_flagged_and_the_independent_pair_is_not(graded: Path) -> None:
    pairs = {(p["student_a"], p["student_b"], p["package"]): float(p["score"])
             for p in _csv(graded / "similarity.csv")}
    assert ("sim_chatter_alice", "sim_chatter_carol", "chatter") in pairs, pairs
    assert not [p for p in pairs if "sim_chatter_bob" in p], pairs
    page = (graded / "report.html").read_text()
    assert "sim_chatter_alice and sim_chatter_carol, chatter" in page and "class='side'" in page


def test_regrade_changes_one_student_only(graded: Path) -> None:
    """A copy of the class's grading where one student's verdict was changed by hand: regrading
    that student from their submission gives their verdict back and leaves everyone else's files
    as they were."""
    student = "bad_no_package"
    out = graded.parent / "regrade"  # where the sandbox user may pass, as for the grading itself
    for results in graded.glob("*/results.json"):
        (out / results.parent.name).mkdir(parents=True)
        shutil.copyfile(results, out / results.parent.name / "results.json")
    shutil.copyfile(graded / "gradebook.csv", out / "gradebook.csv")
    mine = out / student / "results.json"
    tampered = json.loads(mine.read_text())
    tampered["tests"][0].update(status="passed", score=tampered["tests"][0]["max_score"])
    mine.write_text(json.dumps(tampered))
    others = {p: p.read_bytes() for p in out.glob("*/results.json") if p != mine}
    rows_before = _csv(out / "gradebook.csv")
    done = subprocess.run(["rosrun", "course_grader", "grade", "--regrade", student, "--only-from", "expected.json",
                           "--out", str(out), str(ROOT / "courses" / "robotics_labs" / "samples" / student)],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stdout
    assert json.loads(mine.read_text())["tests"][0]["status"] == "failed"
    assert {p: p.read_bytes() for p in out.glob("*/results.json") if p != mine} == others
    assert _csv(out / "gradebook.csv") == rows_before  # the row given back; every other row as it was
    groups = {(g["milestone"], g["cause"]): g["students"].split() for g in _csv(out / "failure_groups.csv")}
    assert student in groups[("chatter", "package_missing")]
    assert "graded 1 submission(s)" in done.stdout


def test_outputs_for_the_class(graded: Path) -> None:
    gradebook = (graded / "gradebook.csv").read_text().splitlines()
    assert gradebook[0].startswith("student,") and len(gradebook) == len(SAMPLES) + 1
    assert "<table>" in (graded / "report.html").read_text()
    for sample in SAMPLES:
        for milestone in json.loads((sample / "expected.json").read_text()):
            assert (graded / sample.name / milestone / "junit.xml").is_file()


def test_nothing_left_running(graded: Path) -> None:
    """Every run's trusted processes carry COURSE_ARTIFACTS_DIR under the output folder, and every
    sandboxed student process has its workspace mounted from there (whatever it did to its
    environment): none may survive."""
    left = processes_of(str(graded))
    assert not left, "processes left running after grading:\n" + "\n".join(left)


def test_the_course_checkout_is_unchanged(request: pytest.FixtureRequest, graded: Path) -> None:
    """No sample (an attack rewrites the check, writes into the course) changed the checkout."""
    grading = request.config.stash[GRADING]
    assert checkout_state() == grading.checkout_before, "the grading changed the course checkout"


def test_every_verdict_says_which_isolation_was_in_force(graded: Path) -> None:
    for sample in SAMPLES:
        results = json.loads((graded / sample.name / "results.json").read_text())
        assert "isolation: " in results["output"], sample.name
    assert "Isolation of student code: " in (graded / "report.html").read_text()


def test_the_student_ros_logs_are_copied_out(graded: Path) -> None:
    """The trusted side copies each run's ROS logs (the student's node logs) into the outputs."""
    copied = sorted(p.name for p in (graded / "lab2_chatter_scripts" / "chatter" / "ros_log").rglob("*.log"))
    assert any(name.startswith("talker") for name in copied), copied


def test_no_log_tail_holds_a_line_of_the_sandbox(graded: Path) -> None:
    """A student's log tail holds what their code printed, never a line of the grader's making:
    a shell the sandbox started in a folder its user cannot read began it with `sh: 0: getcwd()
    failed: Permission denied` (lab2_chatter_shell_clean_log's talker runs a shell as it starts)."""
    found = ["%s/%s: %s" % (sample.name, name, line) for sample in SAMPLES
             for name, test in _tests_of(graded, sample.name).items()
             for line in test["output"].splitlines() if "getcwd() failed" in line]
    assert not found, "\n".join(found)
    if ROOT / "courses" / "robotics_labs" / "samples" / "lab2_chatter_shell_clean_log" in SAMPLES:
        assert "talker starting" in _tests_of(graded, "lab2_chatter_shell_clean_log")["chatter"]["output"]


UNITTEST_WORDS = re.compile(r"is not true|is not false| != |AssertionError|Traceback \(most recent call last\)")


def test_no_reason_speaks_unittest(graded: Path) -> None:
    """A student reads the check's sentence, never the assertion behind it: no failure reason
    holds unittest's words or a traceback, unless it quotes the student's own (a line of their
    node's or their build's log)."""
    found = []
    for sample in SAMPLES:
        for name, test in _tests_of(graded, sample.name).items():
            if test["status"] == "passed":
                continue
            reason = test["output"].split("\n\n--- last lines of", 1)[0]
            logs = "".join(p.read_text(errors="replace") for p in (graded / sample.name / name).rglob("*.log"))
            build_log = graded / "_work" / sample.name / "build.log"
            logs += build_log.read_text(errors="replace") if build_log.is_file() else ""
            for line in reason.splitlines():
                if UNITTEST_WORDS.search(line) and line.strip() not in logs:
                    found.append("%s/%s: %s" % (sample.name, name, line))
    assert not found, "\n".join(found)


def test_no_text_a_student_reads_holds_the_graders_paths(graded: Path) -> None:
    """Reasons, log tails and tracebacks quote paths from the student's package down: never the
    grader's output or work folder, however a check or a log cut the path."""
    found = []
    for sample in SAMPLES:
        results = json.loads((graded / sample.name / "results.json").read_text())
        texts = [results.get("output", "")] + [t.get("output", "") for t in results["tests"]]
        for text in texts:
            for marker in (str(graded), "/_work/", str(graded.parent)):
                if marker in text:
                    found.append("%s: %r" % (sample.name, text[max(0, text.index(marker) - 80):][:200]))
    assert not found, "\n".join(found)
