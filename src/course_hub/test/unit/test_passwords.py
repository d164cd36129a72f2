"""Initial passwords: every listed user gets one at the hub's start, in FirstUseAuthenticator's own
password file (real dbm, real bcrypt), and once only; the sheet that hands them out is root's."""
from __future__ import annotations

import dbm
import os
import random
import stat

import bcrypt
from hypothesis import given, strategies as st

from course_hub import classlist, passwords

CLASS = classlist.parse("username,role\ntom,ta\nalice,student\nbob,student\n")


def seeded(tmp_path, users=CLASS):
    db, sheet = str(tmp_path / "passwords.dbm"), passwords.sheet_of(str(tmp_path))
    return db, sheet, passwords.seed(db, users, sheet, rounds=4)  # bcrypt's cheapest cost: the same format


def test_every_listed_user_gets_an_initial_password_the_authenticator_accepts(tmp_path):
    db, sheet, given_now = seeded(tmp_path)
    assert [name for name, _ in given_now] == ["tom", "alice", "bob"]  # the class list's order
    with dbm.open(db, "r") as stored:
        for name, password in given_now:
            hashed = stored[name.encode("utf8")]
            # what FirstUseAuthenticator.authenticate does with a stored hash
            assert bcrypt.hashpw(password.encode("utf8"), hashed) == hashed
            assert bcrypt.hashpw(b"not-" + password.encode("utf8"), hashed) != hashed
    assert passwords.read_sheet(sheet) == dict(given_now)
    assert stat.S_IMODE(os.stat(sheet).st_mode) == 0o600
    with open(sheet) as f:
        assert f.readline().strip() == "username,role,initial_password"
        assert f.readline().startswith("tom,ta,")


def test_a_user_who_has_a_password_is_never_given_another(tmp_path):
    db, sheet, first = seeded(tmp_path)
    with dbm.open(db, "w") as stored:  # alice changed hers (/hub/auth/change-password)
        stored[b"alice"] = bcrypt.hashpw(b"alices-own-choice", bcrypt.gensalt(4))
    again = passwords.seed(db, classlist.parse("username\nalice\nbob\ncarol\n"), sheet, rounds=4)
    assert again and [name for name, _ in again] == ["carol"]  # a late addition to the list
    with dbm.open(db, "r") as stored:
        assert bcrypt.checkpw(b"alices-own-choice", stored[b"alice"])
    sheet_now = passwords.read_sheet(sheet)
    assert sheet_now["bob"] == dict(first)["bob"] and sheet_now["carol"] == dict(again)["carol"]


def test_a_reset_user_gets_a_new_password_on_a_new_line(tmp_path):
    db, sheet, first = seeded(tmp_path)
    with dbm.open(db, "w") as stored:
        del stored[b"bob"]  # an admin's reset: the entry deleted
    (again,) = passwords.seed(db, CLASS, sheet, rounds=4)
    assert again[0] == "bob" and again[1] != dict(first)["bob"]
    assert passwords.read_sheet(sheet)["bob"] == again[1]


@given(st.integers(min_value=0, max_value=2 ** 32))
def test_passwords_are_three_groups_of_four_without_look_alikes(seed):
    made = passwords.generate(random.Random(seed).choice)
    groups = made.split("-")
    assert [len(g) for g in groups] == [4, 4, 4]
    assert not set("".join(groups)) - set(passwords.ALPHABET)
    assert not set("0o1li") & set(passwords.ALPHABET)
