"""Initial passwords: every listed user gets one at the hub's start, in FirstUseAuthenticator's own
password file (real dbm, real bcrypt), and once only; the sheet that hands them out is root's."""
from __future__ import annotations

import dbm
import os
import random
import stat

import bcrypt
import pytest
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


def test_a_reset_replaces_the_password_at_once_and_refuses_a_name_off_the_list(tmp_path):
    db, sheet, first = seeded(tmp_path)
    ((name, new),) = passwords.reset(db, CLASS, sheet, ["alice"], rounds=4)
    assert name == "alice" and new != dict(first)["alice"]
    with dbm.open(db, "r") as stored:
        assert bcrypt.checkpw(new.encode(), stored[b"alice"])
        assert not bcrypt.checkpw(dict(first)["alice"].encode(), stored[b"alice"])
    assert passwords.read_sheet(sheet)["alice"] == new
    with pytest.raises(ValueError, match="mallory"):
        passwords.reset(db, CLASS, sheet, ["mallory"], rounds=4)


def test_the_command_seeds_then_resets_and_says_so(tmp_path, capsys):
    roster = tmp_path / "class.csv"
    roster.write_text("username,role\ntom,ta\nalice\n")
    data = tmp_path / "data"
    assert passwords.main(["--data", str(data), "--class-list", str(roster)]) == 0
    assert "2 new initial password(s) (tom, alice)" in capsys.readouterr().out
    assert passwords.main(["--data", str(data), "--class-list", str(roster), "--reset", "alice"]) == 0
    said = capsys.readouterr().out
    assert said.startswith("alice: new initial password ") and passwords.read_sheet(passwords.sheet_of(str(data)))["alice"] in said
    assert passwords.main(["--data", str(data), "--class-list", str(roster), "--reset", "bob"]) == 2
    assert "not on the class list: bob" in capsys.readouterr().err


def test_the_check_run_beside_the_event_loop_accepts_the_sheets_password_and_nothing_else(tmp_path):
    users = classlist.parse("username\nalice\n")
    dbm_path, sheet = str(tmp_path / "passwords.dbm"), str(tmp_path / "sheet.csv")
    ((_, given_password),) = passwords.seed(dbm_path, users, sheet, rounds=4)
    assert passwords.check_password(dbm_path, "alice", given_password) == passwords.RIGHT
    assert passwords.check_password(dbm_path, "alice", given_password + "x") == passwords.WRONG
    # a name without a password: the first one is kept (FirstUseAuthenticator's rule), if long enough
    assert passwords.check_password(dbm_path, "bob", "abc", min_length=7) == passwords.TOO_SHORT
    assert passwords.check_password(dbm_path, "bob", "long-enough", min_length=7) == passwords.RIGHT
    assert passwords.check_password(dbm_path, "bob", "another-one") == passwords.WRONG
