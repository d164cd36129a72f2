"""One module per Gazebo robot plugin this simulator speaks for; importing the package
registers them all (see base.REGISTRY)."""
from . import camera, diff_drive, imu, joint_control, laser  # noqa: F401  (registration)
from .base import REGISTRY, Plugin, make_plugins  # noqa: F401
