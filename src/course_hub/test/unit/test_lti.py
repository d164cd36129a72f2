"""The login from the LMS (course_hub.lti.CourseLTIAuthenticator) through a real JupyterHub: the
hub's own process from .venv-hub, its database and its LTI 1.3 handlers on a loopback port; this
test is the LMS. It posts the third-party login to /hub/lti13/oauth_login, reads the state and
nonce the hub sends the browser to the platform with (and the cookies it sets), signs an
id_token with its own RSA key, whose JWKS it serves on loopback, and posts it to
/hub/lti13/oauth_callback as a platform does.

A launch that should pass makes a user (a TA an admin) and lands on the workbench (on a
milestone when the link names one); each bad one (forged signature, another aud, an unknown iss
or deployment, expired, a replayed state or nonce, no role, a name another LMS user holds) is
refused with its message, logged, and makes no user. Skipped where .venv-hub is missing, as
test_plugins.py is (COURSE_HUB=1 bash setup/install.sh makes it)."""
from __future__ import annotations

import http.client
import http.server
import json
import os
import sqlite3
import subprocess
import threading
import time
import uuid
from http.cookies import SimpleCookie
from typing import Any, Dict, Iterator, List, Optional, Tuple
from urllib.parse import parse_qs, urlencode, urlsplit

import jwt
import pytest
from cryptography.hazmat.primitives.asymmetric import rsa

from course_checks.waiting import wait_for
from course_hub import lms
from course_net.ports import free_port

UNIT = os.path.dirname(os.path.abspath(__file__))
PACKAGE_SRC = os.path.abspath(os.path.join(UNIT, "..", "..", "src"))
CHECKOUT = os.path.abspath(os.path.join(UNIT, "..", "..", "..", ".."))
HUB_BIN = os.path.join(CHECKOUT, ".venv-hub", "bin")
ISS = "https://lms.example.edu"
CLIENT_ID = "10000000000042"
DEPLOYMENT = "1:course-ros"
KID = "lms-key-1"
LEARNER = lms.LIS + "membership#Learner"
INSTRUCTOR = lms.LIS + "membership#Instructor"
TEACHING_ASSISTANT = lms.LIS + "membership/Instructor#TeachingAssistant"
START_TIMEOUT_S = 60.0

pytestmark = pytest.mark.skipif(not os.access(os.path.join(HUB_BIN, "jupyterhub"), os.X_OK),
                                reason="the hub's venv (.venv-hub) is not there: make hub's set-up makes it "
                                "(COURSE_HUB=1 bash setup/install.sh)")


def rsa_key() -> rsa.RSAPrivateKey:
    return rsa.generate_private_key(public_exponent=65537, key_size=2048)


class Platform:
    """The LMS: its signing key, its JWKS on a loopback port, and the id_tokens it signs."""

    def __init__(self) -> None:
        self.key = rsa_key()
        jwk = json.loads(jwt.algorithms.RSAAlgorithm.to_jwk(self.key.public_key()))
        body = json.dumps({"keys": [dict(jwk, kid=KID, alg="RS256", use="sig")]}).encode()

        class Keys(http.server.BaseHTTPRequestHandler):
            def do_GET(self) -> None:  # noqa: N802 (http.server's name)
                self.send_response(200)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            def log_message(self, *args: Any) -> None:
                pass

        self.server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Keys)
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()
        self.url = "http://127.0.0.1:%d" % self.server.server_address[1]

    def claims(self, nonce: str, sub: str, roles: Optional[List[str]] = None, **changes: Any) -> Dict[str, Any]:
        """A resource link launch's claims as a platform sends them; `changes` replace or (None)
        remove claims."""
        now = int(time.time())
        claims: Dict[str, Any] = {
            "iss": ISS, "aud": CLIENT_ID, "sub": sub, "nonce": nonce, "iat": now, "exp": now + 300,
            "https://purl.imsglobal.org/spec/lti/claim/version": "1.3.0",
            "https://purl.imsglobal.org/spec/lti/claim/message_type": "LtiResourceLinkRequest",
            lms.DEPLOYMENT_CLAIM: DEPLOYMENT,
            "https://purl.imsglobal.org/spec/lti/claim/target_link_uri": "https://hub.example.org/hub/",
            "https://purl.imsglobal.org/spec/lti/claim/resource_link": {"id": "link-1"},
            "https://purl.imsglobal.org/spec/lti/claim/context": {"id": "c1", "label": "ROS", "title": "ROS labs"},
            lms.ROLES_CLAIM: roles if roles is not None else [LEARNER],
            lms.AGS_CLAIM: {"lineitems": "https://lms.example.edu/api/lti/courses/7/line_items"},
        }
        for name, value in changes.items():
            name = {"custom": lms.CUSTOM_CLAIM, "deployment_id": lms.DEPLOYMENT_CLAIM, "roles": lms.ROLES_CLAIM}.get(
                name, name)
            if value is None:
                claims.pop(name, None)
            else:
                claims[name] = value
        return claims

    def sign(self, claims: Dict[str, Any], key: Optional[rsa.RSAPrivateKey] = None) -> str:
        return jwt.encode(claims, key or self.key, algorithm="RS256", headers={"kid": KID})

    def close(self) -> None:
        self.server.shutdown()
        self.server.server_close()


class Hub:
    """JupyterHub with CourseLTIAuthenticator, from .venv-hub, on a loopback port; its log in a
    file, its database a file this test reads."""

    def __init__(self, folder: str, platform: Platform) -> None:
        self.folder = folder
        self.port = free_port()
        self.data = os.path.join(folder, "data")
        self.db = os.path.join(folder, "jupyterhub.sqlite")
        self.log_path = os.path.join(folder, "hub.log")
        config = os.path.join(folder, "jupyterhub_config.py")
        with open(config, "w") as out:
            out.write("\n".join([
                "c = get_config()",
                "c.JupyterHub.authenticator_class = 'course_hub.lti.CourseLTIAuthenticator'",
                "c.JupyterHub.proxy_class = 'lti_hub_proxy.RoutesInMemory'",
                "c.JupyterHub.hub_ip = '127.0.0.1'",
                "c.JupyterHub.hub_port = %d" % self.port,
                "c.JupyterHub.db_url = 'sqlite:///%s'" % self.db,
                "c.JupyterHub.cookie_secret_file = %r" % os.path.join(folder, "cookie_secret"),
                "c.CourseLTIAuthenticator.issuer = %r" % ISS,
                "c.CourseLTIAuthenticator.client_id = {%r}" % CLIENT_ID,
                "c.CourseLTIAuthenticator.deployment_ids = {%r}" % DEPLOYMENT,
                "c.CourseLTIAuthenticator.authorize_url = %r" % (platform.url + "/authorize"),
                "c.CourseLTIAuthenticator.jwks_endpoint = %r" % (platform.url + "/jwks"),
                "c.CourseLTIAuthenticator.data_dir = %r" % self.data,
                ""]))
        clean = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
        self.log_file = open(self.log_path, "w")
        self.proc = subprocess.Popen([os.path.join(HUB_BIN, "jupyterhub"), "-f", config], cwd=folder,
                                     stdin=subprocess.DEVNULL, stdout=self.log_file, stderr=subprocess.STDOUT,
                                     env=dict(clean, PYTHONPATH=os.pathsep.join([PACKAGE_SRC, UNIT]),
                                              PATH=HUB_BIN + os.pathsep + clean.get("PATH", "")))
        if not wait_for(self.healthy, START_TIMEOUT_S, 0.1):
            self.close()
            raise AssertionError("the hub did not answer within %d s: %s" % (START_TIMEOUT_S, self.log()[-3000:]))

    def healthy(self) -> bool:
        if self.proc.poll() is not None:
            raise AssertionError("the hub ended (exit %s): %s" % (self.proc.returncode, self.log()[-3000:]))
        try:
            return self.request("GET", "/hub/health")[0] == 200
        except OSError:
            return False

    def request(self, method: str, path: str, form: Optional[Dict[str, str]] = None,
                cookies: Optional[Dict[str, str]] = None) -> Tuple[int, Dict[str, str], Dict[str, str], str]:
        """(status, headers, cookies set, body) of one request, redirects not followed."""
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=30)
        try:
            headers = {"Content-Type": "application/x-www-form-urlencoded"}
            if cookies:
                headers["Cookie"] = "; ".join("%s=%s" % item for item in cookies.items())
            connection.request(method, path, body=urlencode(form) if form is not None else None, headers=headers)
            response = connection.getresponse()
            body = response.read().decode("utf-8", "replace")
            jar = SimpleCookie()
            for header in response.headers.get_all("Set-Cookie") or []:
                jar.load(header)
            answer = dict(response.headers)
            answer["Set-Cookie"] = "\n".join(response.headers.get_all("Set-Cookie") or [])
            return response.status, answer, {k: m.value for k, m in jar.items()}, body
        finally:
            connection.close()

    def log(self) -> str:
        with open(self.log_path, encoding="utf-8", errors="replace") as stream:
            return stream.read()

    def users(self) -> Dict[str, bool]:
        """The hub's users, each with whether they are admin, from its database."""
        with sqlite3.connect(self.db) as db:
            return {name: bool(admin) for name, admin in db.execute("SELECT name, admin FROM users")}

    def servers(self) -> int:
        with sqlite3.connect(self.db) as db:
            return db.execute("SELECT COUNT(*) FROM servers").fetchone()[0]

    def close(self) -> None:
        self.proc.terminate()
        try:
            self.proc.wait(30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait(10)
        self.log_file.close()


class Launch:
    """One browser's launch: the login start's state, nonce and cookies."""

    def __init__(self, hub: Hub, iss: str = ISS) -> None:
        self.hub = hub
        status, headers, self.cookies, body = hub.request("POST", "/hub/lti13/oauth_login", {
            "iss": iss, "login_hint": "u-1", "target_link_uri": "https://hub.example.org/hub/",
            "client_id": CLIENT_ID, "lti_deployment_id": DEPLOYMENT})
        self.status, self.body, self.set_cookies = status, body, headers.get("Set-Cookie", "").splitlines()
        query = parse_qs(urlsplit(headers.get("Location", "")).query) if status == 302 else {}
        self.state = query.get("state", [""])[0]
        self.nonce = query.get("nonce", [""])[0]
        self.redirect_uri = query.get("redirect_uri", [""])[0]

    def finish(self, id_token: str, cookies: Optional[Dict[str, str]] = None,
               state: Optional[str] = None) -> Tuple[int, str, str]:
        """(status, Location, body) of posting `id_token` back to the hub."""
        status, headers, _, body = self.hub.request(
            "POST", "/hub/lti13/oauth_callback", {"id_token": id_token, "state": state or self.state},
            cookies=self.cookies if cookies is None else cookies)
        return status, headers.get("Location", ""), body


@pytest.fixture(scope="module")
def platform() -> Iterator[Platform]:
    made = Platform()
    yield made
    made.close()


@pytest.fixture(scope="module")
def hub(tmp_path_factory: pytest.TempPathFactory, platform: Platform) -> Iterator[Hub]:
    started = Hub(str(tmp_path_factory.mktemp("lti-hub")), platform)
    yield started
    started.close()


def unique(prefix: str) -> str:
    return "%s-%s" % (prefix, uuid.uuid4().hex[:8])


def assert_refused(hub: Hub, before: Dict[str, bool], answer: Tuple[int, str, str], status: int, why: str) -> None:
    """Refused with `status` and `why` on the page, one log line saying so, and no user made."""
    code, location, body = answer
    assert code == status, (code, location, body[-2000:])
    assert "LTI launch refused: " in body and why in body, body[-3000:]
    assert any("LTI launch refused" in line and why in line for line in hub.log().splitlines()), hub.log()[-3000:]
    assert hub.users() == before and hub.servers() == 0


# --- launches that pass ------------------------------------------------------------------------

def test_a_learners_launch_makes_a_student_and_opens_the_workbench(hub: Hub, platform: Platform):
    launch = Launch(hub)
    assert launch.status == 302 and launch.state and launch.nonce
    assert launch.redirect_uri.endswith("/hub/lti13/oauth_callback")
    # the platform posts the id_token from another site: the cookies must come back with it
    assert len(launch.set_cookies) == 2 and all("SameSite=None" in c and "Secure" in c for c in launch.set_cookies)
    sub = unique("Student")
    code, location, body = launch.finish(platform.sign(platform.claims(launch.nonce, sub)))
    assert code == 302, body[-2000:]
    assert hub.users()[sub.lower()] is False  # not an admin
    assert not location.startswith("/hub/lti13")  # on to the hub, not back to the login
    record = json.load(open(os.path.join(hub.data, lms.USERS_FILE)))[sub.lower()]
    assert record == {"iss": ISS, "sub": sub, "deployment_id": DEPLOYMENT,
                      "lineitems_url": "https://lms.example.edu/api/lti/courses/7/line_items"}
    assert oct(os.stat(os.path.join(hub.data, lms.USERS_FILE)).st_mode & 0o777) == "0o600"


@pytest.mark.parametrize("role", [INSTRUCTOR, TEACHING_ASSISTANT, "Instructor"])
def test_an_instructor_or_teaching_assistant_is_a_ta_an_admin_of_the_hub(hub: Hub, platform: Platform, role: str):
    launch = Launch(hub)
    sub = unique("ta")
    code, _, body = launch.finish(platform.sign(platform.claims(launch.nonce, sub, [role, LEARNER])))
    assert code == 302, body[-2000:]
    assert hub.users()[sub] is True


def test_a_launch_naming_a_milestone_opens_the_workbench_on_it(hub: Hub, platform: Platform):
    launch = Launch(hub)
    sub = unique("m")
    claims = platform.claims(launch.nonce, sub, custom={"milestone": "checkpoint1"})
    code, location, body = launch.finish(platform.sign(claims))
    assert code == 302, body[-2000:]
    assert location == "/hub/spawn?next=/hub/user-redirect/lab/tree/milestones/checkpoint1.md"
    assert sub in hub.users()


def test_one_lms_user_keeps_one_hub_user_launch_after_launch(hub: Hub, platform: Platform):
    sub = unique("again")
    for _ in range(2):
        launch = Launch(hub)
        assert launch.finish(platform.sign(platform.claims(launch.nonce, sub)))[0] == 302
    assert sum(1 for name in hub.users() if name == sub) == 1


# --- bad input: refused, logged, no user -------------------------------------------------------

NOW = int(time.time())
# (what is wrong, the claims changed, status, the refusal's words): each signed and posted as a
# platform would, after a good login start
BAD_TOKENS = [
    ("forged signature", {}, 400, "InvalidSignatureError"),  # same kid, another key (below)
    ("another tool's", {"aud": "another-tool"}, 401, "the id_token is not for this hub"),
    ("unknown issuer", {"iss": "https://evil.example.com"}, 400, "InvalidIssuerError"),
    ("unknown deployment", {"deployment_id": "2:another-course"}, 401, "which is not one of this hub"),
    ("expired", {"iat": NOW - 400, "exp": NOW - 100}, 400, "ExpiredSignatureError"),
    ("no role claim", {lms.ROLES_CLAIM: None}, 400, "roles not in request"),
    ("no role", {"roles": []}, 403, "none of which the hub knows"),
    ("no role the hub knows", {"roles": [lms.LIS + "membership#Mentor", lms.LIS + "institution/person#Instructor"]},
     403, "none of which the hub knows"),
    ("no milestone id", {"custom": {"milestone": "../../etc/passwd"}}, 400, "which is no milestone id"),
]


@pytest.mark.parametrize("changes, status, why", [case[1:] for case in BAD_TOKENS], ids=[c[0] for c in BAD_TOKENS])
def test_a_bad_id_token_is_refused_logged_and_makes_no_user(hub: Hub, platform: Platform, changes, status, why):
    launch, before = Launch(hub), hub.users()
    claims = platform.claims(launch.nonce, unique("bad"), **changes)
    token = platform.sign(claims, key=rsa_key() if why == "InvalidSignatureError" else None)
    assert_refused(hub, before, launch.finish(token), status, why)


def test_an_unknown_issuer_is_refused_at_the_login_start(hub: Hub):
    start = Launch(hub, iss="https://evil.example.com")
    assert (start.status, start.state) == (400, "")
    assert "which is not this class&#39;s LMS" in start.body or "which is not this class's LMS" in start.body
    assert "https://evil.example.com" in hub.log()


def test_a_replayed_launch_is_refused_by_its_state(hub: Hub, platform: Platform):
    launch = Launch(hub)
    sub = unique("replay")
    token = platform.sign(platform.claims(launch.nonce, sub))
    assert launch.finish(token)[0] == 302
    before = hub.users()
    # the same post again, cookies and all (a browser's back button, or someone who captured it)
    assert_refused(hub, before, launch.finish(token), 400, "state was used already")


def test_a_replayed_nonce_is_refused(hub: Hub, platform: Platform):
    first = Launch(hub)
    token = platform.sign(platform.claims(first.nonce, unique("nonce")))
    assert first.finish(token)[0] == 302
    before = hub.users()
    # a fresh state of its own, the first launch's token and nonce cookie
    second = Launch(hub)
    cookies = dict(second.cookies)
    nonce_cookie = [name for name in first.cookies if "nonce" in name]
    assert nonce_cookie, first.cookies
    cookies[nonce_cookie[0]] = first.cookies[nonce_cookie[0]]
    assert_refused(hub, before, second.finish(token, cookies=cookies), 400, "nonce was used already")


def test_a_launch_without_its_cookies_is_refused(hub: Hub, platform: Platform):
    launch, before = Launch(hub), hub.users()
    token = platform.sign(platform.claims(launch.nonce, unique("nocookie")))
    assert_refused(hub, before, launch.finish(token, cookies={}), 400, "OAuth state missing from cookies")


def test_a_second_lms_user_whose_name_collides_is_refused_never_merged(hub: Hub, platform: Platform):
    word = unique("jean")
    first = Launch(hub)
    assert first.finish(platform.sign(platform.claims(first.nonce, word + "_luc")))[0] == 302
    before = hub.users()
    second = Launch(hub)
    # another person: jean-luc's folder, container and disk would be jean_luc's
    token = platform.sign(platform.claims(second.nonce, word.upper() + "-LUC"))
    answer = second.finish(token)
    assert_refused(hub, before, answer, 403, "which another LMS user")
    assert ISS not in answer[2]  # the page names nobody's LMS identity; the log does
    assert "would take the hub name of %s_luc of %s" % (word, ISS) in hub.log()
