"""Grades back to the LMS against a real LTI 1.3 platform: PyPI's lti1p3platform on loopback
(course_testkit.lti.LoopbackPlatform). The token comes from the library's client-credentials
endpoint, which checks the client assertion's signature against the tool's JWKS it fetches over
HTTP; every AGS request passes the library's bearer-token check (the platform's signature, issuer,
expiry, scopes) and its line item and score handlers. What is asserted is what the platform
stored: the line items, each student's score, maximum, comment and timestamp.

The launch side, as a tool sees it (the hub's end of it in a browser is `make lti-check`,
tests/e2e/test_lti.py): a click on a course link starts the third-party login at the tool's URL
with the library's parameters; the authentication request the tool sends back is answered with a
form posting an id_token, signed with the key of the platform's JWKS, holding the user's roles,
the link's custom parameters, the AGS endpoint and the tool's nonce; a request for another
user, to a redirect_uri the tool did not register, or without the tool's client id, is refused."""
from __future__ import annotations

import argparse
import csv
import html
import http.cookiejar
import json
import os
import re
import urllib.error
import urllib.parse
import urllib.request
from typing import Dict, Tuple

import jwt

import pytest
import yaml

from course_grader import cli
from course_hub import grade_cli
from course_lti import config, record
from course_lti.post import Poster
from course_lti.scores import MilestoneInfo
from course_lti.users import LmsUser
from course_testkit.lti import INSTRUCTOR, LEARNER, LoopbackPlatform, rsa_key_pair, write_results

COURSE = [MilestoneInfo("chatter", "Example publisher and subscriber", 10.0),
          MilestoneInfo("checkpoint1", "TimestampString publisher and subscriber", 10.0)]
REASON = "publishes nothing on /chatter_talk: the talker exited (NameError: name 'rate' is not defined)"


@pytest.fixture
def platform():
    with LoopbackPlatform() as running:
        yield running


def lti_yaml(tmp_path, platform: LoopbackPlatform, key: bytes = b"", **fields) -> str:
    (tmp_path / "tool.pem").write_bytes(key or platform.tool_private_key)
    data = {"issuer": platform.issuer, "client_id": platform.client_id, "token_url": platform.token_url,
            "lineitems_url": platform.lineitems_url, "private_key": "tool.pem", "kid": platform.kid, "retries": 2}
    data.update(fields)
    path = str(tmp_path / "lti.yaml")
    with open(path, "w") as stream:
        yaml.safe_dump(data, stream)
    return path


def class_graded(tmp_path) -> str:
    out = str(tmp_path / "grades")
    write_results(out, "alice", [("chatter", 10, 10, "passed\n\n--- listener.log ---\nheard", ""),
                                 ("checkpoint1", 0, 10, "FAILED: %s\n\n--- talker.log ---\nTraceback" % REASON,
                                  "exited_early")])
    write_results(out, "bob", [("chatter", 0, 10, "FAILED: " + REASON, "exited_early")])
    return out


USERS = {"alice": LmsUser("lms-user-1", "https://lms.test"), "bob": LmsUser("lms-user-2", "https://lms.test")}


def test_scores_reach_the_platforms_gradebook_once(tmp_path, platform):
    out = class_graded(tmp_path)
    lines = []
    poster = Poster(config.load(lti_yaml(tmp_path, platform)), USERS, "robotics_labs", COURSE, say=lines.append)
    summary = poster.run(out)
    assert summary.line() == "LMS: 3 scores posted, 0 unchanged, 0 not graded (no score sent), 0 pending", lines
    assert platform.token_errors == [] and ("GET", "/tool/jwks") in platform.requests  # it checked our signature
    stored = platform.scores_by_resource()
    assert sorted(stored) == ["chatter", "checkpoint1"]
    assert {i["tag"] for i in platform.book.lineitems.values()} == {"robotics_labs"}
    chatter = stored["chatter"]
    assert (chatter["lms-user-1"]["scoreGiven"], chatter["lms-user-1"]["comment"]) == (10.0, "passed")
    assert (chatter["lms-user-2"]["scoreGiven"], chatter["lms-user-2"]["scoreMaximum"]) == (0.0, 10.0)
    assert chatter["lms-user-2"]["comment"] == "failed: " + REASON  # the reason, without the logs
    assert stored["checkpoint1"]["lms-user-1"]["gradingProgress"] == "FullyGraded"
    assert stored["checkpoint1"]["lms-user-1"]["activityProgress"] == "Completed"
    posts = platform.book.score_posts
    again = Poster(config.load(lti_yaml(tmp_path, platform)), USERS, "robotics_labs", COURSE).run(out)
    assert (again.posted, again.unchanged) == (0, 3) and platform.book.score_posts == posts
    os.remove(os.path.join(out, record.POSTED))  # the record lost: everything is sent again, the same
    third = Poster(config.load(lti_yaml(tmp_path, platform)), USERS, "robotics_labs", COURSE).run(out)
    assert third.posted == 3 and platform.scores_by_resource() == stored and len(platform.book.lineitems) == 2


def test_a_tool_signing_with_another_key_gets_no_token_and_nothing_is_lost(tmp_path, platform):
    out = class_graded(tmp_path)
    stranger = lti_yaml(tmp_path, platform, key=rsa_key_pair()[0])
    summary = Poster(config.load(stranger), USERS, "robotics_labs", COURSE).run(out)
    assert platform.token_errors and "Signature verification failed" in platform.token_errors[0]
    assert len(summary.pending) == 3 and "invalid_client" in summary.pending[0].why
    assert platform.book.score_posts == 0
    assert len(record.load_pending(out)) == 3
    fixed = Poster(config.load(lti_yaml(tmp_path, platform)), USERS, "robotics_labs", COURSE).run(out)
    assert fixed.posted == 3 and not os.path.exists(os.path.join(out, record.PENDING))


def test_a_platform_down_for_a_moment_is_tried_again(tmp_path, platform):
    out = class_graded(tmp_path)
    waits = []
    platform.outage(2)
    summary = Poster(config.load(lti_yaml(tmp_path, platform)), USERS, "robotics_labs", COURSE,
                     sleep=waits.append).run(out)
    assert waits == [1.0, 2.0] and summary.posted == 3 and not summary.pending


def test_grade_post_only_and_dry_run(tmp_path, platform, capsys):
    out = class_graded(tmp_path)
    table = tmp_path / "users.csv"
    table.write_text("student,user_id\nalice,lms-user-1\nbob,lms-user-2\n")
    command = ["--lti", lti_yaml(tmp_path, platform), "--lti-users", str(table), "--post-only", "--out", out]
    assert cli.main(command + ["--dry-run"]) == 0
    printed = capsys.readouterr().out
    assert "LMS: 3 scores would be posted (dry run)" in printed and printed.count("/scores {") == 3
    assert platform.requests == []  # a dry run sends nothing, not even for a token
    assert cli.main(command) == 0
    assert "LMS: 3 scores posted, 0 unchanged, 0 not graded (no score sent), 0 pending" in capsys.readouterr().out
    assert platform.scores_by_resource()["chatter"]["lms-user-2"]["comment"] == "failed: " + REASON


def test_grade_refuses_a_bad_configuration_before_grading(tmp_path, platform, capsys):
    bad = lti_yaml(tmp_path, platform, token_url="http://lms.example.edu/token")
    assert cli.main(["--lti", bad, "--lti-users", "x.csv", "--class", str(tmp_path), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "%s: token_url: 'http://lms.example.edu/token': plain http" % bad in err
    assert cli.main(["--post-only", "--out", str(tmp_path)]) == 2


def test_the_hub_posts_everyone_graded_and_nothing_for_who_was_not(tmp_path, platform):
    data = tmp_path / "data"
    out = str(data / "grades" / "20261126T160000Z")
    write_results(out, "alice", [("chatter", 10, 10, "passed", "")])
    with open(os.path.join(out, "not-graded.csv"), "w", newline="") as stream:
        csv.writer(stream).writerows([["student", "reason"], ["bob", "your catkin_ws/src changed while it was copied"]])
    (data / "lti-users.json").write_text('{"alice": {"iss": "https://lms.test", "sub": "lms-user-1"}, '
                                         '"bob": {"iss": "https://lms.test", "sub": "lms-user-2"}}')
    args = argparse.Namespace(data=str(data), lti=lti_yaml(tmp_path, platform), lti_users="", dry_run=False)
    summary = grade_cli.lms_poster(args).run(out)
    assert summary.line() == "LMS: 1 scores posted, 0 unchanged, 1 not graded (no score sent), 0 pending"
    assert platform.scores_by_resource() == {"chatter": {"lms-user-1": platform.scores_by_resource()["chatter"]
                                                         ["lms-user-1"]}}  # bob: no score, not a 0


TOOL = "http://hub.localhost:8000"


class NoRedirects(urllib.request.HTTPRedirectHandler):
    """A browser whose redirects the test follows itself (they go to the tool, which is not there)."""

    def redirect_request(self, *args: object) -> None:
        return None


def browser() -> urllib.request.OpenerDirector:
    return urllib.request.build_opener(urllib.request.HTTPCookieProcessor(http.cookiejar.CookieJar()), NoRedirects)


def get(opener: urllib.request.OpenerDirector, url: str) -> Tuple[int, Dict[str, str], str]:
    try:
        with opener.open(url, timeout=10) as reply:
            return reply.status, dict(reply.headers), reply.read().decode()
    except urllib.error.HTTPError as err:
        return err.code, dict(err.headers), err.read().decode()


def click(opener: urllib.request.OpenerDirector, platform: LoopbackPlatform, sub: str, link: str) -> Dict[str, str]:
    """`sub` opens the course page and clicks `link`: the parameters of the tool's login URL."""
    status, _, page = get(opener, platform.course_url(sub))
    assert status == 200 and 'id="link-%s"' % link in page, page
    href = re.search(r'id="link-%s" href="([^"]+)"' % link, page).group(1)
    status, headers, _ = get(opener, platform.base + href)
    assert status == 302 and headers["Location"].startswith(TOOL + "/hub/lti13/oauth_login?"), headers
    return dict(urllib.parse.parse_qsl(urllib.parse.urlsplit(headers["Location"]).query))


def authentication_request(start: Dict[str, str], **changes: str) -> Dict[str, str]:
    """What the tool sends the browser to the authorization endpoint with (ltiauthenticator's)."""
    request = {"response_type": "id_token", "scope": "openid", "response_mode": "form_post", "prompt": "none",
               "client_id": start["client_id"], "redirect_uri": TOOL + "/hub/lti13/oauth_callback",
               "login_hint": start["login_hint"], "lti_message_hint": start["lti_message_hint"],
               "nonce": "nonce-1", "state": "state-1"}
    request.update(changes)
    return request


@pytest.fixture
def course(platform):
    platform.register_tool(TOOL + "/hub/lti13/oauth_login", TOOL + "/hub/", [TOOL + "/hub/lti13/oauth_callback"])
    platform.enrol("lms-user-1", [LEARNER], "Alice")
    platform.enrol("lms-user-9", [INSTRUCTOR], "Tom")
    platform.add_link("workbench", "ROS workbench")
    platform.add_link("chatter", "Milestone: chatter", {"milestone": "chatter"})
    return platform


def test_a_launch_is_the_librarys_login_initiation_then_a_signed_id_token_posted_to_the_tool(course):
    alice = browser()
    start = click(alice, course, "lms-user-1", "chatter")
    assert start == {"iss": course.issuer, "login_hint": "lms-user-1", "target_link_uri": TOOL + "/hub/",
                     "lti_message_hint": "chatter", "client_id": course.client_id,
                     "lti_deployment_id": course.deployment_id}
    query = urllib.parse.urlencode(authentication_request(start))
    status, _, page = get(alice, course.authorize_url + "?" + query)
    assert status == 200 and 'action="%s/hub/lti13/oauth_callback"' % TOOL in page and ".submit()" in page, page
    fields = dict(re.findall(r'name="([^"]+)" value="([^"]*)"', page))
    assert fields["state"] == "state-1"
    keys = jwt.PyJWKClient(course.jwks_url)
    token = html.unescape(fields["id_token"])
    claims = jwt.decode(token, keys.get_signing_key_from_jwt(token).key, algorithms=["RS256"],
                        audience=course.client_id, issuer=course.issuer)
    assert claims["sub"] == "lms-user-1" and claims["nonce"] == "nonce-1"
    assert claims["https://purl.imsglobal.org/spec/lti/claim/roles"] == [LEARNER]
    assert claims["https://purl.imsglobal.org/spec/lti/claim/custom"] == {"milestone": "chatter"}
    assert claims["https://purl.imsglobal.org/spec/lti/claim/deployment_id"] == course.deployment_id
    assert claims["https://purl.imsglobal.org/spec/lti/claim/message_type"] == "LtiResourceLinkRequest"
    assert claims["https://purl.imsglobal.org/spec/lti/claim/resource_link"]["id"] == "chatter"
    assert claims["https://purl.imsglobal.org/spec/lti-ags/claim/endpoint"]["lineitems"] == course.lineitems_url
    assert course.launches == [claims]


def test_the_platform_refuses_an_authentication_request_that_is_not_its_users_or_the_tools(course):
    tom = browser()
    start = click(tom, course, "lms-user-9", "workbench")
    assert json.loads(get(tom, course.jwks_url)[2])["keys"][0]["kid"]
    refusals = {"login_hint": {"login_hint": "lms-user-1"},  # alice's launch from tom's browser
                "redirect_uri": {"redirect_uri": "https://evil.example/steal"},
                "client_id": {"client_id": "another-tool"},
                "response_mode": {"response_mode": "query"},
                "lti_message_hint": {"lti_message_hint": "no-such-link"}}
    for what, changes in refusals.items():
        query = urllib.parse.urlencode(authentication_request(start, **changes))
        status, _, page = get(tom, course.authorize_url + "?" + query)
        assert status == 400 and 'id=refused' in page and "id_token" not in page, (what, page)
    assert course.launches == []
    nobody = browser()  # no session with the platform: no launch either
    status, _, page = get(nobody, course.base + "/lms/launch?link=workbench")
    assert status == 400, page
