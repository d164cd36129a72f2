"""Which isolation this machine gives student code, decided once per grading and reported in
every verdict (never silently weaker):

- `full`: the grader is root: student code runs as the unprivileged sandbox user, in its own
  user, PID, mount, IPC and UTS namespaces (bubblewrap), with the system read-only and the
  grader's outputs and other students' files hidden.
- `namespaces`: the grader is an ordinary user: the same namespaces, without a user switch.
- `user`: root where namespaces are refused (a Docker container without CAP_SYS_ADMIN, as on
  Gradescope): only the user switch, file permissions and the limits.
- `none`: an ordinary user where namespaces are refused: only the limits.

`COURSE_SANDBOX_LEVEL` may ask for a weaker level than the machine gives (to test the degraded
modes here); it can never ask for a stronger one.
"""
from __future__ import annotations

import functools
import os
import pwd
import subprocess
from typing import Dict, List, Optional

LEVEL_VAR = "COURSE_SANDBOX_LEVEL"
FULL, NAMESPACES, USER, NONE = "full", "namespaces", "user", "none"
ORDER = [NONE, USER, NAMESPACES, FULL]

DESCRIPTIONS: Dict[str, str] = {
    FULL: "full: student code ran as the user {user} in its own PID, mount and user namespaces, "
          "with the system and the course read-only and other students' files hidden",
    NAMESPACES: "namespaces: student code ran in its own PID, mount and user namespaces, with the "
                "system and the course read-only and other students' files hidden (no user switch: "
                "{cause})",
    USER: "user only: {cause}, so student code ran as the user {user} with file permissions and limits "
          "alone (it could see other processes)",
    NONE: "none: {cause}, so student code ran with the grader's rights and limits alone",
}
# Why a level is weaker than full, when the machine decided it.
CAUSES: Dict[str, str] = {
    NAMESPACES: "the grader is not root",
    USER: "this machine refuses namespaces",
    NONE: "this machine refuses namespaces and the grader is not root",
}


def uses_namespaces(level: str) -> bool:
    return level in (FULL, NAMESPACES)


def switches_user(level: str) -> bool:
    return level in (FULL, USER)


def describe(level: str, user: str, environ: Optional[Dict[str, str]] = None) -> str:
    """The sentence every verdict carries: the level, what it means, and why it is weaker than
    full (the machine, or $COURSE_SANDBOX_LEVEL asking for it)."""
    environ = os.environ if environ is None else environ
    cause = CAUSES.get(level, "")
    if environ.get(LEVEL_VAR) == level:
        cause = "%s=%s asked for it" % (LEVEL_VAR, level)
    return DESCRIPTIONS.get(level, level).format(user=user, cause=cause)


def weaker(a: str, b: str) -> str:
    return a if ORDER.index(a) < ORDER.index(b) else b


def user_exists(user: str) -> bool:
    try:
        pwd.getpwnam(user)
        return True
    except KeyError:
        return False


def probe_command(root: bool, user: str) -> List[str]:
    """The smallest sandbox: new user and PID namespaces, as the sandbox user when root."""
    prefix = ["setpriv", "--reuid", user, "--regid", user, "--clear-groups", "--"] if root else []
    return prefix + ["bwrap", "--unshare-user", "--unshare-pid", "--die-with-parent", "--ro-bind", "/", "/",
                     "--proc", "/proc", "--", "true"]


@functools.lru_cache(maxsize=4)
def namespaces_work(root: bool, user: str) -> bool:
    try:
        return subprocess.run(probe_command(root, user), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, timeout=20).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


class Unavailable(RuntimeError):
    """The grader is root but the sandbox user does not exist: it will not run students as root."""


def detect(user: str, environ: Optional[Dict[str, str]] = None) -> str:
    """The strongest level this machine gives (weakened by $COURSE_SANDBOX_LEVEL if set)."""
    environ = os.environ if environ is None else environ
    root = os.geteuid() == 0
    if root and not user_exists(user):
        raise Unavailable("the sandbox user %r does not exist: run `make deps` (setup/install.sh creates it) "
                          "before grading as root" % user)
    if namespaces_work(root, user):
        level = FULL if root else NAMESPACES
    else:
        level = USER if root else NONE
    asked = environ.get(LEVEL_VAR)
    if asked in ORDER:
        level = weaker(asked, level)
        if not root and level == USER:
            level = NONE
    return level
