"""course_web.outbox: bounded lanes, throttling, replies first, round-robin between topics."""
from __future__ import annotations

from course_web.outbox import DEFAULT_QUEUE_LENGTH, MAX_QUEUE_LENGTH, Outbox, lane_size


def drain(outbox, now=0.0):
    out = []
    while (payload := outbox.take(now)) is not None:
        out.append(payload)
    return out


def test_a_full_lane_drops_its_oldest_and_counts_it():
    outbox = Outbox()
    outbox.open_lane("pose", queue_length=3)
    for n in range(10):
        outbox.put("pose", n)
    assert drain(outbox) == [7, 8, 9]
    assert outbox.dropped() == {"pose": 7}


def test_queue_length_zero_is_still_bounded():
    assert lane_size(0) == DEFAULT_QUEUE_LENGTH
    assert lane_size(10 ** 9) == MAX_QUEUE_LENGTH


def test_replies_go_first_and_topics_take_turns():
    outbox = Outbox()
    outbox.open_lane("a")
    outbox.open_lane("b")
    for n in range(3):
        outbox.put("a", "a%d" % n)
    outbox.put("b", "b0")
    outbox.reply("status")
    assert drain(outbox) == ["status", "a0", "b0", "a1", "a2"]


def test_throttle_rate_spaces_a_lanes_messages():
    outbox = Outbox()
    outbox.open_lane("image", queue_length=1, throttle_ms=100)
    outbox.put("image", "f1")
    assert outbox.take(10.0) == "f1"
    outbox.put("image", "f2")
    outbox.put("image", "f3")
    assert outbox.take(10.05) is None
    assert 0.04 < outbox.next_due(10.05) <= 0.05
    assert outbox.take(10.1) == "f3"  # the newest: queue_length 1
    assert outbox.next_due(10.1) is None


def test_a_closed_lane_refuses_late_messages():
    outbox = Outbox()
    outbox.open_lane("a")
    outbox.close_lane("a")
    assert outbox.put("a", "late") is False
    assert drain(outbox) == []


def test_only_a_message_into_an_empty_lane_wakes_the_sender():
    outbox = Outbox()
    outbox.open_lane("pose", queue_length=1, throttle_ms=50)
    assert outbox.put("pose", "p1") is True  # the sender may be asleep with no deadline
    assert outbox.take(10.0) == "p1"
    assert outbox.put("pose", "p2") is True
    assert outbox.put("pose", "p3") is False  # the sender sleeps until p2's slot, which p3 now takes
    assert outbox.take(10.01) is None and outbox.next_due(10.01) > 0
    assert outbox.take(10.05) == "p3"
