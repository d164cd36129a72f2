"""HTTP for the LMS: one request with the standard library, and retries with exponential backoff.

An LMS that is down (no connection, a 5xx) or busy (429) is tried again after 1, 2, 4, ... s
(at most MAX_DELAY_S each, or the Retry-After it asks for within that bound), a bounded number of
times and within a bounded total time; then the request is Unavailable. Any other 4xx is a
refusal (Refused), with the LMS's own message: trying again would get the same answer. The sleep
and the clock are given, so a test drives the backoff without waiting.
"""
from __future__ import annotations

import json
import time
import urllib.error
import urllib.request
from typing import Callable, Dict, List, Mapping, NamedTuple, Optional

MAX_DELAY_S = 30.0
FIRST_DELAY_S = 1.0
TIMEOUT_S = 30.0
MESSAGE_LIMIT = 300


class Response(NamedTuple):
    status: int
    headers: Mapping[str, str]
    body: bytes

    def json(self) -> object:
        return json.loads(self.body.decode("utf-8") or "null")


class Unreachable(Exception):
    """No answer: the connection failed or timed out."""


class Refused(Exception):
    """The LMS answered no (a 4xx other than 429): what it said, for the TA."""

    def __init__(self, method: str, url: str, status: int, message: str) -> None:
        super().__init__("%s %s: refused, HTTP %d: %s" % (method, url, status, message))
        self.status = status
        self.message = message


class Unavailable(Exception):
    """Still down or busy after every retry."""


def lms_message(response: Response) -> str:
    """What the LMS said in an error answer: its JSON's message fields, else the body's start."""
    text = response.body.decode("utf-8", "replace")
    try:
        data = json.loads(text)
    except ValueError:
        data = None
    if isinstance(data, dict):
        parts = [str(data[k]) for k in ("error", "error_description", "message", "errors", "reason") if data.get(k)]
        if parts:
            text = ": ".join(parts)
    text = " ".join(text.split())
    return text[:MESSAGE_LIMIT] or "(no message)"


class Http:
    """One HTTP request at a time, through urllib (no retry)."""

    def __init__(self, timeout: float = TIMEOUT_S) -> None:
        self.timeout = timeout

    def send(self, method: str, url: str, headers: Mapping[str, str], body: Optional[bytes] = None) -> Response:
        """The answer, whatever its status; Unreachable when there is none."""
        request = urllib.request.Request(url, data=body, headers=dict(headers), method=method)
        try:
            with urllib.request.urlopen(request, timeout=self.timeout) as answer:
                return Response(answer.status, dict(answer.headers.items()), answer.read())
        except urllib.error.HTTPError as err:
            return Response(err.code, dict(err.headers.items()) if err.headers else {}, err.read() or b"")
        except (urllib.error.URLError, OSError) as err:
            raise Unreachable("%s %s: %s" % (method, url, getattr(err, "reason", None) or err)) from err


Sender = Callable[[str, str, Mapping[str, str], Optional[bytes]], Response]


def header(headers: Mapping[str, str], name: str) -> str:
    """The value of the header `name`, whatever the case of its key ("" without it)."""
    return {key.lower(): value for key, value in headers.items()}.get(name.lower(), "")


def retry_after(response: Response) -> Optional[float]:
    """The seconds a Retry-After header asks for (None without one, or in the date form)."""
    try:
        return max(0.0, float(header(response.headers, "Retry-After")))
    except ValueError:
        return None


class Retrying:
    """Sends through `send`, trying again on no answer, a 5xx or a 429, with exponential backoff."""

    def __init__(self, send: Sender, retries: int, budget_s: float, sleep: Callable[[float], None] = time.sleep,
                 clock: Callable[[], float] = time.monotonic, say: Callable[[str], None] = lambda line: None) -> None:
        self._send = send
        self.retries = retries
        self.budget_s = budget_s
        self._sleep = sleep
        self._clock = clock
        self._say = say
        self.delays: List[float] = []  # every wait so far (a test reads them)

    def send(self, method: str, url: str, headers: Mapping[str, str], body: Optional[bytes] = None) -> Response:
        """A 2xx or 3xx answer; Refused on a 4xx but 429; Unavailable once the retries are spent."""
        started = self._clock()
        delay = FIRST_DELAY_S
        tries = 0
        while True:
            tries += 1
            try:
                response = self._send(method, url, headers, body)
                problem = "HTTP %d: %s" % (response.status, lms_message(response)) \
                    if response.status >= 500 or response.status == 429 else ""
            except Unreachable as err:
                response, problem = None, str(err)
            if not problem:
                assert response is not None
                if response.status >= 400:
                    raise Refused(method, url, response.status, lms_message(response))
                return response
            wait = min(MAX_DELAY_S, (retry_after(response) if response is not None else None) or delay)
            if tries > self.retries or self._clock() - started + wait > self.budget_s:
                raise Unavailable("%s %s: %s (tried %d times in %.0f s)" % (
                    method, url, problem, tries, self._clock() - started))
            self._say("LMS: %s; trying again in %.0f s" % (problem, wait))
            self.delays.append(wait)
            self._sleep(wait)
            delay = min(MAX_DELAY_S, delay * 2)


def json_headers(token: str, accept: str, content_type: str = "") -> Dict[str, str]:
    """The headers of an AGS request: the bearer token, the media type wanted, the one sent."""
    headers = {"Authorization": "Bearer %s" % token, "Accept": accept}
    if content_type:
        headers["Content-Type"] = content_type
    return headers
