"""A grading folder as scores: per milestone and per assignment, and no score for what was not graded."""
from __future__ import annotations

import os

from course_lti import scores
from course_lti.scores import MilestoneInfo
from course_testkit.lti import write_results

COURSE = [MilestoneInfo("chatter", "Example publisher and subscriber", 10.0),
          MilestoneInfo("checkpoint1", "TimestampString publisher and subscriber", 20.0),
          MilestoneInfo("checkpoint3", "Patrol service", 10.0)]
PER_MILESTONE = {m.name: (m.name,) for m in COURSE}
FAILED = "FAILED: publishes nothing on /chatter_talk\n\n--- talker.log (last lines) ---\nTraceback ..."


def grading(tmp_path):
    out = str(tmp_path)
    write_results(out, "alice", [("chatter", 10, 10, "passed\n\n--- logs", ""), ("checkpoint1", 0, 20, FAILED, "silent")])
    write_results(out, "bob", [("chatter", 0, 10, "FAILED: not graded (interrupted)", "interrupted")])
    write_results(out, "dave", [("chatter", 10, 10, "passed", "")])
    with open(os.path.join(out, "gradebook.csv"), "w") as stream:
        stream.write("student,chatter,checkpoint1,total,max\nalice,10,0,10,30\nbob,0,,0,10\ncarol,,,,\ndave,10,,10,10\n")
    with open(os.path.join(out, "not-graded.csv"), "w") as stream:
        stream.write("student,reason\ncarol,your catkin_ws/src changed while it was copied\n")
    return out


def test_per_milestone_each_verdict_is_a_score_with_its_reason(tmp_path):
    out = grading(tmp_path)
    found = scores.from_grading(out, PER_MILESTONE, COURSE, "robotics_labs", True)
    alice = {s.item.resource_id: s for s in found.scores if s.student == "alice"}
    assert set(alice) == {"chatter", "checkpoint1"}  # checkpoint3: not graded for her, so no score
    assert (alice["chatter"].score_given, alice["chatter"].score_maximum, alice["chatter"].comment) == (10, 10, "passed")
    assert alice["checkpoint1"].comment == "failed: publishes nothing on /chatter_talk"  # the reason, not the logs
    assert alice["checkpoint1"].item == scores.LineItem("checkpoint1", "checkpoint1: TimestampString publisher and "
                                                        "subscriber", 20.0, "robotics_labs")
    payload = alice["checkpoint1"].payload("u-1")
    assert payload == {"userId": "u-1", "scoreGiven": 0.0, "scoreMaximum": 20.0,
                       "comment": "failed: publishes nothing on /chatter_talk",
                       "timestamp": alice["checkpoint1"].timestamp, "activityProgress": "Completed",
                       "gradingProgress": "FullyGraded"}


def test_who_was_not_graded_gets_no_score(tmp_path):
    out = grading(tmp_path)
    found = scores.from_grading(out, PER_MILESTONE, COURSE, "robotics_labs", True)
    assert {s.student for s in found.scores} == {"alice", "dave"}
    assert set(found.not_graded) == {"carol"}  # the hub could not snapshot her
    # bob's only verdict is the grading's interruption, not his work: held back, not a 0
    assert [(w.student, w.resource_id) for w in found.withheld] == [("bob", "chatter")]
    assert "regrade" in found.withheld[0].why


def test_a_student_without_results_is_not_graded(tmp_path):
    out = grading(tmp_path)
    os.remove(os.path.join(out, "dave", "results.json"))
    found = scores.from_grading(out, PER_MILESTONE, COURSE, "robotics_labs", True)
    assert "dave" in found.not_graded and "dave" not in {s.student for s in found.scores}


def test_per_assignment_the_sum_over_the_whole_assignment(tmp_path):
    out = grading(tmp_path)
    groups = {"lab2": ("chatter", "checkpoint1", "checkpoint3")}
    found = scores.from_grading(out, groups, COURSE, "robotics_labs", False)
    alice = [s for s in found.scores if s.student == "alice"]
    assert len(alice) == 1
    assert (alice[0].item.label, alice[0].score_given, alice[0].score_maximum) == ("lab2", 10.0, 40.0)
    assert alice[0].comment.splitlines() == [
        "chatter: passed (10/10)", "checkpoint1: failed (0/20): publishes nothing on /chatter_talk",
        "checkpoint3: not handed in (0/10)"]
    assert [(w.student, w.resource_id) for w in found.withheld] == [("bob", "lab2")]


def test_the_timestamp_is_when_the_results_were_written_the_same_at_every_read(tmp_path):
    out = grading(tmp_path)
    path = os.path.join(out, "alice", "results.json")
    os.utime(path, (1795000000.25, 1795000000.25))
    first = scores.from_grading(out, PER_MILESTONE, COURSE, "t", True).scores
    again = scores.from_grading(out, PER_MILESTONE, COURSE, "t", True).scores
    stamp = [s.timestamp for s in first if s.student == "alice"][0]
    assert stamp == "2026-11-18T11:06:40.250+00:00"
    assert first == again


def test_long_reasons_are_cut_with_a_mark():
    assert scores.cut("x" * 50, 20) == "x" * 14 + scores.CUT and len(scores.cut("x" * 50, 20)) == 20
    assert scores.cut("short", 20) == "short"
    verdict = scores.Verdict("m", 0, 10, False, "y" * 5000, "")
    assert len(scores.milestone_comment(verdict)) == scores.COMMENT_LIMIT
