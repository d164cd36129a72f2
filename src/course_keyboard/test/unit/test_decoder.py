"""KeyDecoder: arrows in both cursor modes, split reads, unknown escape sequences."""
from course_keyboard.arrows import SEQUENCES
from course_keyboard.decoder import KeyDecoder


def test_arrow_sequences_decode():
    assert KeyDecoder().feed(b"\x1b[A\x1b[B\x1b[C\x1b[Dq") == ["up", "down", "right", "left", "q"]


def test_application_mode_arrows():
    assert KeyDecoder().feed(b"\x1bOA") == ["up"]
    assert KeyDecoder().feed(b"\x1bOB\x1bOC\x1bOD") == ["down", "right", "left"]


def test_every_sequence_of_the_table_decodes_to_its_name():
    for name, sequence in SEQUENCES.items():
        assert KeyDecoder().feed(sequence) == [name]


def test_sequence_split_across_reads():
    d = KeyDecoder()
    assert d.feed(b"\x1b") == []
    assert d.feed(b"[") == []
    assert d.feed(b"Ds") == ["left", "s"]


def test_every_split_of_a_stream_gives_the_same_keys():
    stream = b"w\x1b[A\x1bOD\x1b[Zq"
    whole = KeyDecoder().feed(stream)
    for cut in range(len(stream) + 1):
        d = KeyDecoder()
        assert d.feed(stream[:cut]) + d.feed(stream[cut:]) == whole


def test_unknown_escape_sequences_are_skipped():
    assert KeyDecoder().feed(b"\x1b[Zq") == ["Z", "q"]
    assert KeyDecoder().feed(b"\x1bq") == ["q"]
