"""A real LTI 1.3 platform on loopback, for the tests of the grades sent back to the LMS.

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

`write_results` writes a grading folder as course_grader does (`<out>/<student>/results.json`),
for the tests of what is posted from one.
"""
from __future__ import annotations

import json
import os
import threading
import urllib.parse
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any, Dict, List, Optional, Sequence, Tuple

import jwt
from cryptography.hazmat.primitives import serialization
from cryptography.hazmat.primitives.asymmetric import rsa
from lti1p3platform.exceptions import LineItemNotFoundException, LtiException, MissingRequiredClaim, \
    UnsupportedGrantType
from lti1p3platform.lineitem import TLineItem
from lti1p3platform.ltiplatform import LTI1P3PlatformConfAbstract
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


class LoopbackPlatform:
    """The platform on 127.0.0.1, a free port, in a thread; a context manager.

    Its URLs: `token_url`, `lineitems_url` (one course context), `tool_jwks_url` (the tool's JWKS,
    the public half of `tool_private_key` under `kid`). `outage(n)` answers the next n requests
    503, as a platform that is down; `requests` lists (method, path) of every request."""

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
        self._platform = _Platform(issuer=issuer, client_id=client_id, deployment_id=deployment_id,
                                   private_key=self._platform_keys[0], public_key=self._platform_keys[1],
                                   tool_jwks_url=self.tool_jwks_url)
        self._thread = threading.Thread(target=self._server.serve_forever, daemon=True)

    def __enter__(self) -> "LoopbackPlatform":
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._server.shutdown()
        self._server.server_close()
        self._thread.join()

    def outage(self, requests: int) -> None:
        """The next `requests` requests are answered 503 Service Unavailable."""
        self._outages = requests

    def scores_by_resource(self) -> Dict[str, Dict[str, Dict[str, Any]]]:
        """resourceId -> userId -> the score stored."""
        return {item["resourceId"]: self.book.scores.get(url, {}) for url, item in self.book.lineitems.items()}

    def _answer(self, method: str, path: str, query: Dict[str, str], headers: Any, body: bytes
                ) -> Tuple[int, str, bytes]:
        """(status, content type, body) for one request."""
        if self._outages > 0:
            self._outages -= 1
            return 503, "application/json", b'{"error": "down for maintenance"}'
        if method == "GET" and path == "/tool/jwks":
            return 200, "application/json", json.dumps(jwks_of(self._tool_public_key, self.kid)).encode()
        with self._lock:
            if method == "POST" and path == "/token":
                return self._token(body)
            if path.startswith("/ags/lineitems"):
                return self._ags(method, path, query, headers, body)
        return 404, "application/json", b'{"error": "no such endpoint"}'

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
                status, kind, out = platform._answer(self.command, parts.path, dict(urllib.parse.parse_qsl(parts.query)),
                                                     self.headers, body)
                self.send_response(status)
                self.send_header("Content-Type", kind)
                self.send_header("Content-Length", str(len(out)))
                self.end_headers()
                self.wfile.write(out)

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
