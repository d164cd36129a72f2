"""One posting run's logic against an LMS double that answers in memory: what is sent, the record
that makes a second run send only what changed, the pending file, the dry run. (The same against a
real LTI 1.3 platform: tests/test_lti_platform.py.)"""
from __future__ import annotations

import json
import os

from course_lti import config, record
from course_lti.post import EXIT_PENDING, Poster
from course_lti.scores import MilestoneInfo
from course_lti.transport import Response, Unreachable
from course_lti.users import LmsUser
from course_testkit.lti import write_results

COURSE = [MilestoneInfo("chatter", "Example publisher and subscriber", 10.0),
          MilestoneInfo("checkpoint1", "TimestampString publisher and subscriber", 20.0)]
USERS = {"alice": LmsUser("u-alice", "https://lms.test"), "bob": LmsUser("u-bob", "https://lms.test")}


class Lms:
    """The LMS's answers, in memory: a token, line items, scores; `down` refuses every connection."""

    def __init__(self) -> None:
        self.lineitems = {}  # url -> line item
        self.scores = []  # (line item url, score)
        self.calls = []
        self.down = False
        self.refuse_user = ""

    def send(self, method, url, headers, body=None):
        self.calls.append((method, url))
        if self.down:
            raise Unreachable("connection refused")
        if url.endswith("/token"):
            return Response(200, {}, b'{"access_token": "t", "expires_in": 3600}')
        assert headers["Authorization"] == "Bearer t"
        data = json.loads(body) if body else None
        if url.endswith("/scores"):
            if data["userId"] == self.refuse_user:
                return Response(400, {}, b'{"message": "user not enrolled"}')
            self.scores.append((url[:-len("/scores")], data))
            return Response(200, {}, b"")
        if method == "POST":
            item = dict(data, id="https://lms.test/items/%d" % (len(self.lineitems) + 1))
            self.lineitems[item["id"]] = item
            return Response(201, {}, json.dumps(item).encode())
        return Response(200, {}, json.dumps(list(self.lineitems.values())).encode())

    def posted(self):
        return sorted((self.lineitems[url]["resourceId"], s["userId"], s["scoreGiven"]) for url, s in self.scores)


def a_grading(tmp_path, write_config, **fields):
    out = str(tmp_path / "grades")
    write_results(out, "alice", [("chatter", 10, 10, "passed", ""), ("checkpoint1", 0, 20, "FAILED: silent", "silent")])
    write_results(out, "bob", [("chatter", 10, 10, "passed", "")])
    return out, config.load(write_config(**fields))


def poster(loaded, lms, lines, users=USERS, **kwargs):
    return Poster(loaded, users, "robotics_labs", COURSE, say=lines.append, send=lms.send, sleep=lambda s: None,
                  **kwargs)


def test_scores_go_to_line_items_created_once_and_a_rerun_sends_nothing(tmp_path, write_config):
    out, loaded = a_grading(tmp_path, write_config)
    lms, lines = Lms(), []
    summary = poster(loaded, lms, lines).run(out)
    assert lms.posted() == [("chatter", "u-alice", 10.0), ("chatter", "u-bob", 10.0), ("checkpoint1", "u-alice", 0.0)]
    assert sorted(i["resourceId"] for i in lms.lineitems.values()) == ["chatter", "checkpoint1"]
    assert all(i["tag"] == "robotics_labs" for i in lms.lineitems.values())
    assert summary.line() == "LMS: 3 scores posted, 0 unchanged, 0 not graded (no score sent), 0 pending"
    assert summary.exit_code() == 0 and not os.path.exists(os.path.join(out, record.PENDING))
    assert sum(1 for m, u in lms.calls if u.endswith("/token")) == 1  # one token for the run
    lms.calls.clear()
    again = poster(loaded, lms, lines).run(out)
    assert again.line() == "LMS: 0 scores posted, 3 unchanged, 0 not graded (no score sent), 0 pending"
    assert lms.calls == []  # nothing sent at all, not even a token request


def test_a_changed_score_is_sent_again_alone(tmp_path, write_config):
    out, loaded = a_grading(tmp_path, write_config)
    lms = Lms()
    poster(loaded, lms, []).run(out)
    write_results(out, "bob", [("chatter", 0, 10, "FAILED: regraded: silent", "silent")])  # a regrade
    os.utime(os.path.join(out, "bob", "results.json"), (2000000000, 2000000000))
    lms.scores.clear()
    summary = poster(loaded, lms, []).run(out)
    assert lms.posted() == [("chatter", "u-bob", 0.0)] and summary.unchanged == 2
    assert lms.scores[0][1]["timestamp"] == "2033-05-18T03:33:20.000+00:00"


def test_an_lms_that_is_down_leaves_every_score_pending_and_the_next_run_posts_them(tmp_path, write_config):
    out, loaded = a_grading(tmp_path, write_config, retries=2)
    lms, lines = Lms(), []
    lms.down = True
    summary = poster(loaded, lms, lines).run(out)
    assert summary.exit_code() == EXIT_PENDING and len(summary.pending) == 3
    assert summary.line().endswith("3 pending: see %s" % os.path.join(out, record.PENDING))
    assert len(lms.calls) == 3  # the token request, tried 3 times: the others were not tried once it was down
    kept = record.load_pending(out)
    assert [(p.student, p.user_id) for p in kept] == [("alice", "u-alice"), ("alice", "u-alice"), ("bob", "u-bob")]
    assert kept[0].score["scoreMaximum"] == 10.0 and "connection refused" in kept[0].why
    lms.down = False
    later = poster(loaded, lms, lines).run(out)
    assert later.line() == "LMS: 3 scores posted, 0 unchanged, 0 not graded (no score sent), 0 pending"
    assert "LMS: 3 score(s) pending from an earlier run: trying them again" in lines
    assert not os.path.exists(os.path.join(out, record.PENDING))


def test_a_refused_score_and_an_unknown_student_are_pending_the_others_posted(tmp_path, write_config):
    out, loaded = a_grading(tmp_path, write_config)
    lms = Lms()
    lms.refuse_user = "u-bob"
    summary = poster(loaded, lms, [], users={"bob": USERS["bob"]}).run(out)
    assert lms.posted() == []
    whys = sorted(p.why for p in summary.pending)
    assert "user not enrolled" in whys[0] and "HTTP 400" in whys[0]
    assert whys[1].startswith("no LMS user id for alice") and len(whys) == 3
    lms.refuse_user = ""
    summary = poster(loaded, lms, [], users=USERS).run(out)
    assert summary.posted == 3 and not summary.pending


def test_a_student_from_another_platform_is_not_posted_to(tmp_path, write_config):
    out, loaded = a_grading(tmp_path, write_config)
    summary = poster(loaded, Lms(), [], users={"alice": LmsUser("u", "https://other.lms"), "bob": USERS["bob"]}).run(out)
    assert summary.posted == 1 and all("not https://lms.test" in p.why for p in summary.pending)


def test_a_deleted_line_item_is_looked_up_again(tmp_path, write_config):
    out, loaded = a_grading(tmp_path, write_config)
    lms = Lms()
    poster(loaded, lms, []).run(out)
    lms.lineitems.clear()
    lms.scores.clear()
    posted = record.Posted(out)
    posted.scores.clear()  # as if nothing was posted, the line items' URLs still in the record
    posted.save()
    original = lms.send

    def gone(method, url, headers, body=None):
        if url.endswith("/scores") and url[:-len("/scores")] not in lms.lineitems:
            return Response(404, {}, b'{"message": "no such line item"}')
        return original(method, url, headers, body)
    lms.send = gone
    summary = poster(loaded, lms, []).run(out)
    assert summary.posted == 3 and len(lms.posted()) == 3


def test_a_dry_run_prints_the_requests_and_sends_nothing(tmp_path, write_config):
    out, loaded = a_grading(tmp_path, write_config)
    lms, lines = Lms(), []
    summary = poster(loaded, lms, lines, dry_run=True).run(out)
    assert lms.calls == [] and not os.path.exists(os.path.join(out, record.POSTED))
    assert summary.line() == "LMS: 3 scores would be posted (dry run), 0 unchanged, 0 not graded (no score sent), 0 pending"
    assert lines[0].startswith("DRY RUN: POST https://lms.test/token grant_type=client_credentials")
    assert "DRY RUN: GET https://lms.test/ags/lineitems?resource_id=chatter&tag=robotics_labs" in lines
    score_lines = [line for line in lines if "/scores " in line]
    assert len(score_lines) == 3
    assert json.loads(score_lines[0].split("/scores ", 1)[1])["userId"] == "u-alice"


def test_per_assignment_one_score_per_student(tmp_path, write_config):
    out, loaded = a_grading(tmp_path, write_config, grades="per_assignment")
    lms = Lms()
    poster(loaded, lms, []).run(out)
    assert lms.posted() == [("robotics_labs", "u-alice", 10.0), ("robotics_labs", "u-bob", 10.0)]
    assert {i["scoreMaximum"] for i in lms.lineitems.values()} == {30.0}
