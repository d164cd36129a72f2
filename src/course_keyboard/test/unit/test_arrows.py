"""The arrow table and what the arrows ask a robot to do."""
from course_keyboard.arrows import ESC, INTRODUCERS, NAMES_BY_FINAL, SEQUENCES
from course_keyboard.drive import arrow_velocity


def test_the_table_holds_the_four_arrows_as_csi_sequences():
    assert sorted(SEQUENCES) == ["down", "left", "right", "up"]
    for sequence in SEQUENCES.values():
        assert len(sequence) == 3 and sequence[0] == ESC and sequence[1] == INTRODUCERS[0]


def test_the_decoding_direction_is_the_table_read_backwards():
    assert {name: bytes([final]) for final, name in NAMES_BY_FINAL.items()} == {
        "up": b"A", "down": b"B", "right": b"C", "left": b"D"}


def test_arrows_drive_like_turtle_teleop_key():
    assert arrow_velocity("up", 2.0, 3.0) == (2.0, 0.0)
    assert arrow_velocity("down", 2.0, 3.0) == (-2.0, 0.0)
    assert arrow_velocity("left", 2.0, 3.0) == (0.0, 3.0)
    assert arrow_velocity("right", 2.0, 3.0) == (0.0, -3.0)
    assert arrow_velocity("x", 2.0, 3.0) is None
