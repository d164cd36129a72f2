from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["course_milestones", "course_milestones.steps"], package_dir={"": "src"}))
