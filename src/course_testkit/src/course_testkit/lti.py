"""A real LTI 1.3 platform on loopback, the test LMS: the grades sent back to it, and the launches
from it that log students into the hub.

PyPI's lti1p3platform is the platform's side of LTI 1.3 as a library: the registration (issuer,
client id, the platform's key pair, the tool's JWKS URL), the token endpoint's checks
(`get_access_token`: the client-credentials grant, the client assertion's RS256 signature against
the key of its kid in the tool's JWKS, which it fetches over HTTP, the scopes it grants) and AGS
(`AssignmentsGradesService`: the bearer token checked against the platform's key, its issuer,
expiry and scopes, the methods allowed; line items and scores handed to storage methods it leaves
abstract). `LoopbackPlatform` serves those over HTTP on 127.0.0.1 and gives the storage: a
gradebook in memory, which keeps the latest score per user and refuses one older than the one it
has (AGS 2.0: a platform must not replace a score with an older one). Every check of a request is
the library's; what this module adds is the HTTP around it, the storage, and the tool's JWKS URL
(the tool's own endpoint, served here too).

The launch side (`make lti-check`, tests/e2e/test_lti.py) is the library's too: its OIDC login
initiation (`OIDCLoginAbstract`: the preflight URL with iss, login_hint, target_link_uri,
lti_message_hint, client_id and lti_deployment_id) and its message launch
(`LTIAdvantageMessageLaunchAbstract`: the authentication request checked for its nonce, state,
redirect_uri and client_id, the id_token's claims built and signed with the platform's key, the
AGS endpoint claim). This module adds what a platform's own pages are: a roster (`enrol`: each
user's LMS id and roles), course links (`add_link`, with custom parameters), a course page per
user with those links (`course_url`: it also opens the user's session with the platform, a
cookie), the authorization endpoint's further checks (the user's session is the login_hint's, the
redirect_uri is one the tool registered, the request is an OIDC implicit form_post one), the
auto-submitting form that posts the id_token and state to the tool, and the platform's JWKS.

`write_results` writes a grading folder as course_grader does (`<out>/<student>/results.json`),
for the tests of what is posted from one.
"""
from __future__ import annotations

import html
import json
import os
import threading
import urllib.parse
from http.cookies import SimpleCookie
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any, Dict, List, NamedTuple, Optional, Sequence, Tuple

import jwt
from cryptography.hazmat.primitives import serialization
from cryptography.hazmat.primitives.asymmetric import rsa
from lti1p3platform.exceptions import LineItemNotFoundException, LtiException, MissingRequiredClaim, \
    PreflightRequestValidationException, UnsupportedGrantType
from lti1p3platform.lineitem import TLineItem
from lti1p3platform.ltiplatform import LTI1P3PlatformConfAbstract
from lti1p3platform.message_launch import LTIAdvantageMessageLaunchAbstract
from lti1p3platform.oidc_login import OIDCLoginAbstract
from lti1p3platform.registration import Registration
from lti1p3platform.request import Request, TRequest
from lti1p3platform.response import Response
from lti1p3platform.score import TScore, UpdateScoreStatus
from lti1p3platform.service_connector import AssignmentsGradesService, TPage


def rsa_key_pair() -> Tuple[bytes, bytes]:
    """A fresh 2048-bit RSA key pair: (private PEM, public PEM)."""
    key = rsa.generate_private_key(public_exponent=65537, key_size=2048)
    private = key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                serialization.NoEncryption())
    public = key.public_key().public_bytes(serialization.Encoding.PEM, serialization.PublicFormat.SubjectPublicKeyInfo)
    return private, public


def jwks_of(public_pem: bytes, kid: str) -> Dict[str, List[Dict[str, Any]]]:
    """The JWKS a tool publishes for its public key."""
    key = json.loads(jwt.algorithms.RSAAlgorithm.to_jwk(serialization.load_pem_public_key(public_pem)))
    key.update({"kid": kid, "alg": "RS256", "use": "sig"})
    return {"keys": [key]}


class _Platform(LTI1P3PlatformConfAbstract):
    """The library's platform configuration, with one registration (the tool's)."""

    def init_platform_config(self, **settings: Any) -> None:
        self._registration = (Registration().set_iss(settings["issuer"]).set_client_id(settings["client_id"])
                              .set_deployment_id(settings["deployment_id"])
                              .set_platform_private_key(settings["private_key"].decode())
                              .set_platform_public_key(settings["public_key"].decode())
                              .set_tool_key_set_url(settings["tool_jwks_url"]))

    def get_registration_by_params(self, **kwargs: Any) -> Registration:
        assert self._registration is not None
        return self._registration


class Gradebook:
    """The platform's storage: line items and the latest score of each user on each."""

    def __init__(self) -> None:
        self.lineitems: Dict[str, Dict[str, Any]] = {}  # id (URL) -> line item
        self.scores: Dict[str, Dict[str, Dict[str, Any]]] = {}  # line item id -> userId -> score
        self.score_posts = 0  # every score POST the library let through


class _Request(Request):
    """One HTTP request as the library reads it."""

    def build_metadata(self, request: Dict[str, Any]) -> TRequest:
        return request  # type: ignore[return-value]


class _Ags(AssignmentsGradesService):
    """The library's AGS with its storage methods on a Gradebook."""

    def __init__(self, request: Request, platform: _Platform, lineitems_url: str, book: Gradebook) -> None:
        super().__init__(request, platform, lineitems_url)
        self.book = book

    def find_lineitems(self, page: int = 1, limit: Optional[int] = None, line_item_id: Optional[str] = None,
                       resource_link_id: Optional[str] = None, resource_id: Optional[str] = None,
                       tag: Optional[str] = None) -> TPage:
        found = [item for item in self.book.lineitems.values()
                 if (resource_id is None or item.get("resourceId") == resource_id)
                 and (tag is None or item.get("tag") == tag)]
        return {"content": found, "has_next": False}

    def find_lineitem(self, line_item_id: str) -> TLineItem:
        item = self.book.lineitems.get(self._url(line_item_id))
        if item is None:
            raise LineItemNotFoundException(line_item_id)
        return item  # type: ignore[return-value]

    def create_lineitem(self, creation_data: TLineItem) -> TLineItem:
        item = dict(creation_data)
        item["id"] = self._url(str(len(self.book.lineitems) + 1))
        self.book.lineitems[item["id"]] = item
        return item  # type: ignore[return-value]

    def update_lineitem(self, update_data: TLineItem) -> TLineItem:
        item = self.find_lineitem(str(update_data["id"]))
        item.update(update_data)
        return item

    def delete_lineitem(self, line_item_id: str) -> None:
        self.find_lineitem(line_item_id)
        del self.book.lineitems[self._url(line_item_id)]
        self.book.scores.pop(self._url(line_item_id), None)

    def update_score(self, line_item_id: str, score: TScore) -> UpdateScoreStatus:
        url = self._url(line_item_id)
        self.find_lineitem(line_item_id)
        self.book.score_posts += 1
        mine = self.book.scores.setdefault(url, {})
        earlier = mine.get(str(score["userId"]))
        if earlier is not None and str(earlier["timestamp"]) > str(score["timestamp"]):
            return UpdateScoreStatus.OLD_TIMESTAMP
        mine[str(score["userId"])] = dict(score)
        return UpdateScoreStatus.SUCCESS if earlier is not None else UpdateScoreStatus.CREATED

    def get_results(self, line_item_id: str, page: int = 1, limit: Optional[int] = None,
                    user_id: Optional[str] = None) -> TPage:
        url = self._url(line_item_id)
        found = [{"userId": user, "resultScore": s["scoreGiven"], "resultMaximum": s["scoreMaximum"],
                  "comment": s.get("comment", ""), "scoreOf": url}
                 for user, s in self.book.scores.get(url, {}).items() if user_id in (None, user)]
        return {"content": found, "has_next": False}

    def _url(self, line_item_id: str) -> str:
        return line_item_id if "://" in line_item_id else "%s/%s" % (self.ags.lineitems_url, line_item_id)


LIS = "http://purl.imsglobal.org/vocab/lis/v2/"
LEARNER = LIS + "membership#Learner"
INSTRUCTOR = LIS + "membership#Instructor"
SESSION_COOKIE = "lms_session"  # the platform's own login: which of its users is at this browser


class Member(NamedTuple):
    """A user of the platform's course: LMS user id (the launches' sub), roles, display name."""

    sub: str
    roles: Tuple[str, ...]
    name: str


class Link(NamedTuple):
    """A course link to the tool (a resource link), with its custom parameters."""

    link_id: str
    title: str
    custom: Tuple[Tuple[str, str], ...] = ()


class LaunchRefused(Exception):
    """The platform will not launch: the message is its page's."""


class _Reply(NamedTuple):
    """One HTTP answer: status, content type, body, further headers (Location, Set-Cookie)."""

    status: int
    kind: str
    body: bytes
    headers: Tuple[Tuple[str, str], ...] = ()


class _LoginInitiation(OIDCLoginAbstract):
    """The library's third-party login initiation; the message hint is the course link's id."""

    def set_lti_message_hint(self, **kwargs: Any) -> None:
        self._lti_message_hint = kwargs["link_id"]

    def get_redirect(self, url: str) -> str:
        return url


class _Launch(LTIAdvantageMessageLaunchAbstract):
    """The library's message launch, answering the tool's authentication request for one of the
    platform's users on one of its links (see LoopbackPlatform.authorize)."""

    def __init__(self, request: Request, platform: "LoopbackPlatform", session: str) -> None:
        super().__init__(request, platform._platform)
        self.owner, self.session = platform, session
        self.claims: Dict[str, Any] = {}

    def prepare_launch(self, preflight_response: Dict[str, Any]) -> None:
        """The checks the library leaves to the platform, then the claims of this user and link."""
        owner = self.owner
        if preflight_response.get("response_type") != "id_token" or \
                "openid" not in str(preflight_response.get("scope", "")).split() or \
                preflight_response.get("response_mode") != "form_post":
            raise LaunchRefused("not an OIDC implicit-flow form_post authentication request")
        if preflight_response.get("redirect_uri") not in owner.redirect_uris:
            raise LaunchRefused("redirect_uri %r is not one the tool registered" % preflight_response.get("redirect_uri"))
        member = owner.roster.get(str(preflight_response.get("login_hint")))
        if member is None or member.sub != self.session:
            raise LaunchRefused("the login_hint is not the user logged in to the platform at this browser")
        link = owner.links.get(str(preflight_response.get("lti_message_hint")))
        if link is None:
            raise LaunchRefused("lti_message_hint names no course link")
        self.set_user_data(member.sub, list(member.roles), full_name=member.name)
        self.set_resource_link_claim(link.link_id, title=link.title)
        self.set_launch_context_claim(owner.context_id, context_title=owner.context_title)
        if link.custom:
            self.set_custom_parameters_claim(dict(link.custom))
        self.set_ags(owner.lineitems_url, allow_creating_lineitems=True)

    def get_launch_data(self) -> Tuple[Dict[str, Any], str]:
        message, state = super().get_launch_data()
        self.claims = message  # the library signs this very dict, adding iat and exp
        return message, state

    def render_launch_form(self, launch_data: Dict[str, Any], **kwargs: Any) -> bytes:
        """The page that posts the id_token and state to the tool's redirect_uri at once (the OIDC
        form_post response mode)."""
        fields = "".join('<input type="hidden" name="%s" value="%s">' % (name, html.escape(str(launch_data[name])))
                         for name in ("id_token", "state"))
        return ('<!doctype html><title>Opening the tool</title><form id="lti-launch" method="post" action="%s">%s'
                '<noscript><button>Continue</button></noscript></form>'
                '<script>document.getElementById("lti-launch").submit();</script>'
                % (html.escape(launch_data["launch_url"]), fields)).encode()


class LoopbackPlatform:
    """The platform on 127.0.0.1, a free port, in a thread; a context manager.

    Its URLs: `token_url`, `lineitems_url` (one course context), `tool_jwks_url` (the tool's JWKS,
    the public half of `tool_private_key` under `kid`). `outage(n)` answers the next n requests
    503, as a platform that is down; `requests` lists (method, path) of every request.

    The launches: `register_tool` (the tool's login initiation URL, target link URI and redirect
    URIs), `enrol` (a user and their roles), `add_link` (a course link, its custom parameters);
    `course_url(sub)` is the course page as that user sees it, `authorize_url` the platform's
    OIDC authorization endpoint, `jwks_url` its keys. `launches` lists the claims of every
    id_token it signed."""

    def __init__(self, issuer: str = "https://lms.test", client_id: str = "course-tool",
                 deployment_id: str = "1", kid: str = "tool-key-1") -> None:
        self.issuer, self.client_id, self.deployment_id, self.kid = issuer, client_id, deployment_id, kid
        self.tool_private_key, self._tool_public_key = rsa_key_pair()
        self._platform_keys = rsa_key_pair()
        self.book = Gradebook()
        self.requests: List[Tuple[str, str]] = []
        self.token_errors: List[str] = []
        self._outages = 0
        self._lock = threading.Lock()
        self._server = ThreadingHTTPServer(("127.0.0.1", 0), self._handler())
        self._server.daemon_threads = True
        self.base = "http://127.0.0.1:%d" % self._server.server_address[1]
        self.token_url = self.base + "/token"
        self.lineitems_url = self.base + "/ags/lineitems"
        self.tool_jwks_url = self.base + "/tool/jwks"
        self.authorize_url = self.base + "/lms/authorize"
        self.jwks_url = self.base + "/lms/jwks"
        self._platform = _Platform(issuer=issuer, client_id=client_id, deployment_id=deployment_id,
                                   private_key=self._platform_keys[0], public_key=self._platform_keys[1],
                                   tool_jwks_url=self.tool_jwks_url)
        self.context_id, self.context_title = "ros-course", "ROS course"
        self.roster: Dict[str, Member] = {}
        self.links: Dict[str, Link] = {}
        self.redirect_uris: Tuple[str, ...] = ()
        self.launches: List[Dict[str, Any]] = []
        self._thread = threading.Thread(target=self._server.serve_forever, daemon=True)

    def __enter__(self) -> "LoopbackPlatform":
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._server.shutdown()
        self._server.server_close()
        self._thread.join()

    def register_tool(self, login_url: str, target_link_uri: str, redirect_uris: Sequence[str]) -> None:
        """The tool as registered with the platform: where a launch starts (its OIDC login
        initiation URL), the link's target, and where id_tokens may be posted."""
        registration = self._platform.get_registration()
        registration.set_oidc_login_url(login_url).set_launch_url(target_link_uri)
        self.redirect_uris = tuple(redirect_uris)

    def enrol(self, sub: str, roles: Sequence[str], name: str = "") -> None:
        """A user of the course: LMS user id `sub`, LTI roles (LEARNER, INSTRUCTOR, ...)."""
        self.roster[sub] = Member(sub, tuple(roles), name or sub)

    def add_link(self, link_id: str, title: str, custom: Optional[Dict[str, str]] = None) -> None:
        """A course link to the tool; `custom`: its custom parameters (the launch's custom claim)."""
        self.links[link_id] = Link(link_id, title, tuple(sorted((custom or {}).items())))

    def course_url(self, sub: str) -> str:
        """The course page as user `sub` opens it (it logs that user in to the platform)."""
        return "%s/lms/course?user=%s" % (self.base, urllib.parse.quote(sub))

    def outage(self, requests: int) -> None:
        """The next `requests` requests are answered 503 Service Unavailable."""
        self._outages = requests

    def scores_by_resource(self) -> Dict[str, Dict[str, Dict[str, Any]]]:
        """resourceId -> userId -> the score stored."""
        return {item["resourceId"]: self.book.scores.get(url, {}) for url, item in self.book.lineitems.items()}

    def _answer(self, method: str, path: str, query: Dict[str, str], headers: Any, body: bytes) -> _Reply:
        """The answer to one request."""
        if self._outages > 0:
            self._outages -= 1
            return _Reply(503, "application/json", b'{"error": "down for maintenance"}')
        if method == "GET" and path == "/tool/jwks":
            return _Reply(200, "application/json", json.dumps(jwks_of(self._tool_public_key, self.kid)).encode())
        with self._lock:
            if method == "POST" and path == "/token":
                return _Reply(*self._token(body))
            if path.startswith("/ags/lineitems"):
                return _Reply(*self._ags(method, path, query, headers, body))
            if path.startswith("/lms/"):
                return self._lms(method, path, query, headers, body)
        return _Reply(404, "application/json", b'{"error": "no such endpoint"}')

    def _lms(self, method: str, path: str, query: Dict[str, str], headers: Any, body: bytes) -> _Reply:
        """The platform's own pages: the course page, a link's launch, the OIDC authorization
        endpoint, the JWKS."""
        session = SimpleCookie(headers.get("Cookie") or "")
        user = session[SESSION_COOKIE].value if SESSION_COOKIE in session else ""
        try:
            if path == "/lms/jwks":
                return _Reply(200, "application/json", json.dumps(self._platform.get_jwks()).encode())
            if path == "/lms/course":
                return self._course_page(query.get("user", ""))
            if path == "/lms/launch":
                return self._login_initiation(user, query.get("link", ""))
            if path == "/lms/authorize":
                form = dict(urllib.parse.parse_qsl(body.decode())) if method == "POST" else {}
                return self._authorize(user, dict(query), form)
        except (LaunchRefused, PreflightRequestValidationException, AssertionError) as err:
            why = str(err) or "the authentication request lacks nonce, state, redirect_uri or this client_id"
            page = "<!doctype html><title>Launch refused</title><p id=refused>Launch refused: %s</p>" % html.escape(why)
            return _Reply(400, "text/html", page.encode())
        return _Reply(404, "application/json", b'{"error": "no such page"}')

    def _course_page(self, sub: str) -> _Reply:
        """The course as `sub` sees it: its links to the tool; the user's platform session begins."""
        if sub not in self.roster:
            raise LaunchRefused("no such user in the course")
        items = "".join('<li><a id="link-%s" href="/lms/launch?link=%s">%s</a></li>' % (
            html.escape(link.link_id), urllib.parse.quote(link.link_id), html.escape(link.title))
            for link in self.links.values())
        page = "<!doctype html><title>%s</title><h1>%s</h1><p>%s</p><ul>%s</ul>" % (
            html.escape(self.context_title), html.escape(self.context_title), html.escape(self.roster[sub].name), items)
        return _Reply(200, "text/html", page.encode(),
                      (("Set-Cookie", "%s=%s; Path=/; HttpOnly; SameSite=Lax" % (SESSION_COOKIE, sub)),))

    def _login_initiation(self, user: str, link_id: str) -> _Reply:
        """A click on a course link: the library's third-party login initiation, a redirect to the
        tool's login URL."""
        if user not in self.roster or link_id not in self.links:
            raise LaunchRefused("log in to the platform and open a course link")
        login = _LoginInitiation(None, self._platform)
        login.set_lti_message_hint(link_id=link_id)
        return _Reply(302, "text/plain", b"", (("Location", login.initiate_login(user)),))

    def _authorize(self, user: str, query: Dict[str, str], form: Dict[str, str]) -> _Reply:
        """The tool's authentication request: the library's launch, its id_token posted to the tool
        by an auto-submitting form."""
        launch = _Launch(_Request({"method": "GET", "get_data": query, "form_data": form, "headers": {},
                                   "content_type": None, "path": "/lms/authorize", "json": None}), self, user)
        page = launch.lti_launch()
        self.launches.append(launch.claims)
        return _Reply(200, "text/html", page)

    def _token(self, body: bytes) -> Tuple[int, str, bytes]:
        form = dict(urllib.parse.parse_qsl(body.decode()))
        try:
            token = self._platform.get_access_token(form)
        except (MissingRequiredClaim, UnsupportedGrantType, LtiException, jwt.PyJWTError) as err:
            self.token_errors.append("%s: %s" % (type(err).__name__, err))
            return 400, "application/json", json.dumps({"error": "invalid_client",
                                                       "error_description": str(err)}).encode()
        return 200, "application/json", json.dumps(token).encode()

    def _ags(self, method: str, path: str, query: Dict[str, str], headers: Any, body: bytes
             ) -> Tuple[int, str, bytes]:
        request = _Request({"method": method, "form_data": {}, "get_data": dict(query), "headers": headers,
                            "content_type": headers.get("Content-Type"), "path": path,
                            "json": json.loads(body.decode() or "null") if body else None})
        service = _Ags(request, self._platform, self.lineitems_url, self.book)
        rest = [p for p in path[len("/ags/lineitems"):].split("/") if p]
        if not rest:
            handler = service.handle_get_lineitems if method == "GET" else service.handle_create_lineitem
            response: Response = service.handle_resp(handler)
        elif len(rest) == 1:
            response = service.handle_resp(service.handle_get_lineitem, line_item_id=rest[0])
        elif rest[1] == "scores":
            response = service.handle_resp(service.handle_update_score, line_item_id=rest[0])
        else:
            response = service.handle_resp(service.handle_get_results, line_item_id=rest[0])
        result = response.result
        if isinstance(result, dict) and "content" in result:
            result = result["content"]  # the container is the list of line items (AGS 2.0)
        payload = result if result is not None else {"message": response.message}
        return response.code, response.media_type, json.dumps(payload).encode()

    def _handler(self) -> type:
        platform = self

        class Handler(BaseHTTPRequestHandler):
            def _serve(self) -> None:
                parts = urllib.parse.urlsplit(self.path)
                length = int(self.headers.get("Content-Length") or 0)
                body = self.rfile.read(length) if length else b""
                platform.requests.append((self.command, self.path))
                reply = platform._answer(self.command, parts.path, dict(urllib.parse.parse_qsl(parts.query)),
                                         self.headers, body)
                self.send_response(reply.status)
                self.send_header("Content-Type", reply.kind)
                self.send_header("Content-Length", str(len(reply.body)))
                for name, value in reply.headers:
                    self.send_header(name, value)
                self.end_headers()
                self.wfile.write(reply.body)

            do_GET = do_POST = do_PUT = do_DELETE = _serve

            def log_message(self, *args: object) -> None:
                pass

        return Handler


def write_results(out: str, student: str, verdicts: Sequence[Tuple[str, float, float, str, str]]) -> str:
    """`<out>/<student>/results.json` as course_grader.gradescope writes it, for verdicts
    (milestone, points, max points, output, cause): an output "passed", or "FAILED: reason",
    then the log tails after a blank line. Its path."""
    tests = [{"name": "%s: title (text)" % milestone, "number": str(number), "score": points, "max_score": maximum,
              "status": "passed" if output.startswith("passed") else "failed", "output": output,
              "visibility": "visible", "extra_data": {"milestone": milestone, "seconds": 1.0, "cause": cause}}
             for number, (milestone, points, maximum, output, cause) in enumerate(verdicts, 1)]
    folder = os.path.join(out, student)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "results.json")
    with open(path, "w") as stream:
        json.dump({"score": sum(t["score"] for t in tests), "tests": tests}, stream)
    return path
