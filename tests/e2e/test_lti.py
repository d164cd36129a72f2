"""`make lti-check`: the class's hub logging students in from a real LTI 1.3 platform, and its
grades going back to that platform's gradebook, end to end (root, podman, headless Chromium). An
end-to-end suite (the `e2e` marker: `make test` leaves it out).

    sudo make lti-check                                   # builds the student image (cached), then checks
    sudo make lti-check LTI_CHECK_ARGS="--image localhost/ros-course-lti --no-build"

The LMS is PyPI's lti1p3platform on loopback (course_testkit.lti.LoopbackPlatform: its OIDC login
initiation, its message launch signing the id_token, its token endpoint and AGS), not a fake
written for the test: a course of three students (Learner) and a TA (Instructor), a course link
to the hub and a second one with the custom parameter milestone=chatter. The hub is `make hub`'s
own start (course_testkit.hub.LocalHub: course-hub, deploy/jupyterhub's config) with
HUB_AUTH=lti and the HUB_LTI_* variables naming that platform, at http://hub.localhost:<port>
(a *.localhost name: Chromium keeps the launch's SameSite=None; Secure cookies on it over http).
Each person is a fresh headless Chromium:

- alice and carol open the course page on the platform and click the course link: the platform
  sends the browser to the hub's /hub/lti13/oauth_login, the hub to the platform's authorization
  endpoint, whose page posts the signed id_token to /hub/lti13/oauth_callback; each lands in their
  JupyterLab at /user/<name>/lab on their own origin;
- bob clicks the milestone's link and lands on /user/bob/lab/tree/milestones/chatter.md, the
  milestone's page open;
- the hub recorded each one's LMS identity and the course's AGS line items (lti-users.json);
- tom (Instructor) launches, is the hub's admin: the admin page lists the class, and he opens
  alice's server;
- alice writes a passing chatter package in her workbench, bob one whose scripts are not
  executable, carol a sparse file no snapshot takes (she is not graded);
- `hub_grade --lti` grades the class and posts to the platform: its gradebook holds alice's and
  bob's scores and comments (bob's the failure's reason), nothing for carol or tom;
- a second `hub_grade --lti` changes no score and adds no line item; posting the first grading
  again sends nothing.

One line per check, the last `lti check K/N`; the test passes when all passed. Everything it
started (the hub, the servers' containers, the browsers, the platform) is stopped at the end.
LTI_CHECK_ARGS holds the options, as HUB_CHECK_ARGS does for make hub-check
(course_testkit.hub_suite.options).
"""
from __future__ import annotations

import argparse
import json
import re
import subprocess
from pathlib import Path
from typing import Any, Dict, Tuple

import pytest
import yaml

from course_checks.waiting import wait_for
from course_hub.runner import PODMAN  # the hub's own podman: its networks
from course_testkit.browser import chromium
from course_testkit.hub import HubUser, LocalHub
from course_testkit.hub_suite import LTI_CHECK, Report, browser_user, build_image, run_as_test, upload
from course_testkit.lti import INSTRUCTOR, LEARNER, LoopbackPlatform
from course_testkit.podman import CHECKOUT

pytestmark = pytest.mark.e2e

STUDENTS = ("alice", "bob", "carol")
TA = "tom"
MILESTONE = "chatter"
WORKBENCH_LINK = "workbench"
SAMPLES = CHECKOUT / "courses" / "robotics_labs" / "samples"
FILES = {"alice": SAMPLES / "lab2_chatter_scripts" / "lab2" / "src" / "chatter",
         "bob": SAMPLES / "lab2_chatter_no_chmod" / "chatter"}
LANDING_TIMEOUT_S = 300.0  # a first spawn, as make hub-check allows
LAB_SHELL = "return !!document.querySelector('#jp-main-dock-panel')"  # JupyterLab's page, rendered
LAB_TEXT = "return document.body ? document.body.innerText : ''"
REFUSALS = ("LTI launch refused", "Launch refused")  # the hub's error page, the platform's


def hub_environment(platform: LoopbackPlatform) -> Dict[str, str]:
    """make hub's variables for the login from this platform (docs/hub.md, "Logging in from the LMS")."""
    return {"HUB_AUTH": "lti", "HUB_LTI_ISSUER": platform.issuer, "HUB_LTI_CLIENT_ID": platform.client_id,
            "HUB_LTI_DEPLOYMENT_ID": platform.deployment_id, "HUB_LTI_AUTHORIZE_URL": platform.authorize_url,
            "HUB_LTI_JWKS_URL": platform.jwks_url}


def lti_yaml(work: Path, platform: LoopbackPlatform) -> Path:
    """The tool's registration for grades back (docs/grading.md): the token URL, the tool's key and
    kid, no line items URL (each student's launch recorded the course's)."""
    (work / "lti-tool-key.pem").write_bytes(platform.tool_private_key)
    path = work / "lti.yaml"
    path.write_text(yaml.safe_dump({"issuer": platform.issuer, "client_id": platform.client_id,
                                    "deployment_id": platform.deployment_id, "token_url": platform.token_url,
                                    "private_key": "lti-tool-key.pem", "kid": platform.kid}))
    return path


def click_course_link(driver: Any, platform: LoopbackPlatform, sub: str, link: str) -> None:
    """`sub` opens the course on the platform and clicks the link, as a student does."""
    driver.get(platform.course_url(sub))
    driver.find_element("id", "link-" + link).click()


def lands_in_lab(driver: Any, name: str, path: str = "/lab") -> str:
    """Waits until the browser shows `name`'s JupyterLab at /user/<name><path>, rendered; its URL.
    On a refusal or a timeout, the page's text says where it stopped."""
    wanted = "/user/%s%s" % (name, path)

    def there() -> bool:
        return driver.current_url.split("?")[0].endswith(wanted) and bool(driver.execute_script(LAB_SHELL))

    def refused() -> bool:  # the hub's or the platform's refusal: nothing more will come
        return any(word in str(driver.execute_script(LAB_TEXT)) for word in REFUSALS)
    if not wait_for(lambda: there() or refused(), LANDING_TIMEOUT_S, 0.5) or not there():
        raise AssertionError("%s is at %s: %s" % (name, driver.current_url,
                                                   " ".join(str(driver.execute_script(LAB_TEXT)).split())[:400]))
    return driver.current_url


def run_grading(hub: LocalHub, config: Path, stamp: str) -> Tuple[int, str]:
    """`rosrun course_hub hub_grade --lti CONFIG` on the chatter milestone: (exit code, output)."""
    done = subprocess.run(["rosrun", "course_hub", "hub_grade", "--data", str(hub.data), "--class-list",
                           str(hub.class_list), "--only", MILESTONE, "--stamp", stamp, "--lti", str(config)],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False)
    return done.returncode, done.stdout


def lms_line(output: str) -> str:
    """The summary line of what went to the LMS."""
    found = re.findall(r"LMS: \d+ scores posted.*", output)
    assert found, output[-2500:]
    return found[-1]


def run(opts: argparse.Namespace, report: Report, work: Path) -> None:
    """Every check in turn, each a line of `report`; the first whose failure leaves nothing to check ends it."""
    if not opts.no_build:
        report.attempt("image %s built from docker/Dockerfile" % opts.image,
                       lambda: (build_image(opts.image, work / "build.log"), "log in %s" % (work / "build.log"))[1])
    with LoopbackPlatform() as platform:
        for name in STUDENTS:
            platform.enrol(name, [LEARNER], name.capitalize())
        platform.enrol(TA, [INSTRUCTOR], TA.capitalize())
        platform.add_link(WORKBENCH_LINK, "ROS workbench")
        platform.add_link(MILESTONE, "Milestone: chatter", {"milestone": MILESTONE})
        extra = Path(opts.extra_config).read_text() if opts.extra_config else ""
        hub = LocalHub(opts.image, work, STUDENTS, (TA,), extra, env=hub_environment(platform))
        platform.register_tool(hub.url + "/hub/lti13/oauth_login", hub.url + "/hub/",
                               [hub.url + "/hub/lti13/oauth_callback"])
        try:
            checks(opts, report, work, platform, hub)
        finally:
            hub.stop()


def checks(opts: argparse.Namespace, report: Report, work: Path, platform: LoopbackPlatform, hub: LocalHub) -> None:
    """The checks, against a platform and a hub not started yet."""
    def started() -> str:
        said = hub.start()
        return "%s; the LMS %s at %s (lti1p3platform)" % (said, platform.issuer, platform.base)
    if not report.attempt("the LMS on loopback; make hub's runner starts JupyterHub with HUB_AUTH=lti", started):
        print(hub.tail())
        return

    users: Dict[str, HubUser] = {}

    def students_land() -> str:
        said = []
        for name in ("alice", "carol"):
            with chromium() as driver:
                click_course_link(driver, platform, name, WORKBENCH_LINK)
                url = lands_in_lab(driver, name)
                assert url.startswith("http://%s.hub.localhost:" % name), url
                users[name] = browser_user(driver, hub.url, name)
            said.append(url)
        return "a click on the course link in the LMS: %s" % ", ".join(said)
    if not report.attempt("alice and carol click the course link in the LMS and land in their JupyterLab",
                          students_land):
        print(hub.tail())
        return

    def milestone() -> str:
        path = "/lab/tree/milestones/%s.md" % MILESTONE
        with chromium() as driver:
            click_course_link(driver, platform, "bob", MILESTONE)
            url = lands_in_lab(driver, "bob", path)
            users["bob"] = browser_user(driver, hub.url, "bob")
            assert wait_for(lambda: "example publisher/subscriber pair" in driver.execute_script(LAB_TEXT), 60, 0.5), \
                " ".join(str(driver.execute_script(LAB_TEXT)).split())[:400]
        return "bob's link with milestone=%s: %s, the milestone's page open" % (MILESTONE, url)
    report.attempt("the milestone's course link opens the workbench on the milestone's page", milestone)

    def identities() -> str:
        record = json.loads((hub.data / "lti-users.json").read_text())
        for name in STUDENTS:
            assert record.get(name, {}).get("sub") == name and record[name].get("iss") == platform.issuer, record
            assert record[name].get("lineitems_url") == platform.lineitems_url, record[name]
        claims = {claim["sub"]: claim for claim in platform.launches}
        assert claims["bob"]["https://purl.imsglobal.org/spec/lti/claim/custom"] == {"milestone": MILESTONE}
        return "lti-users.json: %s, each with iss %s and the course's line items %s" % (
            sorted(record), platform.issuer, platform.lineitems_url)
    report.attempt("the hub recorded each launch's LMS identity and AGS line items", identities)

    def ta() -> str:
        with chromium() as driver:
            click_course_link(driver, platform, TA, WORKBENCH_LINK)
            own = lands_in_lab(driver, TA)
            driver.get(hub.url + "/hub/admin")
            assert wait_for(lambda: all(name in driver.execute_script(LAB_TEXT) for name in STUDENTS), 60, 0.5), \
                "the admin page: %s" % " ".join(str(driver.execute_script(LAB_TEXT)).split())[:400]
            driver.get(hub.url + "/user/alice/lab")
            if wait_for(lambda: "/oauth2/authorize" in driver.current_url or "/user/alice/lab" in driver.current_url,
                        60, 0.2) and "/oauth2/authorize" in driver.current_url:
                driver.find_element("css selector", "form input[type=submit], form button").click()
            alice = lands_in_lab(driver, "alice")
        return "tom (Instructor) landed in %s, the admin page lists %s, and he opened %s" % (
            own, ", ".join(STUDENTS), alice)
    report.attempt("the TA's launch makes him the hub's admin: the class on the admin page, a student's server", ta)

    def files() -> str:
        counts = {name: upload(users[name], folder, "catkin_ws/src/chatter") for name, folder in FILES.items()}
        with users["alice"].terminal() as term:
            code, said = term.run("chmod +x ~/catkin_ws/src/chatter/scripts/*.py")
        assert code == 0, said
        with users["carol"].terminal() as term:  # more than a snapshot takes: carol is not graded
            code, said = term.run("truncate -s 16G ~/catkin_ws/src/big.bin && du -h --apparent-size "
                                  "~/catkin_ws/src/big.bin")
        assert code == 0, said
        return "uploaded %s in their workbenches; alice did chmod +x; carol made a sparse file of %s" % (
            counts, said.split()[0])
    if not report.attempt("alice and bob write their chatter package in the workbench, carol a sparse file", files):
        return

    config = lti_yaml(work, platform)
    first: Dict[str, Dict[str, Any]] = {}

    def graded() -> str:
        code, output = run_grading(hub, config, "deadline")
        line = lms_line(output)
        assert line.startswith("LMS: 2 scores posted, 0 unchanged, 1 not graded"), line
        book = platform.scores_by_resource()
        assert sorted(book) == [MILESTONE], book
        scores = book[MILESTONE]
        assert sorted(scores) == ["alice", "bob"], "scores for %s" % sorted(scores)  # none for carol or tom
        alice, bob = scores["alice"], scores["bob"]
        assert alice["scoreGiven"] == alice["scoreMaximum"] > 0 and alice["comment"] == "passed", alice
        assert bob["scoreGiven"] == 0 and bob["comment"].startswith("failed: ") and "not executable" in bob["comment"], \
            bob
        assert all(s["gradingProgress"] == "FullyGraded" and s["activityProgress"] == "Completed"
                   for s in scores.values()), scores
        first.update(json.loads(json.dumps(scores)))
        return "exit %d (carol not graded); %s; the gradebook: alice %s/%s %r, bob %s/%s %r" % (
            code, line, alice["scoreGiven"], alice["scoreMaximum"], alice["comment"], bob["scoreGiven"],
            bob["scoreMaximum"], bob["comment"][:90])
    if not report.attempt("hub_grade --lti: the LMS gradebook holds each graded student's score and comment, "
                          "none for the student not graded", graded):
        return

    def again() -> str:
        items = dict(platform.book.lineitems)
        code, output = run_grading(hub, config, "deadline-again")
        second = lms_line(output)
        scores = platform.scores_by_resource()[MILESTONE]
        same = {user: {k: v for k, v in s.items() if k != "timestamp"} for user, s in scores.items()}
        before = {user: {k: v for k, v in s.items() if k != "timestamp"} for user, s in first.items()}
        assert same == before and platform.book.lineitems == items, (same, before)
        posts = platform.book.score_posts
        done = subprocess.run(["rosrun", "course_grader", "grade", "--lti", str(config), "--lti-users",
                               str(hub.data / "lti-users.json"), "--post-only", "--out",
                               str(hub.data / "grades" / "deadline")],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False)
        repost = lms_line(done.stdout)
        assert repost.startswith("LMS: 0 scores posted, 2 unchanged"), repost
        assert platform.book.score_posts == posts, "the re-post sent %d score(s)" % (platform.book.score_posts - posts)
        return ("a second grading (exit %d): %s, the same scores and comments (later timestamps), no new line item; "
                "the first grading posted again: %s, nothing sent" % (code, second, repost))
    report.attempt("again: a second hub_grade changes no score; a grading posted again sends nothing", again)


def test_the_lms_launch_and_grades_end_to_end():
    run_as_test(LTI_CHECK, run, PODMAN)
