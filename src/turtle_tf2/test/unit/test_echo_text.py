from turtle_tf2.echo_text import format_sample
from turtle_tf2.geometry import quaternion_from_euler


def test_static_a_b_sample_layout():
    text = format_sample(12.5, (0.0, 0.0, 3.0), quaternion_from_euler(3.14, 0.0, 0.0))
    lines = text.splitlines()
    assert lines[0] == "At time 12.500"
    assert lines[1] == "- Translation: [0.000, 0.000, 3.000]"
    assert lines[2] == "- Rotation: in Quaternion [1.000, 0.000, 0.000, 0.001]"
    assert lines[3] == "- Rotation: in RPY (radian) [3.140, 0.000, 0.000]"
    assert lines[4] == "- Rotation: in RPY (degree) [179.909, 0.000, 0.000]"


def test_precision_is_honoured():
    assert "[1.0, 2.0, 3.0]" in format_sample(0.0, (1.0, 2.0, 3.0), (0.0, 0.0, 0.0, 1.0), precision=1)
