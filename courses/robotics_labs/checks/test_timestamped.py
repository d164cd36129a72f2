import pytest

import timestamped as ts


@pytest.mark.parametrize("names, types, text, time", [
    (["message", "timestamp"], ["string", "float64"], "message", "timestamp"),
    (["f", "s"], ["float64", "string"], "s", "f"),
    (["user_input", "time"], ["string", "time"], "user_input", "time"),
])
def test_fields_found_by_type(names, types, text, time):
    fields, problem = ts.find_fields(names, types)
    assert (fields.text, fields.time, problem) == (text, time, "")


@pytest.mark.parametrize("names, types", [
    (["data"], ["string"]),
    (["a", "b"], ["string", "string"]),
    (["header", "message", "timestamp"], ["std_msgs/Header", "string", "float64"]),
])
def test_fields_other_than_one_text_and_one_number(names, types):
    _, problem = ts.find_fields(names, types)
    assert "one string" in problem and names[0] in problem


def test_clock_units():
    now = 1_700_000_000.25
    assert ts.as_seconds(now, now) == now
    assert ts.as_seconds(now * 1e9, now) == pytest.approx(now)
    assert ts.as_seconds(now * 1e3, now) == pytest.approx(now)
    assert ts.as_seconds(0.0, now) == 0.0


def test_entry_window():
    assert ts.entered_in_time(100.2, 100.0, 100.3, False)
    assert not ts.entered_in_time(0.0, 100.0, 100.3, False)
    assert not ts.entered_in_time(98.0, 100.0, 100.3, False)  # stamped when the prompt was shown
    assert ts.entered_in_time(99.0, 99.9, 100.3, True)  # a whole-second stamp


LINE = "Message: hello turtle, Sent at: 1700000000.123456, Received at: 1700000000.124000"


@pytest.mark.parametrize("output", [
    LINE,
    "[INFO] [1700000000.2]: " + LINE,
    "Message: hello turtle , Sent at: 1700000000.123456 , Received at: 1700000000.124",
    "message: 'hello turtle', sent at: 1700000000.123456, received at: 1700000000124000000",
])
def test_printed_line_found(output):
    line = ts.line_for("other\n" + output + "\n", "hello turtle")
    assert line and line.sent == "1700000000.123456"


def test_printed_line_other_format():
    assert ts.line_for("hello turtle (sent 1.0, received 2.0)", "hello turtle") is None


def test_time_matches_to_printed_precision():
    assert ts.time_matches("1700000000.123456", 1700000000.1234561)
    assert not ts.time_matches("1700000000.124456", 1700000000.123456)  # the receive time
    assert ts.time_matches("1700000000.12", 1700000000.1234)
    assert ts.time_matches("1700000000", 1700000000.4)
    assert ts.time_matches("1700000000123456000", 1700000000.123456)
    assert not ts.time_matches("1700000100.0", 1700000000.0)


def test_prompt_count():
    out = "Please enter a line of text and press <Enter>: \nPlease enter a line of text and press <Enter>:"
    assert ts.prompt_count(out) == 2
    assert ts.prompt_count("> ") == 0
