"""The AGS access token: OAuth 2 client credentials with a JWT client assertion (IMS Security
Framework 1.0, section 4.1), signed RS256 by the tool's private key.

    POST token_url  grant_type=client_credentials
                    client_assertion_type=urn:ietf:params:oauth:client-assertion-type:jwt-bearer
                    client_assertion=<JWT: iss=sub=client_id, aud=token URL, iat, exp, jti; header kid>
                    scope=<the AGS scopes, space-separated>

The token is kept until shortly before it expires (EARLY_S), so a run posting a class asks once.
"""
from __future__ import annotations

import time
import urllib.parse
import uuid
from typing import Callable, Optional, Tuple

import jwt

from course_lti.config import LtiConfig
from course_lti.transport import Refused, Response

SCOPE_LINEITEM = "https://purl.imsglobal.org/spec/lti-ags/scope/lineitem"
SCOPE_RESULT_READ = "https://purl.imsglobal.org/spec/lti-ags/scope/result.readonly"
SCOPE_SCORE = "https://purl.imsglobal.org/spec/lti-ags/scope/score"
AGS_SCOPES = (SCOPE_LINEITEM, SCOPE_RESULT_READ, SCOPE_SCORE)
ASSERTION_TYPE = "urn:ietf:params:oauth:client-assertion-type:jwt-bearer"
ASSERTION_LIFETIME_S = 300
EARLY_S = 60  # a token is asked for again this long before it expires
DEFAULT_EXPIRES_S = 3600


def client_assertion(config: LtiConfig, now: float, jti: str = "") -> str:
    """The signed JWT the tool proves itself with."""
    claims = {"iss": config.client_id, "sub": config.client_id, "aud": config.assertion_audience,
              "iat": int(now), "exp": int(now) + ASSERTION_LIFETIME_S, "jti": jti or uuid.uuid4().hex}
    return jwt.encode(claims, config.private_key_pem, algorithm="RS256", headers={"kid": config.kid})


def token_request(config: LtiConfig, now: float, scopes: Tuple[str, ...] = AGS_SCOPES) -> bytes:
    """The form body of the token request."""
    return urllib.parse.urlencode({
        "grant_type": "client_credentials",
        "client_assertion_type": ASSERTION_TYPE,
        "client_assertion": client_assertion(config, now),
        "scope": " ".join(scopes),
    }).encode("ascii")


class TokenSource:
    """The current access token, asked for when there is none or it is about to expire."""

    def __init__(self, config: LtiConfig, send: Callable[..., Response], clock: Callable[[], float] = time.time
                 ) -> None:
        self.config = config
        self._send = send
        self._clock = clock
        self._token: Optional[str] = None
        self._until = 0.0
        self.asked = 0  # token requests made (a test reads it)

    def get(self) -> str:
        """A token valid for at least EARLY_S more seconds."""
        now = self._clock()
        if self._token is None or now >= self._until:
            response = self._send("POST", self.config.token_url,
                                  {"Content-Type": "application/x-www-form-urlencoded", "Accept": "application/json"},
                                  token_request(self.config, now))
            self.asked += 1
            data = response.json()
            if not isinstance(data, dict) or not data.get("access_token"):
                raise Refused("POST", self.config.token_url, response.status, "no access_token in the answer")
            expires = data.get("expires_in")
            lifetime = float(expires) if isinstance(expires, (int, float)) and expires > 0 else DEFAULT_EXPIRES_S
            self._token = str(data["access_token"])
            self._until = now + max(0.0, lifetime - EARLY_S)
        return self._token

    def forget(self) -> None:
        """Drop the token (the LMS said 401: ask again)."""
        self._token = None
