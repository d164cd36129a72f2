import math

import pytest

from mujoco_gazebo.ros.spawn_cli import UsageError, load_xml, parse_args


def test_text_003_command_line():
    a = parse_args("-database coke_can -sdf -model coke_can3 -x 1 -z 1".split())
    assert (a.fmt, a.source, a.source_value, a.model) == ("sdf", "database", "coke_can", "coke_can3")
    assert a.pose == [1.0, 0.0, 1.0, 0.0, 0.0, 0.0]
    assert "<model" in load_xml(a)


def test_param_source_and_orientation():
    a = parse_args("-urdf -model tb3 -x 0.5 -Y 1.57 -param robot_description".split())
    assert a.fmt == "urdf" and a.pose[5] == 1.57
    assert load_xml(a, get_param=lambda name: "<robot/>" if name == "robot_description" else None) == "<robot/>"


@pytest.mark.parametrize("argv", ["-sdf -database coke_can", "-sdf -model m", "-model m -file a -param b -sdf",
                                  "-sdf -model m -database c -x nan", "-sdf -model m -database c -x", "-bogus"])
def test_bad_arguments(argv):
    with pytest.raises(UsageError):
        parse_args(argv.split())


def test_missing_sources_are_clear_errors():
    with pytest.raises(UsageError, match="not in the model database"):
        load_xml(parse_args("-sdf -model m -database nothing_here".split()))
    with pytest.raises(UsageError, match="not set"):
        load_xml(parse_args("-urdf -model m -param robot_description".split()), get_param=lambda n: None)
