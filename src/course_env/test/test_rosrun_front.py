"""Our `rosrun` front picks the executable Debian's rosrun would, only faster.

Both are run on a throw-away package tree (no master needed): one executable, a
relay pair like catkin's devel space makes, a non-executable file, two equal
names (Debian's menu), a missing package, options and paths. `--prefix echo`
and a wrapper make every run print the path it would execute instead of running it.
"""
from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

FRONT = Path(__file__).resolve().parents[1] / "bin" / "rosrun"
UPSTREAM = Path("/usr/bin/rosrun")

pytestmark = pytest.mark.skipif(not UPSTREAM.exists(), reason="Debian's rosrun is not installed")


def _script(path: Path, mode: int = 0o755) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text('#!/bin/sh\necho "ran $0 $*"\n')
    path.chmod(mode)


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> dict:
    root = tmp_path_factory.mktemp("ws")
    src = root / "src" / "demo_pkg"
    src.mkdir(parents=True)
    (src / "package.xml").write_text(
        '<?xml version="1.0"?><package format="2"><name>demo_pkg</name><version>0.0.0</version>'
        '<description>d</description><maintainer email="staff@example.org">staff</maintainer><license>BSD</license>'
        '<buildtool_depend>catkin</buildtool_depend></package>')
    _script(src / "nodes" / "single")
    _script(src / "scripts" / "twice")
    _script(src / "nodes" / "twice")
    _script(src / "scripts" / "plain.py", 0o644)
    _script(src / "nodes" / "relayed")
    _script(root / "devel" / "lib" / "demo_pkg" / "relayed")
    (root / "devel" / ".catkin").write_text(str(root / "src"))
    (root / "devel" / "share" / "demo_pkg").mkdir(parents=True)
    env = dict(os.environ)
    env["ROS_PACKAGE_PATH"] = f"{root / 'src'}:{env.get('ROS_PACKAGE_PATH', '')}"
    env["CMAKE_PREFIX_PATH"] = f"{root / 'devel'}:{env.get('CMAKE_PREFIX_PATH', '')}"
    return {"root": root, "env": env}


def _run(tool: Path, args: list[str], env: dict) -> tuple[int, str]:
    done = subprocess.run([str(tool), *args], env=env, stdin=subprocess.DEVNULL,
                          capture_output=True, text=True, timeout=30)
    return done.returncode, done.stdout + done.stderr


CASES = [
    ["demo_pkg", "single", "a", "b"],
    ["demo_pkg", "relayed"],
    ["demo_pkg", "twice"],
    ["demo_pkg", "plain.py"],
    ["demo_pkg", "missing"],
    ["no_such_pkg", "single"],
    ["demo_pkg", "nodes/single", "x"],
    ["--prefix", "echo", "demo_pkg", "single"],
    ["demo_pkg", "dir/"],
    ["demo_pkg"],
    ["--help"],
]


@pytest.mark.parametrize("args", CASES, ids=lambda a: " ".join(a))
def test_same_as_debian(tree, args):
    assert _run(FRONT, args, tree["env"]) == _run(UPSTREAM, args, tree["env"])


def test_runs_the_devel_relay_with_arguments(tree):
    code, out = _run(FRONT, ["demo_pkg", "relayed", "--flag"], tree["env"])
    assert code == 0
    assert out.strip() == f"ran {tree['root'] / 'devel' / 'lib' / 'demo_pkg' / 'relayed'} --flag"


def test_is_first_on_path_after_sourcing():
    """The env hook puts the front before Debian's rosrun."""
    found = subprocess.run(["bash", "-c", "command -v rosrun"], capture_output=True, text=True).stdout.strip()
    if "ROS_DISTRO" not in os.environ:
        pytest.skip("workspace not sourced")
    assert Path(found).resolve() == FRONT.resolve()
