from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(
    packages=["mujoco_gazebo", "mujoco_gazebo.engine", "mujoco_gazebo.plugins", "mujoco_gazebo.ros"],
    package_dir={"": "src"}))
