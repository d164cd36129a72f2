import pytest

from course_relay.args import parse_relay_args


def test_out_defaults_to_in_relay():
    assert parse_relay_args(["/chatter"]) == ("/chatter", "/chatter_relay")


def test_explicit_out_and_remaps_ignored():
    assert parse_relay_args(["a", "b", "__name:=r"]) == ("a", "b")


@pytest.mark.parametrize("argv", [[], ["a", "b", "c"]])
def test_bad_argument_counts(argv):
    with pytest.raises(SystemExit, match="usage"):
        parse_relay_args(argv)
