"""Retries with exponential backoff on a fake clock; refusals; the token's assertion and its cache."""
from __future__ import annotations

import json

import jwt
import pytest

from course_lti import config, token
from course_lti.transport import Refused, Response, Retrying, Unavailable, Unreachable


class Clock:
    """Time that passes only when slept."""

    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now

    def sleep(self, seconds: float) -> None:
        self.now += seconds


def scripted(*answers):
    """A sender giving `answers` in turn (a Response, or an exception to raise); it records calls."""
    calls = []

    def send(method, url, headers, body=None):
        calls.append((method, url, headers, body))
        answer = answers[min(len(calls), len(answers)) - 1]
        if isinstance(answer, Exception):
            raise answer
        return answer
    return send, calls


def ok(body=b"{}"):
    return Response(200, {}, body)


def test_down_then_up_is_tried_again_with_growing_waits():
    clock = Clock()
    send, calls = scripted(Unreachable("refused"), Response(503, {}, b""), Response(502, {}, b""), ok())
    retrying = Retrying(send, retries=5, budget_s=120, sleep=clock.sleep, clock=clock)
    assert retrying.send("GET", "https://lms/x", {}).status == 200
    assert retrying.delays == [1.0, 2.0, 4.0] and len(calls) == 4


def test_the_retries_are_bounded_in_count_and_in_time():
    clock = Clock()
    send, calls = scripted(Response(503, {}, b'{"message": "maintenance"}'))
    with pytest.raises(Unavailable, match="HTTP 503: maintenance .tried 4 times"):
        Retrying(send, retries=3, budget_s=600, sleep=clock.sleep, clock=clock).send("POST", "https://lms/x", {})
    assert len(calls) == 4
    clock, (send, calls) = Clock(), scripted(Unreachable("timed out"))
    retrying = Retrying(send, retries=50, budget_s=20, sleep=clock.sleep, clock=clock)
    with pytest.raises(Unavailable):
        retrying.send("GET", "https://lms/x", {})
    assert sum(retrying.delays) <= 20 and retrying.delays == [1.0, 2.0, 4.0, 8.0]


def test_a_busy_lms_is_waited_for_as_it_asks_within_the_bound():
    clock = Clock()
    send, _ = scripted(Response(429, {"Retry-After": "7"}, b""), Response(429, {"retry-after": "3600"}, b""), ok())
    retrying = Retrying(send, retries=5, budget_s=120, sleep=clock.sleep, clock=clock)
    retrying.send("GET", "https://lms/x", {})
    assert retrying.delays == [7.0, 30.0]


def test_a_refusal_is_not_tried_again_and_says_what_the_lms_said():
    clock = Clock()
    send, calls = scripted(Response(400, {}, json.dumps({"error": "invalid_request",
                                                         "error_description": "userId unknown"}).encode()))
    with pytest.raises(Refused) as caught:
        Retrying(send, retries=5, budget_s=120, sleep=clock.sleep, clock=clock).send("POST", "https://lms/s", {})
    assert caught.value.status == 400 and caught.value.message == "invalid_request: userId unknown"
    assert len(calls) == 1 and clock.now == 1000.0


def test_the_client_assertion_is_signed_by_the_tools_key_with_its_kid(write_config, key_pair):
    loaded = config.load(write_config(audience="https://lms.test/aud"))
    assertion = token.client_assertion(loaded, 1700000000.0, jti="j-1")
    assert jwt.get_unverified_header(assertion) == {"alg": "RS256", "kid": "k1", "typ": "JWT"}
    claims = jwt.decode(assertion, key_pair[1], algorithms=["RS256"], audience="https://lms.test/aud",
                        options={"verify_exp": False, "verify_iat": False})
    assert claims == {"iss": "tool", "sub": "tool", "aud": "https://lms.test/aud", "iat": 1700000000,
                      "exp": 1700000300, "jti": "j-1"}


def test_the_token_is_asked_for_once_and_again_shortly_before_it_expires(write_config):
    loaded = config.load(write_config())
    clock = Clock()
    send, calls = scripted(ok(b'{"access_token": "t1", "expires_in": 3600}'),
                           ok(b'{"access_token": "t2", "expires_in": 3600}'))
    tokens = token.TokenSource(loaded, send, clock)
    assert tokens.get() == "t1" and tokens.get() == "t1" and len(calls) == 1
    method, url, headers, body = calls[0]
    form = dict(pair.split("=", 1) for pair in body.decode().split("&"))
    assert (method, url, form["grant_type"]) == ("POST", "https://lms.test/token", "client_credentials")
    assert form["client_assertion_type"] == "urn%3Aietf%3Aparams%3Aoauth%3Aclient-assertion-type%3Ajwt-bearer"
    assert form["scope"].count("purl.imsglobal.org") == 3
    clock.now += 3600 - token.EARLY_S - 1
    assert tokens.get() == "t1"
    clock.now += 1
    assert tokens.get() == "t2" and len(calls) == 2
    tokens.forget()
    tokens.get()
    assert len(calls) == 3
