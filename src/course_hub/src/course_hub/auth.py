"""The course's login: FirstUseAuthenticator's passwords, checked off the hub's event loop, with
failed logins limited per name and per address.

FirstUseAuthenticator checks a password with bcrypt (cost 12, about 0.25 s here) inside the hub's
single event loop: while a few wrong logins a second arrived, every page, spawn and API call of
the hub waited behind them. This authenticator reads the same password file in the same format
(course_hub.passwords seeds it with the initial passwords), and:

- hashes in a small thread pool of its own, so the loop keeps answering;
- refuses a name or an address with too many recent failures (course_hub.logins) before hashing,
  saying on the login page when to try again;
- knows only the hub's existing users (`create_users` off: the class list's, which JupyterHub
  adds at its start), and with `allow_existing_users` off a user taken off the class list can no
  longer log in.

NativeAuthenticator has a failed-login limit too, but counts per name only, hashes on the event
loop as well, and keeps passwords in the hub's database, where the initial passwords would have
to be written instead; so the course keeps FirstUseAuthenticator's file and adds both here.

Imported by JupyterHub (the hub's venv), never by the course's nodes or unit tests: the logic is
in course_hub.logins and course_hub.passwords.check_password, which need no JupyterHub.
"""
from __future__ import annotations

import asyncio
import math
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Dict, Optional

from firstuseauthenticator import FirstUseAuthenticator
from traitlets import Float, Integer, default

from course_hub.logins import FailedLogins
from course_hub.passwords import RIGHT, TOO_SHORT, check_password


class CourseAuthenticator(FirstUseAuthenticator):
    """FirstUseAuthenticator, off the event loop and with failed logins limited."""

    failures_per_name = Integer(5, config=True, help="failed logins of one name within the window before it "
                                                     "is refused until the oldest ages out")
    failures_per_address = Integer(50, config=True, help="the same for one address (a class behind one NAT)")
    failure_window_s = Float(300.0, config=True, help="the window, in seconds")
    hash_threads = Integer(2, config=True, help="threads checking passwords (bcrypt) beside the event loop")

    @default("create_users")
    def _no_new_users(self) -> bool:
        return False

    @default("allow_existing_users")
    def _only_the_listed(self) -> bool:
        return False

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.failures = FailedLogins(self.failures_per_name, self.failures_per_address, self.failure_window_s)
        self._pool = ThreadPoolExecutor(self.hash_threads, thread_name_prefix="course-login")

    async def authenticate(self, handler: Any, data: Dict[str, str]) -> Optional[str]:
        name = self.normalize_username(data.get("username", ""))
        password = data.get("password", "")
        address = handler.request.remote_ip or "?"
        refused = self.failures.refusal(name, address)
        if refused:
            what, wait = refused
            handler.custom_login_error = "Too many failed logins %s: try again in %d s." % (
                "for this name" if what == "name" else "from your address", max(1, math.ceil(wait)))
            self.log.warning("login of %s from %s refused: too many failed logins per %s", name, address, what)
            return None
        if not self._user_exists(name):
            self.failures.failed(None, address)
            return None
        outcome = await asyncio.get_running_loop().run_in_executor(
            self._pool, check_password, self.dbm_path, name, password, self.min_password_length)
        if outcome == RIGHT:
            self.failures.succeeded(name)
            return name
        if outcome == TOO_SHORT:
            handler.custom_login_error = ("Password too short! Please choose a password at least %d characters "
                                          "long." % self.min_password_length)
        self.failures.failed(name, address)
        return None
