"""What a launch tells the hub (course_hub.lms), without JupyterHub: the hub name made of any
claim (property-based: never a crash, always a name the hub's rules accept, two values apart
stay apart unless the rules make them one), the roles, the milestone, who holds each name, and
nonces used once."""
from __future__ import annotations

import json
import os
import stat

import pytest
from hypothesis import given, settings, strategies as st

from course_format.course_file import MILESTONE_ID
from course_hub import lms, names

LEARNER = lms.LIS + "membership#Learner"
ALICE = lms.Identity("https://lms.example.edu", "a-1", "1:ros", "https://lms.example.edu/items")
BOB = lms.Identity("https://lms.example.edu", "b-2", "1:ros")


@settings(max_examples=500, deadline=None)
@given(st.text(max_size=80))
def test_any_claim_gives_a_name_the_hubs_rules_accept_or_a_refusal(value):
    try:
        name = lms.hub_name(value)
    except lms.Refused as err:
        assert "no letter or digit" in str(err)
        assert not any(c.isascii() and c.isalnum() for c in value.lower())
        return
    assert names.slug(name) and len(name) <= 32 and name == name.lower()
    assert lms.hub_name(name) == name  # a hub name maps onto itself


@given(st.text(alphabet="abcdefghijklmnopqrstuvwxyz0123456789", min_size=33, max_size=60))
def test_long_values_sharing_their_start_stay_apart(tail):
    assert lms.hub_name("x" * 30 + tail) != lms.hub_name("x" * 30 + tail + "0")


@pytest.mark.parametrize("value, name", [
    ("alice", "alice"), ("Alice.Smith@Uni.EDU", "alice-smith-uni-edu"), ("jean_luc", "jean_luc"),
    ("a__b--c", "a-b-c"), ("  -Bob- ", "bob"), ("12345", "u12345"),
    # an LMS's UUID is 36 long: cut, the end a hash of the whole
    ("f81d4fae-7dec-11d0-a765-00a0c91e6bf6", "f81d4fae-7dec-11d0-a765-30a5154b"),
    ("0b1d4fae-7dec-11d0-a765-00a0c91e6bf6", "u0b1d4fae-7dec-11d0-a76-de659fc3"),
])
def test_the_name_rules(value, name):
    assert lms.hub_name(value) == name


def test_a_claim_for_the_name_is_the_configured_one_with_no_fallback():
    claims = {"sub": "s-1", lms.CUSTOM_CLAIM: {"login_id": "jdoe", "number": 42}}
    assert lms.claim_value(claims, "sub") == "s-1"
    assert lms.claim_value(claims, "custom_login_id") == "jdoe"
    assert lms.claim_value(claims, "custom_number") == "42"
    with pytest.raises(lms.Refused, match="no custom parameter 'email'"):
        lms.claim_value(claims, "custom_email")
    with pytest.raises(lms.Refused, match="no claim 'email'"):
        lms.claim_value(claims, "email")


@pytest.mark.parametrize("roles, role", [
    ([LEARNER], "student"), (["Learner"], "student"), ([lms.LIS + "membership/Learner#NonCreditLearner"], "student"),
    ([lms.LIS + "membership#Instructor"], "ta"), ([lms.LIS + "membership/Instructor#TeachingAssistant"], "ta"),
    ([LEARNER, lms.LIS + "membership/Instructor#TeachingAssistant"], "ta"), ("Instructor", "ta"),
])
def test_the_lms_role_decides_the_hubs(roles, role):
    assert lms.role_of({lms.ROLES_CLAIM: roles}) == role


def test_no_role_or_none_the_hub_knows_is_refused():
    with pytest.raises(lms.Refused, match="carries no role"):
        lms.role_of({})
    with pytest.raises(lms.Refused, match="none of which the hub knows"):
        lms.role_of({lms.ROLES_CLAIM: [lms.LIS + "institution/person#Instructor"]})  # another course's TA
    with pytest.raises(lms.Refused, match="no list of roles"):
        lms.role_of({lms.ROLES_CLAIM: {"Instructor": True}})
    assert lms.role_of({lms.ROLES_CLAIM: [lms.LIS + "institution/person#Instructor"]},
                       ta_roles=[lms.LIS + "institution/person#*"]) == "ta"  # a course that wants it says so


def test_a_milestone_is_checked_against_the_course_formats_ids():
    assert lms.MILESTONE.pattern.replace("{0,63}", "*") == MILESTONE_ID.pattern
    assert lms.milestone_of({lms.CUSTOM_CLAIM: {"milestone": "tf2_follow"}}, "milestone") == "tf2_follow"
    assert lms.milestone_of({lms.CUSTOM_CLAIM: {}}, "milestone") is None
    assert lms.milestone_of({}, "milestone") is None
    for bad in ("../x", "Chatter", "a b", "x" * 65, 7, "chatter.md"):
        with pytest.raises(lms.Refused, match="no milestone id"):
            lms.milestone_of({lms.CUSTOM_CLAIM: {"milestone": bad}}, "milestone")


def test_a_launch_without_a_user_id_is_refused():
    with pytest.raises(lms.Refused, match="no sub claim"):
        lms.identity_of({"iss": "x"})
    assert lms.identity_of({"iss": ALICE.iss, "sub": "a-1", lms.DEPLOYMENT_CLAIM: "1:ros",
                            lms.AGS_CLAIM: {"lineitems": ALICE.lineitems_url}}) == ALICE


def test_who_holds_each_name_one_person_one_name_never_merged(tmp_path):
    who = lms.Identities(str(tmp_path))
    assert who.claim("jean_luc", ALICE) == "jean_luc"
    with pytest.raises(lms.NameTaken, match="another LMS user has already") as taken:
        who.claim("jean-luc", BOB)  # one folder, one container: refused
    assert taken.value.holder[:2] == (ALICE.iss, ALICE.sub) and ALICE.sub not in str(taken.value)
    assert who.claim("jean-luc-2", ALICE) == "jean_luc"  # alice keeps hers when her claim changes
    assert who.claim("bob", BOB) == "bob"
    record = json.load(open(tmp_path / lms.USERS_FILE))
    assert record == {"jean_luc": {"iss": ALICE.iss, "sub": "a-1", "deployment_id": "1:ros",
                                   "lineitems_url": ALICE.lineitems_url},
                      "bob": {"iss": BOB.iss, "sub": "b-2", "deployment_id": "1:ros", "lineitems_url": ""}}
    assert stat.S_IMODE(os.stat(tmp_path / lms.USERS_FILE).st_mode) == 0o600
    assert [p for p in os.listdir(tmp_path) if p != lms.USERS_FILE] == []  # no temporary file left


def test_the_same_sub_of_another_platform_is_another_person(tmp_path):
    who = lms.Identities(str(tmp_path))
    who.claim("alice", ALICE)
    with pytest.raises(lms.NameTaken):
        who.claim("alice", ALICE._replace(iss="https://other.example.edu"))


def test_a_damaged_record_refuses_with_where_it_is(tmp_path):
    (tmp_path / lms.USERS_FILE).write_text("{not json")
    with pytest.raises(lms.Refused, match="cannot read its record of LMS users"):
        lms.Identities(str(tmp_path)).claim("alice", ALICE)


def test_a_nonce_is_good_once_within_its_window_and_memory_stays_bounded():
    now = [0.0]
    used = lms.UsedOnce(600, limit=3, clock=lambda: now[0])
    assert used.first_use("n1") and not used.first_use("n1")
    now[0] = 601.0
    assert used.first_use("n1")  # forgotten after the window (its token's iat refuses it by then)
    for value in ("a", "b", "c", "d"):
        assert used.first_use(value)
    assert len(used) <= 3
