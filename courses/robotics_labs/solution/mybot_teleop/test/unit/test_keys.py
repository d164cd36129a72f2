from mybot_teleop_core.keys import DOWN, LEFT, QUIT, RIGHT, STOP, UP, KeyDecoder


def test_arrows_and_letters():
    assert KeyDecoder().feed(b"\x1b[A\x1b[B\x1b[C\x1b[Dsq") == [UP, DOWN, RIGHT, LEFT, STOP, QUIT]


def test_application_mode_arrows():
    assert KeyDecoder().feed(b"\x1bOA\x1bOD") == [UP, LEFT]


def test_sequence_split_across_reads():
    decoder = KeyDecoder()
    assert decoder.feed(b"\x1b") == []
    assert decoder.feed(b"[") == []
    assert decoder.feed(b"Cx") == [RIGHT]


def test_unknown_bytes_are_skipped():
    assert KeyDecoder().feed(b"zz\x1b[Z\x1bq") == [QUIT]
