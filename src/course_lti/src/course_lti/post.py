"""One posting run: a grading folder's scores into the LMS gradebook (AGS), or, dry, printed.

    poster = Poster(config, users, course_name, milestones)     # ConfigError before any grading
    summary = poster.run(out)                                    # after it
    print(summary.line())    # LMS: 28 scores posted, 0 unchanged, 2 not graded (no score sent), 0 pending

For each score of the grading (course_lti.scores): the student's LMS user id (course_lti.users;
none yet: pending), the line items container (the config's, else the one the student's launch
recorded), the line item (the record's, else found or created), then the score, unless the
record says this very score was posted before (a re-run sends only what is missing or changed).
The LMS down or busy past the retries (transport.Retrying): that score and every one after it
are pending, the run does not wait out the retries again for each. A refusal (a 4xx) is pending
with the LMS's message; a line item the LMS no longer has (404) is looked up again once.
Pending scores go to `lti-pending.json` (course_lti.record); the same command run again posts
them. A dry run prints every request it would send (method, URL, body) and sends nothing, not
even the token request.
"""
from __future__ import annotations

import datetime
import json
import os
import time
from typing import Callable, Dict, List, Mapping, NamedTuple, Optional, Sequence, Set, Tuple

from course_format.course_file import Course

from course_lti import config as lti_config
from course_lti import record, scores, users
from course_lti.ags import AgsClient, scores_url, with_query
from course_lti.token import AGS_SCOPES, TokenSource
from course_lti.transport import Http, Refused, Retrying, Sender, Unavailable

EXIT_PENDING = 3  # the commands' exit code when some score could not be posted


class Summary(NamedTuple):
    """What a run did."""

    posted: int
    unchanged: int
    not_graded: Dict[str, str]  # student -> why no score was sent
    withheld: List[scores.Withheld]
    pending: List[record.Pending]
    pending_file: str
    dry_run: bool = False

    def line(self) -> str:
        """The commands' summary line."""
        verb = "would be posted (dry run)" if self.dry_run else "posted"
        text = "LMS: %d scores %s, %d unchanged, %d not graded (no score sent), %d pending" % (
            self.posted, verb, self.unchanged, len(self.not_graded), len(self.pending))
        if self.withheld:
            text += ", %d held back (not graded by the grader: regrade them)" % len(self.withheld)
        if self.pending and not self.dry_run:
            text += ": see %s" % self.pending_file
        return text

    def exit_code(self) -> int:
        return EXIT_PENDING if self.pending and not self.dry_run else 0


def now_iso(clock: Callable[[], float]) -> str:
    return datetime.datetime.fromtimestamp(clock(), datetime.timezone.utc).isoformat(timespec="seconds")


class _Stop(Exception):
    """The LMS cannot be reached or refuses the tool itself: the rest of the run is pending."""


class Poster:
    """Posts gradings of one course with one configuration."""

    def __init__(self, config: lti_config.LtiConfig, known: Mapping[str, users.LmsUser], course_name: str,
                 milestones: Sequence[scores.MilestoneInfo], say: Callable[[str], None] = print,
                 send: Optional[Sender] = None, sleep: Callable[[float], None] = time.sleep,
                 clock: Callable[[], float] = time.time, dry_run: bool = False) -> None:
        """ConfigError when the configuration's assignments do not fit the course."""
        self.config = config
        self.users = dict(known)
        self.milestones = list(milestones)
        self.groups = lti_config.line_item_groups(config, course_name, [m.name for m in self.milestones])
        self.tag = config.tag or course_name
        self.say = say
        self.dry_run = dry_run
        self._clock = clock
        retrying = Retrying(send or Http().send, config.retries, config.retry_seconds, sleep, time.monotonic, say)
        self.retrying = retrying
        self.tokens = TokenSource(config, retrying.send, clock)
        self.client = AgsClient(retrying.send, self.tokens)
        self._shown: Set[object] = set()  # dry run: the line item look-ups already printed

    def identity(self, student: str) -> Tuple[Optional[users.LmsUser], str, str]:
        """(the student's LMS identity, its line items container, why not postable ("" when it is))."""
        user = self.users.get(student)
        if user is None:
            return None, "", "no LMS user id for %s: not in the users file (have they opened the course from the LMS?)" \
                % student
        if user.iss and user.iss != self.config.issuer:
            return None, "", "%s's LMS identity is from %s, not %s" % (student, user.iss, self.config.issuer)
        if self.config.deployment_id and user.deployment_id and user.deployment_id != self.config.deployment_id:
            return None, "", "%s's LMS identity is from deployment %s, not %s" % (
                student, user.deployment_id, self.config.deployment_id)
        container = self.config.lineitems_url or user.lineitems_url
        if not container:
            return None, "", "no line items URL: give lineitems_url in %s" % self.config.file
        return user, container, ""

    def run(self, out: str, students: Optional[Sequence[str]] = None) -> Summary:
        """Post the grading in `out` (for `students`, default everyone in it)."""
        grading = scores.from_grading(out, self.groups, self.milestones, self.tag,
                                      self.config.grades == lti_config.PER_MILESTONE, students)
        posted = record.Posted(out)
        earlier = record.load_pending(out)
        if earlier and not self.dry_run:
            self.say("LMS: %d score(s) pending from an earlier run: trying them again" % len(earlier))
        pending: List[record.Pending] = []
        sent = unchanged = 0
        stopped = ""
        for score in grading.scores:
            user, container, why = self.identity(score.student)
            payload = score.payload(user.sub if user else "")
            if user is None:
                pending.append(record.Pending(score.student, "", "", score.item.payload(), payload, why))
                continue
            if posted.already(container, score.item.resource_id, user.sub, payload):
                unchanged += 1
                continue
            if stopped:
                pending.append(record.Pending(score.student, user.sub, container, score.item.payload(), payload,
                                              "not tried: %s" % stopped))
                continue
            if self.dry_run:
                self._show(posted, container, score, payload)
                sent += 1
                continue
            try:
                self._post(posted, container, score, payload)
            except (Refused, Unavailable) as err:
                pending.append(record.Pending(score.student, user.sub, container, score.item.payload(), payload,
                                              str(err)))
                self.say("LMS: not posted: %s on %s: %s" % (score.student, score.item.resource_id, err))
                if isinstance(err, Unavailable):
                    stopped = str(err)
                continue
            except _Stop as err:
                stopped = str(err)
                pending.append(record.Pending(score.student, user.sub, container, score.item.payload(), payload,
                                              stopped))
                continue
            posted.remember(container, score.item.resource_id, user.sub, score.student, payload, now_iso(self._clock))
            posted.save()
            sent += 1
        path = os.path.join(out, record.PENDING)
        if not self.dry_run:
            record.save_pending(out, pending, now_iso(self._clock))
        for held in grading.withheld:
            self.say("LMS: no score for %s on %s: %s" % (held.student, held.resource_id, held.why))
        return Summary(sent, unchanged, grading.not_graded, grading.withheld, pending, path, self.dry_run)

    def _post(self, posted: record.Posted, container: str, score: scores.StudentScore,
              payload: Dict[str, object]) -> None:
        """One score: its line item (recorded, found or created), then the score itself."""
        item = score.item
        try:
            self.tokens.get()
        except (Refused, Unavailable) as err:
            raise _Stop("no access token: %s" % err) from err
        url = posted.lineitem(container, item.resource_id, item.tag)
        if url is None:
            url = self.client.lineitem(container, item)
            posted.remember_lineitem(container, item.resource_id, item.tag, url)
        try:
            self.client.post_score(url, payload)
        except Refused as err:
            if err.status != 404:
                raise
            posted.forget_lineitem(container, item.resource_id, item.tag)  # deleted in the LMS: again, once
            url = self.client.lineitem(container, item)
            posted.remember_lineitem(container, item.resource_id, item.tag, url)
            self.client.post_score(url, payload)

    def _show(self, posted: record.Posted, container: str, score: scores.StudentScore,
              payload: Dict[str, object]) -> None:
        """A dry run's lines for one score: the requests it would send."""
        item = score.item
        if not self._shown:
            self.say("DRY RUN: POST %s grant_type=client_credentials, client_assertion signed by kid %s, scope=%s"
                     % (self.config.token_url, self.config.kid, " ".join(AGS_SCOPES)))
            self._shown.add("token")
        url = posted.lineitem(container, item.resource_id, item.tag)
        if url is None:
            url = "<line item %s>" % item.resource_id
            if (container, item.resource_id) not in self._shown:
                self._shown.add((container, item.resource_id))
                self.say("DRY RUN: GET %s" % with_query(container, {"resource_id": item.resource_id, "tag": item.tag}))
                self.say("DRY RUN: POST %s %s   (if not found)" % (container, json.dumps(item.payload())))
        self.say("DRY RUN: POST %s %s" % (scores_url(url) if not url.startswith("<") else url + "/scores",
                                         json.dumps(payload)))


def milestones_of(course: Course) -> List[scores.MilestoneInfo]:
    """What the scores need of a course's milestones."""
    return [scores.MilestoneInfo(m.name, m.title, m.points) for m in course.milestones]


def prepare(config_path: str, users_path: str, course: Course, dry_run: bool = False,
            missing_users_ok: bool = False, say: Callable[[str], None] = print) -> Poster:
    """The Poster the commands' --lti CONFIG and users file give, checked before any grading:
    ConfigError with every problem of either file."""
    config = lti_config.load(config_path)
    known = users.load(users_path, missing_ok=missing_users_ok)
    if not known:
        say("LMS: nobody in %s yet: every score will be pending" % users_path)
    return Poster(config, known, course.name, milestones_of(course), say=say, dry_run=dry_run)
