"""The fast start of turtlesim_node: what it skips, and that it leaves everything as it found it."""
import os
import subprocess
import sys
import textwrap

import pytest

from turtlesim import startup
from turtlesim.constants import DEFAULT_BACKGROUND_RGB
from turtlesim.icons import SHELL_COLOURS, IconSet


def test_hidden_module_fails_inside_and_comes_back_after(tmp_path, monkeypatch):
    (tmp_path / "heavy_mod.py").write_text("LOADED = True\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    with startup.hidden_module("heavy_mod"):
        with pytest.raises(ImportError):
            import heavy_mod  # noqa: F401
    assert "heavy_mod" not in sys.modules
    import heavy_mod
    assert heavy_mod.LOADED
    with startup.hidden_module("heavy_mod"):  # already loaded: left alone
        import heavy_mod as again
    assert again is heavy_mod
    del sys.modules["heavy_mod"]


def test_deferred_module_loads_the_real_one_at_the_first_call(tmp_path, monkeypatch):
    (tmp_path / "slow_mod.py").write_text("def double(x):\n    return 2 * x\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    with startup.deferred_module("slow_mod", ["double"]):
        from slow_mod import double
    assert "slow_mod" not in sys.modules
    assert double(21) == 42
    assert sys.modules["slow_mod"].double is not double  # the real one, loaded by the call
    del sys.modules["slow_mod"]


def test_the_node_runs_without_numpy_and_catkin_pkg():
    code = textwrap.dedent("""
        import sys
        from turtlesim import startup
        rospy = startup.import_rospy()
        import turtlesim.app, turtlesim.node
        from turtlesim.msg import Pose
        from io import BytesIO
        buf = BytesIO()
        Pose(x=1.0, y=2.0, theta=0.5, linear_velocity=0.0, angular_velocity=1).serialize(buf)
        print(*[m in sys.modules for m in ("numpy", "catkin_pkg", "pyparsing", "PyQt5.QtWidgets")], len(buf.getvalue()))
        import numpy, roslib.packages
        print(numpy.float32(1.5) + 1, roslib.packages.find_node("turtlesim", "turtlesim_node")[0].endswith("nodes/turtlesim_node"))
    """)
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    out = subprocess.run([sys.executable, "-c", code], env=env, stdout=subprocess.PIPE, text=True, check=True)
    # none of them loaded, messages as before; numpy and roslib's package search work as usual after
    assert out.stdout.split() == ["False", "False", "False", "False", "20", "2.5", "True"]


def test_registration_poll_starts_at_a_millisecond_and_backs_off_to_rospys():
    slept = []

    class FakeTime:
        @staticmethod
        def sleep(seconds):
            slept.append(seconds)

        @staticmethod
        def monotonic():
            return 42.0

    clock = startup.BackoffSleep(FakeTime)
    clock.sleep(0.00001)  # rospy's poll for its XML-RPC server: as short as it was
    for _ in range(9):
        clock.sleep(0.1)  # rospy's poll for the master registration
    assert slept == pytest.approx([0.00001, 0.001, 0.002, 0.004, 0.008, 0.016, 0.032, 0.064, 0.1, 0.1])
    assert clock.monotonic() == 42.0  # everything else is the real module's


def test_registration_poll_is_restored_after_init():
    import time

    import rospy.impl.init as rospy_init
    with startup.quick_registration_poll():
        assert isinstance(rospy_init.time, startup.BackoffSleep)
    assert rospy_init.time is time


def _ros_dirs(tmp_path, monkeypatch):
    home, etc = tmp_path / "home", tmp_path / "etc"
    (home / "config").mkdir(parents=True)
    etc.mkdir()
    monkeypatch.setenv("ROS_HOME", str(home))
    monkeypatch.setenv("ROS_ETC_DIR", str(etc))
    monkeypatch.delenv(startup.LOG_CONFIG_ENV, raising=False)
    return home / "config", etc


def test_log_config_is_found_where_rosgraph_looks_first(tmp_path, monkeypatch):
    config, etc = _ros_dirs(tmp_path, monkeypatch)
    assert startup.log_config_file() is None  # nothing without the crawl: rospy crawls as before
    (etc / "python_logging.conf").write_text("")
    assert startup.log_config_file() == str(etc / "python_logging.conf")
    (config / "python_logging.yaml").write_text("")
    assert startup.log_config_file() == str(config / "python_logging.yaml")  # ROS_HOME before etc
    (config / "python_logging.conf").write_text("")
    assert startup.log_config_file() == str(config / "python_logging.conf")  # .conf before .yaml
    monkeypatch.setenv(startup.LOG_CONFIG_ENV, "/elsewhere.conf")
    assert startup.log_config_file() is None  # the user's choice stands


def test_env_var_is_set_inside_and_restored(monkeypatch):
    monkeypatch.delenv("TURTLESIM_TEST_VAR", raising=False)
    with startup.env_var("TURTLESIM_TEST_VAR", "x"):
        assert os.environ["TURTLESIM_TEST_VAR"] == "x"
    assert "TURTLESIM_TEST_VAR" not in os.environ
    monkeypatch.setenv("TURTLESIM_TEST_VAR", "before")
    with startup.env_var("TURTLESIM_TEST_VAR", "x"):
        pass
    with startup.env_var("TURTLESIM_TEST_VAR", None):
        assert os.environ["TURTLESIM_TEST_VAR"] == "before"
    assert os.environ["TURTLESIM_TEST_VAR"] == "before"


def test_background_from_params_clamps_and_defaults():
    from turtlesim.node import background_from
    assert background_from({}) == DEFAULT_BACKGROUND_RGB
    assert background_from({"background_r": 300, "background_g": -5, "background_b": "blue"}) == \
        (255, 0, DEFAULT_BACKGROUND_RGB[2])


def test_icons_are_drawn_when_first_shown_and_kept():
    icons = IconSet()
    assert len(icons) == len(SHELL_COLOURS)
    first = icons.image(3)
    assert not first.isNull() and icons.image(3) is first
    assert icons.image(3 + len(icons)) is first
