"""The engine layer runs without ROS: every module under mujoco_gazebo/engine imports in a
Python where rospy, genpy and every *_msgs/*_srvs package are unimportable."""
import os
import pkgutil
import subprocess
import sys
from pathlib import Path

import mujoco_gazebo.engine

ENGINE_DIR = Path(mujoco_gazebo.engine.__file__).resolve().parent
PACKAGE_ROOT = ENGINE_DIR.parents[1]  # the folder holding the mujoco_gazebo package

PROBE = r"""
import importlib, importlib.abc, sys

class NoRos(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        top = name.split(".")[0]
        if top in ("rospy", "genpy", "roslib") or top.endswith(("_msgs", "_srvs")):
            raise ImportError("ROS module %s imported by the engine" % name)
        return None

sys.meta_path.insert(0, NoRos())
for module in sys.argv[1:]:
    importlib.import_module(module)
leaked = sorted(m for m in sys.modules if m.split(".")[0] in ("rospy", "genpy", "roslib"))
assert not leaked, leaked
print("ok", len(sys.argv) - 1)
"""


def probe(*modules: str) -> subprocess.CompletedProcess:
    """PROBE importing `modules` in a fresh Python, the folder holding mujoco_gazebo first on its path."""
    path = os.pathsep.join([str(PACKAGE_ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
    return subprocess.run([sys.executable, "-c", PROBE, *modules], env=dict(os.environ, PYTHONPATH=path),
                          capture_output=True, text=True)


def engine_modules():
    return ["mujoco_gazebo.engine." + m.name for m in pkgutil.iter_modules([str(ENGINE_DIR)])]


def test_the_probe_refuses_rospy():
    out = probe("rospy")
    assert out.returncode != 0 and "ROS module rospy" in out.stderr


def test_every_engine_module_imports_without_ros():
    modules = engine_modules()
    assert {"mujoco_gazebo.engine.world", "mujoco_gazebo.engine.odometry", "mujoco_gazebo.engine.imu"} <= set(modules)
    out = probe(*modules)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["ok", str(len(modules))]
