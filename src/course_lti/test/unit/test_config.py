"""lti.yaml and the users file: a good one read, every mistake reported as FILE: FIELD: message."""
from __future__ import annotations

import pytest

from course_lti import config, users
from course_lti.config import ConfigError


def problems(path: str):
    with pytest.raises(ConfigError) as caught:
        config.load(path)
    return caught.value.problems


def test_a_good_file_is_read_with_its_defaults(write_config):
    loaded = config.load(write_config())
    assert (loaded.issuer, loaded.client_id, loaded.kid, loaded.grades) == ("https://lms.test", "tool", "k1",
                                                                           config.PER_MILESTONE)
    assert loaded.assertion_audience == "https://lms.test/token"  # no audience: the token URL
    assert loaded.private_key_pem.startswith(b"-----BEGIN PRIVATE KEY")
    assert (loaded.retries, loaded.retry_seconds) == (config.DEFAULT_RETRIES, config.DEFAULT_RETRY_SECONDS)


def test_every_mistake_is_reported_at_once_with_file_and_field(write_config):
    path = write_config(client_id=None, token_url="http://lms.example.edu/token", private_key="nowhere.pem",
                        grades="per_lab", colour="blue", retries=-1)
    found = problems(path)
    assert all(p.startswith(path + ": ") for p in found), found
    fields = sorted(p.split(": ")[1] for p in found)
    assert fields == ["client_id", "colour", "grades", "private_key", "retries", "token_url"], found
    assert any("plain http sends the token in clear" in p for p in found)


def test_http_is_allowed_on_loopback_only(write_config):
    assert config.load(write_config(token_url="http://127.0.0.1:8080/token")).token_url.startswith("http://")
    assert config.url_problem("http://[::1]:9/x") == ""
    assert "use https" in config.url_problem("http://10.0.0.1/token")
    assert "not an http(s) URL" in config.url_problem("ftp://lms/token")


def test_a_key_that_is_no_rsa_private_key_is_refused(write_config, tmp_path, key_pair):
    (tmp_path / "public.pem").write_bytes(key_pair[1])
    assert any("no unencrypted PEM private key" in p for p in problems(write_config(private_key="public.pem")))


def test_assignments_need_per_assignment_and_known_milestones(write_config):
    found = problems(write_config(assignments={"lab2": ["chatter"]}))
    assert any(p.endswith("assignments: given, but grades is per_milestone: write grades: per_assignment")
               for p in found), found
    loaded = config.load(write_config(grades="per_assignment", assignments={"lab2": ["chatter", "nope"]}))
    with pytest.raises(ConfigError) as caught:
        config.line_item_groups(loaded, "course", ["chatter", "checkpoint1"])
    assert "assignments.lab2: no such milestone in the course: nope" in str(caught.value)


def test_line_item_groups_per_milestone_and_per_assignment(write_config):
    per_milestone = config.load(write_config())
    assert config.line_item_groups(per_milestone, "course", ["a", "b"]) == {"a": ("a",), "b": ("b",)}
    whole = config.load(write_config(grades="per_assignment"))
    assert config.line_item_groups(whole, "course", ["a", "b"]) == {"course": ("a", "b")}


def test_the_hubs_users_file_and_a_csv(tmp_path):
    hub = tmp_path / "lti-users.json"
    hub.write_text('{"alice": {"iss": "https://lms.test", "sub": "u-1", "deployment_id": "1"}}')
    assert users.load(str(hub)) == {"alice": users.LmsUser("u-1", "https://lms.test", "1", "")}
    table = tmp_path / "users.csv"
    table.write_text("student,user_id\nbob,u-2\n")
    assert users.load(str(table)) == {"bob": users.LmsUser("u-2")}


def test_a_users_file_missing_or_malformed_says_what_it_should_hold(tmp_path):
    with pytest.raises(ConfigError) as caught:
        users.load(str(tmp_path / "lti-users.json"))
    assert "missing: it maps each student to their LMS user id" in str(caught.value)
    assert users.load(str(tmp_path / "lti-users.json"), missing_ok=True) == {}
    bad = tmp_path / "users.csv"
    bad.write_text("name,id\nbob,u-2\n")
    with pytest.raises(ConfigError, match="needs the columns student,user_id"):
        users.load(str(bad))
    wrong = tmp_path / "u.json"
    wrong.write_text('{"alice": {"iss": "x"}}')
    with pytest.raises(ConfigError, match="alice: must be an object with a non-empty string sub"):
        users.load(str(wrong))
