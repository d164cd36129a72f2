"""The tool's registration with the LMS, as a TA writes it: `lti.yaml` (YAML, or the same as JSON).

    issuer: https://lms.example.edu            # the platform's issuer (iss of its launches)
    client_id: "10000000000042"                # the client id the LMS gave the tool
    deployment_id: "1:course"                  # optional: only users of this deployment are posted to
    token_url: https://lms.example.edu/login/oauth2/token
    audience: ""                               # optional: the aud of the client assertion (default token_url)
    lineitems_url: https://lms.example.edu/api/lti/courses/7/line_items
                                               # the course context's AGS endpoint (claim `lineitems`);
                                               # optional when lti-users.json records it per user
    private_key: lti-tool-key.pem              # the tool's RSA private key, PEM (relative: to this file)
    kid: course-tool-1                         # the key's id in the tool's JWKS
    grades: per_milestone                      # or per_assignment
    assignments:                               # per_assignment: line item -> its milestones
      lab2: [chatter, checkpoint1, checkpoint2, checkpoint3]
    tag: robotics_labs                         # optional: the line items' tag (default the course's name)
    retries: 5                                 # optional: tries after the first, on a connection error, 5xx, 429
    retry_seconds: 120                         # optional: the most time the retries of one request may take

Every mistake is reported at once, each as `FILE: FIELD: message`, never as a traceback: a TA
reads them before a grading starts (the commands check the file before grading).
"""
from __future__ import annotations

import ipaddress
import os
from typing import Any, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple
from urllib.parse import urlsplit

import yaml
from cryptography.hazmat.primitives import serialization
from cryptography.hazmat.primitives.asymmetric import rsa

PER_MILESTONE = "per_milestone"
PER_ASSIGNMENT = "per_assignment"
KEYS = ("issuer", "client_id", "deployment_id", "token_url", "audience", "lineitems_url", "private_key", "kid",
        "grades", "assignments", "tag", "retries", "retry_seconds")
DEFAULT_RETRIES = 5
DEFAULT_RETRY_SECONDS = 120.0


class ConfigError(ValueError):
    """A configuration that cannot be used: every problem, each `FILE: FIELD: message`."""

    def __init__(self, problems: Sequence[str]) -> None:
        super().__init__("\n".join(problems))
        self.problems = list(problems)


class LtiConfig(NamedTuple):
    """The registration, checked: URLs usable, the key readable, the mode known."""

    file: str
    issuer: str
    client_id: str
    token_url: str
    private_key_pem: bytes  # the key file's content (read once, so a dry run needs no file later)
    kid: str
    deployment_id: str = ""
    audience: str = ""
    lineitems_url: str = ""
    grades: str = PER_MILESTONE
    assignments: Tuple[Tuple[str, Tuple[str, ...]], ...] = ()  # in the file's order
    tag: str = ""
    retries: int = DEFAULT_RETRIES
    retry_seconds: float = DEFAULT_RETRY_SECONDS

    @property
    def assertion_audience(self) -> str:
        """The aud of the client assertion: the configured audience, else the token URL."""
        return self.audience or self.token_url


def is_loopback(host: str) -> bool:
    """Whether `host` names this machine (plain HTTP is allowed there only: a test platform)."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def url_problem(value: str) -> str:
    """Why `value` is no URL the tool may send a token or a grade to ("" when it is one): HTTPS,
    or HTTP to this machine."""
    parts = urlsplit(value)
    if parts.scheme not in ("https", "http") or not parts.hostname:
        return "%r is not an http(s) URL" % value
    if parts.scheme == "http" and not is_loopback(parts.hostname):
        return "%r: plain http sends the token in clear; use https (http only on loopback)" % value
    return ""


class _Checker:
    """Collects the problems of one file."""

    def __init__(self, shown: str) -> None:
        self.shown = shown
        self.problems: List[str] = []

    def error(self, field: str, message: str) -> None:
        self.problems.append("%s: %s: %s" % (self.shown, field, message))

    def text(self, data: Mapping[str, Any], field: str, required: bool) -> str:
        value = data.get(field)
        if value is None or value == "":
            if required:
                self.error(field, "missing")
            return ""
        if isinstance(value, bool) or not isinstance(value, (str, int)):
            self.error(field, "must be a string, not %s" % type(value).__name__)
            return ""
        return str(value)

    def url(self, data: Mapping[str, Any], field: str, required: bool) -> str:
        value = self.text(data, field, required)
        problem = url_problem(value) if value else ""
        if problem:
            self.error(field, problem)
        return value


def _private_key(check: _Checker, given: str, folder: str) -> bytes:
    """The PEM of the RSA private key at `given` (relative to `folder`), b"" after a problem."""
    if not given:
        return b""
    path = os.path.join(folder, os.path.expanduser(given))
    try:
        with open(path, "rb") as stream:
            pem = stream.read()
    except OSError as err:
        check.error("private_key", "cannot read %s: %s" % (path, err.strerror or err))
        return b""
    try:
        key = serialization.load_pem_private_key(pem, password=None)
    except (ValueError, TypeError) as err:
        check.error("private_key", "%s is no unencrypted PEM private key (%s)" % (path, err))
        return b""
    if not isinstance(key, rsa.RSAPrivateKey):
        check.error("private_key", "%s is not an RSA key: LTI 1.3 signs with RS256" % path)
        return b""
    return pem


def _assignments(check: _Checker, given: Any) -> Tuple[Tuple[str, Tuple[str, ...]], ...]:
    if given is None:
        return ()
    if not isinstance(given, dict):
        check.error("assignments", "must map each assignment's name to its list of milestones")
        return ()
    found = []
    for name, milestones in given.items():
        if not isinstance(milestones, list) or not milestones or not all(isinstance(m, str) for m in milestones):
            check.error("assignments.%s" % name, "must be a non-empty list of milestone ids")
            continue
        found.append((str(name), tuple(milestones)))
    return tuple(found)


def _number(check: _Checker, data: Mapping[str, Any], field: str, default: float, least: float) -> float:
    value = data.get(field, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or value < least:
        check.error(field, "must be a number of at least %g, not %r" % (least, value))
        return default
    return value


def parse(data: Any, file: str, shown: str = "") -> LtiConfig:
    """The configuration `data` (the file's parsed content) holds; ConfigError with every problem."""
    check = _Checker(shown or file)
    if not isinstance(data, dict):
        raise ConfigError(["%s: (the file): must be a mapping of the fields %s" % (check.shown, ", ".join(KEYS))])
    for key in data:
        if key not in KEYS:
            check.error(str(key), "unknown field (the fields: %s)" % ", ".join(KEYS))
    grades = check.text(data, "grades", False) or PER_MILESTONE
    if grades not in (PER_MILESTONE, PER_ASSIGNMENT):
        check.error("grades", "must be %s or %s, not %r" % (PER_MILESTONE, PER_ASSIGNMENT, grades))
    assignments = _assignments(check, data.get("assignments"))
    if assignments and grades != PER_ASSIGNMENT:
        check.error("assignments", "given, but grades is %s: write grades: %s" % (grades, PER_ASSIGNMENT))
    config = LtiConfig(
        file=file,
        issuer=check.text(data, "issuer", True),
        client_id=check.text(data, "client_id", True),
        token_url=check.url(data, "token_url", True),
        private_key_pem=_private_key(check, check.text(data, "private_key", True), os.path.dirname(file)),
        kid=check.text(data, "kid", True),
        deployment_id=check.text(data, "deployment_id", False),
        audience=check.text(data, "audience", False),
        lineitems_url=check.url(data, "lineitems_url", False),
        grades=grades,
        assignments=assignments,
        tag=check.text(data, "tag", False),
        retries=int(_number(check, data, "retries", DEFAULT_RETRIES, 0)),
        retry_seconds=float(_number(check, data, "retry_seconds", DEFAULT_RETRY_SECONDS, 0)))
    if check.problems:
        raise ConfigError(check.problems)
    return config


def load(path: str) -> LtiConfig:
    """The configuration in the file `path`; ConfigError with every problem."""
    try:
        with open(path) as stream:
            data = yaml.safe_load(stream)
    except OSError as err:
        raise ConfigError(["%s: (the file): cannot read it: %s" % (path, err.strerror or err)]) from err
    except yaml.YAMLError as err:
        raise ConfigError(["%s: (the file): not YAML: %s" % (path, str(err).replace("\n", " "))]) from err
    return parse(data, os.path.abspath(path), path)


def line_item_groups(config: LtiConfig, course_name: str, milestones: Sequence[str]) -> Dict[str, Tuple[str, ...]]:
    """What each line item holds: per milestone, each milestone alone; per assignment, the
    configured assignments, or one named after the course holding every milestone.
    ConfigError for an assignment naming a milestone the course lacks."""
    if config.grades == PER_MILESTONE:
        return {m: (m,) for m in milestones}
    groups = dict(config.assignments) or {course_name: tuple(milestones)}
    check = _Checker(config.file)
    for name, members in groups.items():
        unknown = [m for m in members if m not in milestones]
        if unknown:
            check.error("assignments.%s" % name, "no such milestone in the course: %s (the course's: %s)"
                        % (", ".join(unknown), ", ".join(milestones)))
    if check.problems:
        raise ConfigError(check.problems)
    return groups


def optional(path: Optional[str]) -> Optional[LtiConfig]:
    """The configuration at `path`, None when no path is given (the commands' --lti)."""
    return load(path) if path else None
