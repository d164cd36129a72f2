import pytest

from mybot_teleop_core.commands import CONTINUOUS, ON_KEY, TeleopCommands, Velocity


def test_keys_scale_velocities():
    c = TeleopCommands(1.5, 0.5)
    assert c.on_key("up") == Velocity(1.5, 0.0)
    assert c.on_key("down") == Velocity(-1.5, 0.0)
    assert c.on_key("left") == Velocity(0.0, 0.5)
    assert c.on_key("right") == Velocity(0.0, -0.5)
    assert c.on_key("stop") == Velocity()


def test_on_key_mode_publishes_nothing_on_ticks():
    c = TeleopCommands(1.0, 1.0, ON_KEY)
    c.on_key("up")
    assert c.on_tick() is None


def test_continuous_mode_repeats_until_stop():
    c = TeleopCommands(1.0, 1.0, CONTINUOUS)
    assert c.on_tick() == Velocity()
    c.on_key("up")
    assert c.on_tick() == Velocity(1.0, 0.0)
    assert c.on_tick() == Velocity(1.0, 0.0)
    c.on_key("stop")
    assert c.on_tick() == Velocity()


def test_quit_stops_robot():
    c = TeleopCommands(1.0, 1.0)
    assert c.on_key("quit") == Velocity()
    assert c.quit


def test_bad_mode_is_refused():
    with pytest.raises(ValueError, match="publish_mode"):
        TeleopCommands(1.0, 1.0, "sometimes")
