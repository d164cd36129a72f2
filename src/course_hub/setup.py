"""catkin's build of course_hub (catkin_python_setup reads this with catkin_pkg at hand): the
package from package.xml. pip builds from pyproject.toml, where catkin_pkg is not installed."""
from setuptools import setup

try:
    from catkin_pkg.python_setup import generate_distutils_setup
except ImportError:  # pip's build (the hub's venv, a hub image): pyproject.toml says it all
    setup()
else:
    setup(**generate_distutils_setup(packages=["course_hub"], package_dir={"": "src"}))
