"""The grader under a TA's hands, on a class of 6 samples graded on `chatter` (--jobs 3):

- one sample (attack_fill_disk) writes 320 MiB into its home at a bound of 100 MiB (--disk 100):
  it fails with the sandbox's disk reason while the two correct samples beside it pass;
- Ctrl+C (SIGINT) once those three have their verdicts: the grader exits with 130, every
  submission has its results.json, the verdicts so far are kept, the rest "not graded
  (interrupted)", and no process or pids cgroup of the grading is left;
- a grader killed with SIGKILL leaves its runs going; the next start ends them, removes their
  pids cgroups and its work folders.
"""
from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import tempfile
from pathlib import Path
from typing import Dict, Iterator, List, Set

import pytest

from course_sandbox import leftovers, pids_cgroup
from course_testkit.gradings import processes_of
from course_checks.nodes import NodeProcess
from course_testkit.samples import SAMPLES_DIR, materialise
from course_checks.waiting import wait_for

# Graded first (the first three), then the three still under way or queued when Ctrl+C comes.
FIRST = ["attack_fill_disk", "lab2_chatter_scripts", "bad_ignore_sigint"]
LATER = ["bad_hang", "bad_fork", "bad_crash"]
DISK_MIB = 100
VERDICTS_S = 300.0  # the first three verdicts (builds one at a time, then runs of about 15 s)
STOPPED_S = 60.0  # a generous deadline for "within seconds": behaviour, not a timing figure
INTERRUPTED = "not graded (interrupted)"


@pytest.fixture
def folder() -> Iterator[Path]:
    made = Path(tempfile.mkdtemp(prefix="grader-interrupt-"))
    made.chmod(0o755)  # the sandbox user passes through it to each student's workspace
    yield made
    shutil.rmtree(made, ignore_errors=True)


def start_grading(folder: Path, names: List[str], out: Path) -> NodeProcess:
    handed_in = [str(materialise(SAMPLES_DIR / name, folder / "derived")) for name in names]
    return NodeProcess(["rosrun", "course_grader", "grade", *handed_in, "--only", "chatter", "--jobs", "3",
                        "--disk", str(DISK_MIB), "--out", str(out)],
                       stdin=subprocess.DEVNULL, log_path=str(folder / ("%s.log" % out.name)))


def outputs(out: Path, student: str) -> Dict[str, Dict]:
    results = json.loads((out / student / "results.json").read_text())
    return {t["name"].split(":", 1)[0]: t for t in results["tests"]}


def cgroups_of(grader: int) -> Set[str]:
    """The pids cgroups that the grader or one of its processes (a check) made, as they are now."""
    parent = pids_cgroup.own_parent()
    if parent is None or not os.path.isdir(parent):
        return set()
    found = set()
    for name in os.listdir(parent):
        if name.startswith(pids_cgroup.NAME_PREFIX):
            maker = int(name[len(pids_cgroup.NAME_PREFIX):].split("-")[0])
            if maker == grader or leftovers.grading_of(maker) == grader:
                found.add(os.path.join(parent, name))
    return found


def wait_watching_cgroups(grader: NodeProcess, condition, timeout: float) -> Set[str]:
    """Wait for `condition()`, noting every pids cgroup of the grading meanwhile."""
    seen: Set[str] = set()

    def done() -> bool:
        seen.update(cgroups_of(grader.proc.pid))
        return condition() or not grader.running()
    assert wait_for(done, timeout, 0.2) and grader.running(), grader.output()[-3000:]
    return seen


def test_ctrl_c_keeps_the_verdicts_so_far_and_leaves_nothing(folder: Path) -> None:
    out = folder / "grades"
    grader = start_grading(folder, FIRST + LATER, out)
    try:
        seen = wait_watching_cgroups(
            grader, lambda: all((out / s / "results.json").is_file() for s in FIRST), VERDICTS_S)
        os.kill(grader.proc.pid, signal.SIGINT)
        code = grader.wait(STOPPED_S)
    finally:
        grader.end()
    said = grader.output()
    assert code == 130, said[-3000:]
    disk = outputs(out, "attack_fill_disk")["chatter"]
    assert disk["status"] == "failed"
    assert "wrote more than %d MiB to disk together" % DISK_MIB in disk["output"], disk["output"]
    for student in FIRST[1:]:
        assert outputs(out, student)["chatter"]["status"] == "passed", outputs(out, student)
    later = [outputs(out, s)["chatter"] for s in LATER]
    assert any(t["output"].startswith("FAILED: " + INTERRUPTED) for t in later), later
    assert len((out / "gradebook.csv").read_text().splitlines()) == 1 + len(FIRST + LATER)
    assert "interrupted:" in said
    assert not processes_of(str(out)), processes_of(str(out))
    if pids_cgroup.available():
        assert seen, "no pids cgroup of the grading was seen: the check of what is left cannot fail"
        assert not {c for c in seen if os.path.exists(c)}, "pids cgroups left: %s" % seen


def test_the_next_start_cleans_what_a_killed_grader_left(folder: Path) -> None:
    out = folder / "grades"
    grader = start_grading(folder, ["lab2_chatter_scripts", "bad_hang"], out)
    try:
        # bad_hang's run under way: its talker (which never publishes) is up in its sandbox.
        seen = wait_watching_cgroups(grader, lambda: any("bad_hang/ws/src/chatter/scripts/talker.py" in p
                                                         for p in processes_of(str(out))), VERDICTS_S)
        os.kill(grader.proc.pid, signal.SIGKILL)
        assert grader.wait(STOPPED_S) == -signal.SIGKILL
    finally:
        grader.end()
    assert processes_of(str(out)), "nothing was left running by a killed grader: nothing to clean"
    work = sorted(p.name for p in (out / "_work").iterdir())
    assert "lab2_chatter_scripts" in work, work
    # The next start, in the same output folder, on a submission with no package (nothing to build or run).
    again = start_grading(folder, ["bad_no_package"], out)
    try:
        code = again.wait(STOPPED_S)
    finally:
        again.end()
    assert code == 0, again.output()[-3000:]
    assert "ended what a killed grading left" in again.output(), again.output()[-3000:]
    assert not processes_of(str(out)), processes_of(str(out))
    if pids_cgroup.available():
        assert seen, "no pids cgroup of the grading was seen: the check of what is left cannot fail"
        assert not {c for c in seen if os.path.exists(c)}, "pids cgroups left: %s" % seen
    assert sorted(p.name for p in (out / "_work").iterdir() if p.is_dir()) == ["bad_no_package"]
