"""Every Gazebo plugin file name a course URDF may name maps to its own plugin module."""
from mujoco_gazebo.plugins import REGISTRY, Plugin


def test_registry_names_each_gazebo_plugin():
    modules = {name: cls.__module__.rsplit(".", 1)[-1] for name, cls in REGISTRY.items()}
    assert modules == {"libgazebo_ros_control.so": "joint_control", "libgazebo_ros_diff_drive.so": "diff_drive",
                       "libgazebo_ros_laser.so": "laser", "libgazebo_ros_gpu_laser.so": "laser",
                       "libgazebo_ros_imu.so": "imu", "libgazebo_ros_imu_sensor.so": "imu",
                       "libgazebo_ros_camera.so": "camera"}
    assert all(issubclass(cls, Plugin) for cls in REGISTRY.values())


def test_due_keeps_the_period_in_simulated_time():
    plugin = Plugin()
    plugin.period = 0.1
    assert [plugin.due(t) for t in (0.0, 0.05, 0.1, 0.15, 0.2)] == [True, False, True, False, True]
    assert plugin.due(1.0) and not plugin.due(1.05)  # after a gap: one update, then the period again
