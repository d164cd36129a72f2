"""One user, one place: every name of a user's things comes from course_hub.names, no two users
share any of them, and a class list that would make two share is refused."""
from __future__ import annotations

import dataclasses
import re

import pytest
from hypothesis import given, settings, strategies as st

from course_hub import classlist, names

LISTABLE = st.from_regex(r"\A[a-z](?:[a-z0-9]|[a-z0-9][_-](?=[a-z0-9])){0,15}\Z")
DNS_LABEL = re.compile(r"^[a-z](?:[a-z0-9-]{0,61}[a-z0-9])?$")


def test_names_with_dashes_keep_them_and_underscores_become_dashes():
    assert [names.places("/d", u).home for u in ("a-b", "a-2db", "jean_luc")] == [
        "/d/users/a-b", "/d/users/a-2db", "/d/users/jean-luc"]
    alice = names.places("/d", "alice")
    assert (alice.container, alice.network, alice.src, alice.grades, alice.disk_image) == (
        "course-hub-alice", "course-hub-net-alice", "/d/users/alice/src", "/d/users/alice/grades",
        "/d/disks/alice.img")
    assert names.subdomain_hook("jean_luc", "hub.example.org", "user") == "jean-luc.hub.example.org"
    assert names.subdomain_hook("x", "hub.example.org", "service") == "services.hub.example.org"


@pytest.mark.parametrize("bad", ["", "Alice", "a--b", "a_-b", "a-", "_a", "1a", "a b", "a/b", "a.b", "a" * 33])
def test_a_name_with_no_safe_place_is_refused(bad):
    with pytest.raises(ValueError, match="no safe name on the hub"):
        names.slug(bad)


@settings(max_examples=300, deadline=None)
@given(st.lists(LISTABLE, min_size=2, max_size=6, unique=True))
def test_users_a_class_list_accepts_together_share_no_place(users):
    text = "username\n" + "\n".join(users) + "\n"
    try:
        roster = classlist.parse(text)
    except classlist.ClassListError as err:
        assert "would share one folder" in str(err)  # the only refusal for names of this shape
        return
    taken = {}
    for user in roster.users:
        place = names.places("/data", user)
        assert DNS_LABEL.match(place.slug) and "--" not in place.slug
        for value in dataclasses.asdict(place).values():
            if value == user:
                continue
            assert taken.setdefault(value, user) == user, "%s and %s share %s" % (taken[value], user, value)
        assert taken.setdefault(place.subdomain("hub"), user) == user


def test_the_class_list_refuses_two_names_that_would_share_a_place_naming_both():
    with pytest.raises(classlist.ClassListError) as err:
        classlist.parse("username\njean-luc\nbob\njean_luc\n", "class.csv")
    assert "class.csv line 4: jean-luc and jean_luc would share one folder" in str(err.value)
    assert sorted(classlist.parse("username\na-b\na-2db\njean-luc\n").users) == ["a-2db", "a-b", "jean-luc"]
