"""Failed logins limited per name and per address (course_hub.logins), on a clock of the test's."""
from __future__ import annotations

import pytest
from hypothesis import given, settings, strategies as st

from course_hub.logins import FailedLogins


class Clock:
    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


def test_a_name_is_refused_after_its_failures_until_the_oldest_ages_out():
    clock = Clock()
    limit = FailedLogins(per_name=3, per_address=100, window_s=60, clock=clock)
    for _ in range(3):
        assert limit.refusal("alice", "10.0.0.1") is None
        limit.failed("alice", "10.0.0.1")
        clock.now += 10
    what, wait = limit.refusal("alice", "10.0.0.9")  # from any address
    assert what == "name" and wait == pytest.approx(30)
    assert limit.refusal("bob", "10.0.0.1") is None  # others may log in from the same address
    clock.now += 30
    assert limit.refusal("alice", "10.0.0.1") is None


def test_an_address_is_refused_for_every_name_and_unknown_names_count_against_it():
    clock = Clock()
    limit = FailedLogins(per_name=3, per_address=4, window_s=60, clock=clock)
    for guess in ("root", "admin", "mallory", "eve"):
        limit.failed(None, "203.0.113.5")
    assert limit.refusal("alice", "203.0.113.5")[0] == "address"
    assert limit.refusal("alice", "10.0.0.1") is None


def test_a_success_forgets_the_names_failures_not_the_addresss():
    limit = FailedLogins(per_name=2, per_address=3, window_s=60, clock=Clock())
    limit.failed("alice", "a")
    limit.failed("alice", "a")
    assert limit.refusal("alice", "b")[0] == "name"
    limit.succeeded("alice")
    assert limit.refusal("alice", "b") is None
    limit.failed("bob", "a")
    assert limit.refusal("carol", "a")[0] == "address"


def test_bad_limits_are_refused():
    with pytest.raises(ValueError):
        FailedLogins(per_name=0)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["alice", "bob", None]), st.sampled_from(["a", "b", "c"]),
                          st.floats(min_value=0, max_value=40), st.booleans()), max_size=80))
def test_never_more_tries_than_the_bounds_within_a_window_and_memory_stays_bounded(events):
    clock = Clock()
    limit = FailedLogins(per_name=3, per_address=5, window_s=60, max_keys=4, clock=clock)
    tried = []  # (time, name, address) of every failed try that was let through
    for name, address, step, succeeds in events:
        clock.now += step
        if limit.refusal(name or "nobody", address) is not None:
            continue
        if succeeds and name:
            limit.succeeded(name)
            tried = [t for t in tried if t[1] != name]
            continue
        limit.failed(name, address)
        tried.append((clock.now, name, address))
        recent = [t for t in tried if t[0] > clock.now - 60]
        if name:
            assert sum(1 for t in recent if t[1] == name) <= 3  # a 4th is never let through
        assert limit.addresses() <= 4
