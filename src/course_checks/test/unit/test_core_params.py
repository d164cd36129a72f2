"""core_params: a run's etc/ros answers roscore.xml's command parameters from files, and
roslaunch's own loader reads the same parameter values from it as from the real one."""
import os
from pathlib import Path

import pytest

from course_checks.core_params import etc_dir_for_run

ROSCORE = """<launch>
  <group ns="/">
    <param name="greeting" command="echo hello" />
    <param name="fixed" value="1" />
    <node pkg="rosout" type="rosout" name="rosout" respawn="true"/>
  </group>
</launch>
"""


@pytest.fixture
def etc(tmp_path):
    real = tmp_path / "etc_ros"
    real.mkdir()
    (real / "roscore.xml").write_text(ROSCORE)
    (real / "python_logging.conf").write_text("[loggers]\n")
    return real


def test_command_params_become_files_holding_their_output_and_the_rest_is_linked(etc, tmp_path):
    run = etc_dir_for_run({"ROS_ETC_DIR": str(etc), "PATH": os.environ["PATH"]}, str(tmp_path / "run"))
    assert run == str(tmp_path / "run")
    text = Path(run, "roscore.xml").read_text()
    assert "command=" not in text and 'value="1"' in text and 'type="rosout"' in text
    (textfile,) = [p for p in Path(run).iterdir() if p.name.startswith("param-")]
    assert textfile.read_text() == "hello\n"
    assert os.readlink(Path(run, "python_logging.conf")) == str(etc / "python_logging.conf")


def test_a_second_run_in_the_same_folder_starts_afresh(etc, tmp_path):
    env = {"ROS_ETC_DIR": str(etc), "PATH": os.environ["PATH"]}
    assert etc_dir_for_run(env, str(tmp_path / "run")) == etc_dir_for_run(env, str(tmp_path / "run"))


@pytest.mark.parametrize("roscore", [None, "<launch><param name='x' command='false'/></launch>", "<launch"])
def test_without_a_usable_roscore_xml_the_real_folder_is_kept(etc, tmp_path, roscore):
    if roscore is None:
        (etc / "roscore.xml").unlink()
    else:
        (etc / "roscore.xml").write_text(roscore)
    assert etc_dir_for_run({"ROS_ETC_DIR": str(etc), "PATH": os.environ["PATH"]}, str(tmp_path / "run")) is None


def test_roslaunch_loads_the_same_core_parameters(tmp_path, monkeypatch):
    """Debian's own /etc/ros/roscore.xml (rosversion roslaunch, rosversion -d), loaded by roslaunch."""
    from roslaunch.config import load_config_default

    def core_params(etc_dir):
        monkeypatch.setenv("ROS_ETC_DIR", etc_dir)
        config = load_config_default([], None)
        return {name: p.value for name, p in config.params.items()}

    real = core_params(os.environ.get("ROS_ETC_DIR", "/etc/ros"))
    assert "/rosversion" in real and "/rosdistro" in real
    run = etc_dir_for_run(dict(os.environ), str(tmp_path / "run"))
    assert run is not None
    assert core_params(run) == real


def test_the_folder_is_readable_by_the_sandbox_user_whatever_the_umask(etc, tmp_path):
    """A student's roslaunch (another user) reads it too; the real files linked keep their modes."""
    before = (etc / "python_logging.conf").stat().st_mode
    old = os.umask(0o077)
    try:
        run = Path(etc_dir_for_run({"ROS_ETC_DIR": str(etc), "PATH": os.environ["PATH"]}, str(tmp_path / "run")))
    finally:
        os.umask(old)
    assert run.stat().st_mode & 0o777 == 0o755
    assert {p.name: p.stat().st_mode & 0o777 for p in run.iterdir() if not p.is_symlink()} == {
        "roscore.xml": 0o644, "param-0.txt": 0o644}
    assert (etc / "python_logging.conf").stat().st_mode == before


def test_runs_starting_together_run_each_command_once(etc, tmp_path):
    """A grading starts several runs at the same moment: the command still runs once."""
    from concurrent.futures import ThreadPoolExecutor

    counter = tmp_path / "ran"
    script = tmp_path / "bin" / "slow-version"
    script.parent.mkdir()
    # slow enough that, unserialised, every run would start it before the first had answered
    script.write_text("#!/bin/sh\necho x >> %s\nsleep 0.3\necho 1.2.3\n" % counter)
    script.chmod(0o755)
    (etc / "roscore.xml").write_text(ROSCORE.replace("echo hello", "slow-version --unique-%s" % tmp_path.name))
    env = {"ROS_ETC_DIR": str(etc), "PATH": "%s:%s" % (script.parent, os.environ["PATH"])}
    with ThreadPoolExecutor(6) as pool:
        runs = list(pool.map(lambda i: etc_dir_for_run(env, str(tmp_path / ("run%d" % i))), range(6)))
    assert all(runs)
    assert [Path(r, "param-0.txt").read_text() for r in runs] == ["1.2.3\n"] * 6
    assert counter.read_text().count("x") == 1
