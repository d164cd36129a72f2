"""causes: one vocabulary of failure causes, a sentence that carries its key, and the keys a check
records in its artifacts folder for the grader."""
import json

import pytest

from course_format import causes


def test_every_cause_has_one_key_and_words():
    keys = [c.key for c in causes.CAUSES]
    assert len(keys) == len(set(keys)) == len(causes.BY_KEY)
    assert all(c.label for c in causes.CAUSES)
    assert {causes.CHECK_FAILED, causes.BUILD_FAILED, "exited_early", "node_exited"} <= set(keys)


def test_a_finding_is_its_sentence_and_carries_its_key():
    made = causes.finding("silent", "talker publishes nothing on /chatter")
    assert made == "talker publishes nothing on /chatter" and isinstance(made, str)
    assert causes.of(made) == "silent" and causes.of(made + " (more)") == ""  # a str built from it carries none
    assert causes.of("a plain sentence", "check_failed") == "check_failed"
    assert causes.Finding("no key given").cause == causes.CHECK_FAILED


def test_an_unknown_key_fails_at_once():
    with pytest.raises(ValueError, match="unknown cause 'slient'"):
        causes.finding("slient", "typo")


def test_a_label_is_the_words_or_the_key_itself():
    assert causes.label("exited_early") == "exited before doing what was asked"
    assert causes.label("from_a_later_version") == "from_a_later_version"


def test_exited_says_which():
    assert (causes.exited(True), causes.exited(False)) == ("node_exited", "exited_early")


def test_recorded_keys_come_back_in_order_and_unknown_ones_are_dropped(tmp_path):
    assert causes.recorded(str(tmp_path)) == []
    causes.record(str(tmp_path), "silent")
    causes.record(str(tmp_path), "wrong_rate")
    assert causes.recorded(str(tmp_path)) == ["silent", "wrong_rate"]
    (tmp_path / causes.RECORD_FILE).write_text(json.dumps(["silent", "no_such_cause", 3]))
    assert causes.recorded(str(tmp_path)) == ["silent"]
    for bad in ("not json", json.dumps({"silent": 1})):
        (tmp_path / causes.RECORD_FILE).write_text(bad)
        assert causes.recorded(str(tmp_path)) == []
