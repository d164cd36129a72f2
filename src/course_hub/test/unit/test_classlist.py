"""The class list: who logs in, who is a TA; a bad line refused with its line number."""
from __future__ import annotations

import pytest

from course_hub import classlist


def test_students_and_tas_are_read_and_other_columns_ignored():
    given = classlist.parse("username,role,name\nalice,student,Alice A.\ntom,TA,Tom\nbob,,Bob\n\n# left\n")
    assert given.users == {"alice", "tom", "bob"}
    assert given.admins == {"tom"}
    assert given.students == ["alice", "bob"]


def test_the_role_column_may_be_missing_and_a_bom_is_no_part_of_the_header():
    assert classlist.parse("\ufeffusername\ncarol\n").students == ["carol"]


@pytest.mark.parametrize("text, words", [
    ("name,role\nalice,student\n", "line 1: the header must name a `username`"),
    ("username,role\nAlice,student\n", "line 2: 'Alice' is no user name"),
    ("username,role\nalice,student\nbob;x,student\n", "line 3: 'bob;x'"),
    ("username,role\nalice,teacher\n", "line 2: role 'teacher' of alice must be one of student, ta"),
    ("username,role\nalice,student\nalice,ta\n", "line 3: alice is listed twice"),
    ("username,role\n", "no user in it"),
    ("username\n" + "a" * 33 + "\n", "at most 32"),
])
def test_a_bad_class_list_is_refused_saying_where(text, words):
    with pytest.raises(classlist.ClassListError) as err:
        classlist.parse(text, "class.csv")
    assert words in str(err.value) and "class.csv" in str(err.value)


def test_a_missing_file_is_a_clear_error(tmp_path):
    with pytest.raises(classlist.ClassListError, match="cannot read the class list .*nope.csv"):
        classlist.load(str(tmp_path / "nope.csv"))


def test_the_example_class_list_loads():
    import os
    here = os.path.dirname(os.path.abspath(__file__))
    example = os.path.join(here, "..", "..", "..", "..", "deploy", "jupyterhub", "classlist.csv")
    assert classlist.load(example).admins
