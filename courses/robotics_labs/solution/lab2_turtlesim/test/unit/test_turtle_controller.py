"""turtle_controller.py's keys: the arrows as turtle_teleop_key, s and q a stop, others nothing."""
import importlib.util
import os

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "..", "src", "turtle_controller.py")


def load_controller():
    spec = importlib.util.spec_from_file_location("turtle_controller", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_keys_to_commands():
    command_for = load_controller().command_for
    assert command_for("up", 2.0, 3.0) == (2.0, 0.0)
    assert command_for("down", 2.0, 3.0) == (-2.0, 0.0)
    assert command_for("left", 2.0, 3.0) == (0.0, 3.0)
    assert command_for("right", 2.0, 3.0) == (0.0, -3.0)
    for key in "sSqQ":
        assert command_for(key, 2.0, 3.0) == (0.0, 0.0)
    assert command_for("x", 2.0, 3.0) is None
