"""Initial passwords for the class list's users, so that nobody can claim a classmate's account.

FirstUseAuthenticator lets the first person who logs in as `alice` choose alice's password. On a
hub whose address a class shares, anyone who knows a classmate's user name could claim it first,
and with it their files. So, when the hub starts, every listed user without a password gets an
initial one: its bcrypt hash goes into the authenticator's own password file (the dbm it reads,
in the format it writes: the user name's UTF-8 bytes -> `bcrypt.hashpw(password, gensalt())`),
and the password itself onto the hand-out sheet, `<data>/initial-passwords.csv` (root's, 0600),
which the instructor hands out. A student changes it at `/hub/auth/change-password`; a user who
already has a password (theirs, or an initial one) is never given another, except by a reset
(`make hub-password RESET=<user>`: a new one in the same step).
"""
from __future__ import annotations

import argparse
import csv
import os
import secrets
import sys
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from course_hub import classlist

SHEET_NAME = "initial-passwords.csv"
DBM_NAME = "passwords.dbm"  # FirstUseAuthenticator's dbm_path in the hub's data folder
SHEET_HEADER = ("username", "role", "initial_password")
# No look-alikes (0/o, 1/l/i): read off a sheet and typed by hand.
ALPHABET = "abcdefghjkmnpqrstuvwxyz23456789"
GROUPS, GROUP_LENGTH = 3, 4  # "kq7m-3tzp-x9aw": 31^12, about 2^59
DEFAULT_ROUNDS = 12  # bcrypt's cost, as FirstUseAuthenticator hashes: about 0.25 s a password here


def generate(choice: Callable[[str], str] = secrets.choice) -> str:
    """A new initial password: three groups of four characters, dash-joined."""
    return "-".join("".join(choice(ALPHABET) for _ in range(GROUP_LENGTH)) for _ in range(GROUPS))


def bcrypt_hash(password: str, rounds: int = DEFAULT_ROUNDS) -> bytes:
    """The hash FirstUseAuthenticator stores and checks (bcrypt, a new salt)."""
    import bcrypt  # the hub's venv has it (FirstUseAuthenticator's dependency)
    return bcrypt.hashpw(password.encode("utf8"), bcrypt.gensalt(rounds))


RIGHT, WRONG, TOO_SHORT = "right", "wrong", "too short"


def check_password(dbm_path: str, name: str, password: str, min_length: int = 0) -> str:
    """FirstUseAuthenticator's check, as a function that may run in any thread (course_hub.auth
    runs it beside the hub's event loop): RIGHT, WRONG, or TOO_SHORT (a first password under
    `min_length`; a first password long enough is stored, as the authenticator does)."""
    import bcrypt
    import dbm
    key = name.encode("utf8")
    with dbm.open(dbm_path, "c", 0o600) as db:
        stored = db.get(key)
        if stored is not None:
            return RIGHT if bcrypt.checkpw(password.encode("utf8"), stored) else WRONG
        if len(password) < min_length:
            return TOO_SHORT
        db[key] = bcrypt_hash(password)
        return RIGHT


def seed(dbm_path: str, users: classlist.ClassList, sheet_path: str,
         rounds: int = DEFAULT_ROUNDS, make: Callable[[], str] = generate) -> List[Tuple[str, str]]:
    """Give every user of `users` who has no password in `dbm_path` an initial one, and add a line
    for each to the sheet at `sheet_path`. The (user, password) pairs given, in class-list order."""
    import dbm  # the implementation FirstUseAuthenticator's dbm.open picks in the same interpreter
    with dbm.open(dbm_path, "c", 0o600) as db:
        without = [name for name in users.roles if db.get(name.encode("utf8")) is None]  # the list's order
    return _give(dbm_path, users, sheet_path, without, rounds, make)


def reset(dbm_path: str, users: classlist.ClassList, sheet_path: str, names: Sequence[str],
          rounds: int = DEFAULT_ROUNDS, make: Callable[[], str] = generate) -> List[Tuple[str, str]]:
    """A new initial password for each of `names` (listed users), in place of whatever password
    they had, added to the sheet: one step, so the name is never without a password (while the
    hub runs: the authenticator reads the file at every login). ValueError for a name off the list."""
    unknown = [name for name in names if name not in users.roles]
    if unknown:
        raise ValueError("not on the class list: %s" % ", ".join(unknown))
    return _give(dbm_path, users, sheet_path, names, rounds, make)


def _give(dbm_path: str, users: classlist.ClassList, sheet_path: str, names: Sequence[str],
          rounds: int, make: Callable[[], str]) -> List[Tuple[str, str]]:
    """A new password for each of `names`: its hash into the password file, a line on the sheet."""
    import dbm
    given = [(name, make()) for name in names]
    if not given:
        return given
    with dbm.open(dbm_path, "c", 0o600) as db:
        for name, password in given:
            db[name.encode("utf8")] = bcrypt_hash(password, rounds)
    _append(sheet_path, [(name, users.roles[name], password) for name, password in given])
    return given


def _append(sheet_path: str, rows: Sequence[Tuple[str, str, str]]) -> None:
    new = not os.path.exists(sheet_path)
    fd = os.open(sheet_path, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
    os.fchmod(fd, 0o600)
    with os.fdopen(fd, "a", newline="") as out:
        writer = csv.writer(out)
        if new:
            writer.writerow(SHEET_HEADER)
        writer.writerows(rows)


def read_sheet(sheet_path: str) -> Dict[str, str]:
    """user -> the last initial password the sheet gives them (a reset adds a newer line)."""
    found: Dict[str, str] = {}
    with open(sheet_path, newline="") as sheet:
        for row in csv.DictReader(sheet):
            found[row["username"]] = row["initial_password"]
    return found


def sheet_of(data_dir: str) -> str:
    """The hand-out sheet of the hub whose data folder is `data_dir`."""
    return os.path.join(data_dir, SHEET_NAME)


def dbm_of(data_dir: str) -> str:
    """FirstUseAuthenticator's password file of the hub whose data folder is `data_dir`."""
    return os.path.join(data_dir, DBM_NAME)


def handed_out(data_dir: str) -> Dict[str, str]:
    """user -> their initial password, off the sheet of the hub whose data folder is `data_dir`."""
    return read_sheet(sheet_of(data_dir))


def main(argv: Optional[Sequence[str]] = None) -> int:
    """`course-hub-passwords` (make hub-password RESET=alice): a new initial password for a user,
    while the hub runs or not; without --reset, the initial passwords the hub's start gives (users
    without one: on Kubernetes, the hub pod's init container runs this before the hub)."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("--data", required=True, help="the hub's data folder (make hub's HUB_DATA)")
    parser.add_argument("--class-list", required=True, help="the class list CSV (HUB_CLASS_LIST)")
    parser.add_argument("--reset", action="append", default=[], metavar="USER", help="give USER a new initial password")
    opts = parser.parse_args(argv)
    try:
        users = classlist.load(opts.class_list)
    except classlist.ClassListError as err:
        print("hub passwords: %s" % err, file=sys.stderr)
        return 2
    os.makedirs(opts.data, mode=0o700, exist_ok=True)
    dbm_path, sheet = dbm_of(opts.data), sheet_of(opts.data)
    if opts.reset:
        try:
            given = reset(dbm_path, users, sheet, opts.reset)
        except ValueError as err:
            print("hub passwords: %s" % err, file=sys.stderr)
            return 2
        for name, password in given:
            print("%s: new initial password %s (also on %s)" % (name, password, sheet))
        return 0
    print("hub passwords: %s" % summary(seed(dbm_path, users, sheet), sheet))
    return 0


def summary(given: Sequence[Tuple[str, str]], sheet_path: str) -> str:
    """What a seed gave, in a line (the passwords themselves are on the sheet only)."""
    return "%d new initial password(s)%s on %s" % (
        len(given), " (%s)" % ", ".join(name for name, _ in given) if given else "", sheet_path)
