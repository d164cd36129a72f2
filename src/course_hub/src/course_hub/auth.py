"""CourseAuthenticator: the course's login, a JupyterHub authenticator configured by traits:

    c.JupyterHub.authenticator_class = "course_hub.auth.CourseAuthenticator"   # or its entry point, "course"
    c.CourseAuthenticator.class_list = "/etc/ros-course/classlist.csv"
    c.CourseAuthenticator.data_dir = "/var/lib/ros-course-hub"

- **Accounts from the class list** (course_hub.classlist): its users are the hub's allowed users
  and nobody else, its TAs the hub's admins (the defaults of `allowed_users` and `admin_users`);
  with `allow_existing_users` off, a user taken off the list can no longer log in, whatever the
  hub's database remembers; `create_users` off: the authenticator knows only the hub's existing
  users (the class list's, which JupyterHub adds at its start).
- **FirstUseAuthenticator's passwords**, in its file `<data_dir>/passwords.dbm` and its format, in
  which every listed user has an initial password before anyone can log in (course_hub.passwords:
  the hand-out sheet `<data_dir>/initial-passwords.csv`). Giving them is a step of the hub's start
  (`course-hub`, course_hub.runner; `course-hub-passwords` on Kubernetes), not of loading this
  class: its configuration sets traits and nothing else.
- **Checked off the event loop:** FirstUseAuthenticator checks a password with bcrypt (cost 12,
  about 0.25 s here) inside the hub's single event loop: while a few wrong logins a second
  arrived, every page, spawn and API call of the hub waited behind them. This one hashes in a
  small thread pool of its own, so the loop keeps answering;
- **Failed logins limited** per name and per address (course_hub.logins), refused before hashing,
  saying on the login page when to try again.

NativeAuthenticator has a failed-login limit too, but counts per name only, hashes on the event
loop as well, and keeps passwords in the hub's database, where the initial passwords would have
to be written instead; so the course keeps FirstUseAuthenticator's file and adds both here.

Imported by JupyterHub in the hub's venv; its logic is in course_hub.logins and
course_hub.passwords.check_password, which the unit tests run without JupyterHub.
"""
from __future__ import annotations

import asyncio
import math
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Dict, Optional, Set

from firstuseauthenticator import FirstUseAuthenticator
from traitlets import Float, Integer, Unicode, default

from course_hub import classlist, defaults, passwords
from course_hub.logins import FailedLogins
from course_hub.passwords import RIGHT, TOO_SHORT, check_password


class CourseAuthenticator(FirstUseAuthenticator):
    """FirstUseAuthenticator with the class list's accounts, off the event loop and with failed
    logins limited (module docstring)."""

    class_list = Unicode("", help="""The class list, a CSV of username,role[,name] (role student or
        ta; course_hub.classlist): its users may log in, its TAs are the hub's admins, and each
        gets an initial password at the hub's start. A bad line stops the hub with its line
        number.""").tag(config=True)
    data_dir = Unicode(defaults.DATA_DIR, help="""The hub's data folder: the password file
        (passwords.dbm, FirstUseAuthenticator's dbm_path) and the hand-out sheet of initial
        passwords (initial-passwords.csv) are there.""").tag(config=True)

    failures_per_name = Integer(5, config=True, help="failed logins of one name within the window before it "
                                                     "is refused until the oldest ages out")
    failures_per_address = Integer(50, config=True, help="the same for one address (a class behind one NAT)")
    failure_window_s = Float(300.0, config=True, help="the window, in seconds")
    hash_threads = Integer(2, config=True, help="threads checking passwords (bcrypt) beside the event loop")

    _roster: Optional[classlist.ClassList] = None

    @property
    def roster(self) -> classlist.ClassList:
        """The class list, read once (ClassListError for a bad line, ValueError when unset)."""
        if self._roster is None:
            if not self.class_list:
                raise ValueError("CourseAuthenticator.class_list is not set: the class list's CSV, whose "
                                 "users may log in (docs/hub.md)")
            self._roster = classlist.load(self.class_list)
        return self._roster

    @property
    def sheet(self) -> str:
        """The hand-out sheet of initial passwords."""
        return passwords.sheet_of(self.data_dir)

    @default("allowed_users")
    def _the_class_list(self) -> Set[str]:
        return set(self.roster.users)

    @default("admin_users")
    def _its_tas(self) -> Set[str]:
        return set(self.roster.admins)

    @default("dbm_path")
    def _in_the_data_folder(self) -> str:
        return passwords.dbm_of(self.data_dir)

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
