"""What an LMS's LTI 1.3 launch tells the hub, read by the hub's rules, with no JupyterHub:

- **the user's hub name** (`hub_name`), from a claim that never changes (`sub`, or a configured
  one such as the LMS login ID), put through the hub's name rules (course_hub.names): whatever
  the LMS sends, the result is a name whose slug is a plain DNS label, or a refusal;
- **the hub role** (`role_of`): Instructor or TeachingAssistant (a context role, or a sub-role of
  Instructor) makes a TA, a hub admin; Learner makes a student; no role claim, or no role the hub
  knows, is refused;
- **the milestone** a launch names in its custom parameters (`milestone_of`), checked against
  the course format's milestone ids before anything uses it;
- **who had each name** (`Identities`): the file `<data>/lti-users.json`, hub name ->
  {iss, sub, deployment_id, lineitems_url}. A second LMS user whose name maps onto a name (or a
  slug: one folder, one container) already held by another is refused, never merged; the grades
  back to the LMS (course_lti.users) read the same file to know whom a score is for;
- **nonces and states used once** (`UsedOnce`): a launch replayed with its cookies is refused.

course_hub.lti glues these into JupyterHub's LTI 1.3 authenticator; the unit tests run them
without JupyterHub. Every refusal is a `Refused` whose message a student or TA can act on.
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import tempfile
import threading
import time
from collections import OrderedDict
from typing import Any, Callable, Dict, Iterable, Mapping, NamedTuple, Optional, Sequence

from course_hub import names

ROLES_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/roles"
CUSTOM_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/custom"
DEPLOYMENT_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/deployment_id"
AGS_CLAIM = "https://purl.imsglobal.org/spec/lti-ags/claim/endpoint"
CUSTOM_PREFIX = "custom_"  # username_key "custom_login_id": the custom parameter login_id (ltiauthenticator's rule)
LIS = "http://purl.imsglobal.org/vocab/lis/v2/"
# A role ending in "*" matches every role that starts with what comes before it.
TA_ROLES = (LIS + "membership#Instructor", LIS + "membership/Instructor#*", LIS + "membership#TeachingAssistant",
            "Instructor", "TeachingAssistant")
STUDENT_ROLES = (LIS + "membership#Learner", LIS + "membership/Learner#*", "Learner")
TA, STUDENT = "ta", "student"
# course_format.course_file.MILESTONE_ID, bounded (a unit test checks that the two agree)
MILESTONE = re.compile(r"^[a-z][a-z0-9_]{0,63}$")
USERS_FILE = "lti-users.json"
NAME_MAX = 32  # course_hub.names.SLUG's bound
HASH_CHARS = 8  # of a long value's SHA-256, kept at the end of its cut name


class Refused(ValueError):
    """A launch the hub refuses; the message says why, for the student or TA who sees it."""


class Identity(NamedTuple):
    """One LMS user, as a launch names them: the platform and its user id (never changes)."""

    iss: str
    sub: str
    deployment_id: str = ""
    lineitems_url: str = ""


def identity_of(claims: Mapping[str, Any]) -> Identity:
    """The launching user's identity; Refused when the launch carries no user id (`sub`): an
    anonymous launch has nobody to give a workbench to."""
    sub = claims.get("sub")
    if not isinstance(sub, str) or not sub.strip():
        raise Refused("the launch names no LMS user (its id_token has no sub claim): the hub gives workbenches to "
                      "users it can tell apart; ask your TA to make the tool's launches carry the user's id")
    endpoint = claims.get(AGS_CLAIM)
    lineitems = endpoint.get("lineitems") if isinstance(endpoint, dict) else None
    return Identity(str(claims.get("iss") or ""), sub, str(claims.get(DEPLOYMENT_CLAIM) or ""),
                    lineitems if isinstance(lineitems, str) else "")


def claim_value(claims: Mapping[str, Any], key: str) -> str:
    """The value of claim `key` (`custom_NAME`: the custom parameter NAME); Refused when it is
    missing or empty: falling back to another claim would give the same person a second name."""
    where, name = (claims.get(CUSTOM_CLAIM), key[len(CUSTOM_PREFIX):]) if key.startswith(CUSTOM_PREFIX) else (claims, key)
    value = where.get(name) if isinstance(where, dict) else None
    if isinstance(value, int) and not isinstance(value, bool):
        value = str(value)
    if not isinstance(value, str) or not value.strip():
        raise Refused("the launch carries no %s for the user's hub name (%s is not set or empty): ask your TA to "
                      "check the LMS tool's custom parameters" % (
                          "custom parameter %r" % name if where is not claims else "claim %r" % key, key))
    return value


def hub_name(value: str) -> str:
    """The hub user name made of a claim's `value`: lower case; every run of characters other
    than letters, digits, `-` and `_` becomes `-`, and a run of `-`/`_` of two or more one `-`;
    no `-` or `_` at either end; `u` before a name that does not start with a letter; a name
    longer than 32 cut, its last characters a hash of the whole value (two long values sharing
    their start stay apart). The result always passes course_hub.names.slug. Refused when
    nothing of `value` is left."""
    word = re.sub(r"[^a-z0-9_-]+", "-", value.strip().lower())
    word = re.sub(r"[-_]{2,}", "-", word).strip("-_")
    if not word:
        raise Refused("the LMS's user name %r has no letter or digit the hub can use: ask your TA" % value[:64])
    if not word[0].isalpha():
        word = "u" + word
    if len(word) > NAME_MAX:
        digest = hashlib.sha256(value.encode("utf-8", "surrogatepass")).hexdigest()[:HASH_CHARS]
        word = word[:NAME_MAX - HASH_CHARS - 1].rstrip("-_") + "-" + digest
    names.slug(word)  # the rules above make it one; a bug would stop here, not name a folder
    return word


def _matches(role: str, patterns: Iterable[str]) -> bool:
    return any(role.startswith(p[:-1]) if p.endswith("*") else role == p for p in patterns)


def role_of(claims: Mapping[str, Any], ta_roles: Sequence[str] = TA_ROLES,
            student_roles: Sequence[str] = STUDENT_ROLES) -> str:
    """TA when any of the launch's roles is one of `ta_roles`, else student when one is of
    `student_roles`; Refused without the roles claim, or with none the hub knows."""
    roles = claims.get(ROLES_CLAIM)
    if roles is None:
        raise Refused("the launch carries no role (claim %s): the hub cannot tell a student from a TA; ask your TA "
                      "to check the LMS tool's settings" % ROLES_CLAIM)
    if isinstance(roles, str):
        roles = [roles]
    if not isinstance(roles, list) or not all(isinstance(r, str) for r in roles):
        raise Refused("the launch's roles claim is no list of roles: %r" % (roles,))
    if any(_matches(r, ta_roles) for r in roles):
        return TA
    if any(_matches(r, student_roles) for r in roles):
        return STUDENT
    raise Refused("the LMS gave this user the role(s) %s, none of which the hub knows (Learner for a student, "
                  "Instructor or TeachingAssistant for a TA)" % (", ".join(roles) or "(none)"))


def milestone_of(claims: Mapping[str, Any], parameter: str) -> Optional[str]:
    """The milestone the launch's custom parameter `parameter` names, or None when it names none;
    Refused when it is no milestone id (a letter, then lower-case letters, digits and `_`, at
    most 64)."""
    custom = claims.get(CUSTOM_CLAIM)
    value = custom.get(parameter) if isinstance(custom, dict) and parameter else None
    if value is None or value == "":
        return None
    if not isinstance(value, str) or not MILESTONE.match(value):
        raise Refused("the course link names the milestone %r, which is no milestone id (a letter, then lower-case "
                      "letters, digits and _): ask your TA to fix the link's custom parameter %s"
                      % (str(value)[:64], parameter))
    return value


class NameTaken(Refused):
    """Another LMS user, `holder`, holds the name (or its slug) already. The message names no
    one: the student who sees it learns nothing of the other person (the hub's log does)."""

    def __init__(self, message: str, holder: Identity) -> None:
        super().__init__(message)
        self.holder = holder


class Identities:
    """The hub's record of who holds each name: `<data_dir>/lti-users.json` (0600), hub name ->
    {iss, sub, deployment_id, lineitems_url}. Read and written at each launch under a lock, and
    replaced whole (a reader never sees half a file)."""

    def __init__(self, data_dir: str) -> None:
        self.path = os.path.join(data_dir, USERS_FILE)
        self._lock = threading.Lock()

    def read(self) -> Dict[str, Dict[str, str]]:
        try:
            with open(self.path, encoding="utf-8") as stream:
                data = json.load(stream)
        except FileNotFoundError:
            return {}
        except (OSError, ValueError) as err:
            raise Refused("the hub cannot read its record of LMS users (%s: %s): tell your TA" % (self.path, err)) from None
        if not isinstance(data, dict):
            raise Refused("the hub's record of LMS users (%s) is no JSON object: tell your TA" % self.path)
        return data

    def _write(self, data: Mapping[str, Mapping[str, str]]) -> None:
        folder = os.path.dirname(self.path)
        os.makedirs(folder, exist_ok=True)
        fd, temporary = tempfile.mkstemp(prefix=".lti-users.", dir=folder)
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as stream:
                json.dump(data, stream, indent=1, sort_keys=True)
            os.chmod(temporary, 0o600)
            os.replace(temporary, self.path)
        except BaseException:
            os.unlink(temporary)
            raise

    def claim(self, name: str, who: Identity) -> str:
        """The hub name of `who`: the one the record gives them already (a person keeps their
        name, folder and disk), else `name`, recorded as theirs. NameTaken when another
        identity holds `name` or a name with its slug."""
        with self._lock:
            data = self.read()
            for held, entry in data.items():
                if isinstance(entry, dict) and (entry.get("iss"), entry.get("sub")) == (who.iss, who.sub):
                    name = held
                    break
            else:
                word = names.slug(name)
                for held, entry in data.items():
                    if _slug_or_none(held) == word:
                        other = entry if isinstance(entry, dict) else {}
                        raise NameTaken("your LMS user name gives the hub name %s, which another LMS user has "
                                        "already (as %s): the hub never merges two people; ask your TA to give one "
                                        "of you another login" % (name, held),
                                        Identity(str(other.get("iss", "?")), str(other.get("sub", "?"))))
            previous = data.get(name) if isinstance(data.get(name), dict) else {}
            entry = {"iss": who.iss, "sub": who.sub, "deployment_id": who.deployment_id,
                     "lineitems_url": who.lineitems_url or str(previous.get("lineitems_url") or "")}
            if data.get(name) != entry:
                data[name] = entry
                self._write(data)
            return name


def _slug_or_none(name: str) -> Optional[str]:
    try:
        return names.slug(name)
    except ValueError:
        return None


class UsedOnce:
    """Values (nonces, states) each accepted once within `ttl_s`: a launch replayed with the
    same id_token and cookies is refused. Bounded: at most `limit` values are remembered, the
    oldest forgotten first (a launch older than `ttl_s` is refused by its iat anyway)."""

    def __init__(self, ttl_s: float, limit: int = 100_000, clock: Callable[[], float] = time.monotonic) -> None:
        self.ttl_s = ttl_s
        self.limit = limit
        self.clock = clock
        self._seen: "OrderedDict[str, float]" = OrderedDict()
        self._lock = threading.Lock()

    def first_use(self, value: str) -> bool:
        """True the first time `value` is seen within the window, False after."""
        now = self.clock()
        with self._lock:
            while self._seen and (next(iter(self._seen.values())) <= now or len(self._seen) >= self.limit):
                self._seen.popitem(last=False)
            if value in self._seen:
                return False
            self._seen[value] = now + self.ttl_s
            return True

    def __len__(self) -> int:
        return len(self._seen)
