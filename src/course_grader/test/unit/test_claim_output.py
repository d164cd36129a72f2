"""claim_output: an output folder is one grading's; a killed grading's work folders are removed
at the next start, a live grading's folder is refused."""
import os

import pytest

from course_testkit.gradings import gone_pid, live_grader
from course_grader.runner import PID_FILE, WORK_DIR, Busy, claim_output, release_output


def test_the_work_of_a_killed_grading_is_removed(tmp_path):
    work = tmp_path / WORK_DIR
    (work / "alice" / "ws").mkdir(parents=True)
    (work / "durations.json").write_text("{}")
    (work / PID_FILE).write_text(str(gone_pid()))
    said = claim_output(str(tmp_path))
    assert "alice" in said
    assert sorted(os.listdir(work)) == ["durations.json", PID_FILE]
    assert (work / PID_FILE).read_text() == str(os.getpid())
    release_output(str(tmp_path))
    assert not (work / PID_FILE).exists()
    assert claim_output(str(tmp_path)) == ""


def test_a_live_grading_keeps_its_folder(tmp_path):
    with live_grader() as grader:
        (tmp_path / WORK_DIR).mkdir()
        (tmp_path / WORK_DIR / PID_FILE).write_text(str(grader.pid))
        (tmp_path / WORK_DIR / "bob").mkdir()
        with pytest.raises(Busy):
            claim_output(str(tmp_path))
        assert (tmp_path / WORK_DIR / "bob").is_dir()
