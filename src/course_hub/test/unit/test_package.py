"""course_hub as a Python package (pyproject.toml, for the hub's venv and a hub image): its
version is package.xml's, its entry points and commands name what exists, and the image carries
jupyterhub at the hub's version."""
from __future__ import annotations

import ast
import os
import re
import tomllib
import xml.etree.ElementTree as ET

PACKAGE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CHECKOUT = os.path.dirname(os.path.dirname(PACKAGE))


def pyproject():
    with open(os.path.join(PACKAGE, "pyproject.toml"), "rb") as f:
        return tomllib.load(f)["project"]


def defined(target):
    """True when `module:name` is a class or function defined at the top of that module's file."""
    module, name = target.split(":")
    path = os.path.join(PACKAGE, "src", *module.split(".")) + ".py"
    with open(path) as f:
        tree = ast.parse(f.read())
    return any(isinstance(node, (ast.ClassDef, ast.FunctionDef)) and node.name == name for node in tree.body)


def test_one_version_for_catkin_and_pip():
    assert pyproject()["version"] == ET.parse(os.path.join(PACKAGE, "package.xml")).getroot().findtext("version")


def test_jupyterhub_finds_the_course_spawner_and_authenticator_by_their_entry_points():
    points = pyproject()["entry-points"]
    assert points["jupyterhub.spawners"] == {"course": "course_hub.spawner:CourseSpawner"}
    assert points["jupyterhub.authenticators"] == {"course": "course_hub.auth:CourseAuthenticator",
                                                   "course-lti": "course_hub.lti:CourseLTIAuthenticator"}
    for group in points.values():
        assert all(defined(target) for target in group.values()), group


def test_the_hubs_commands_are_the_packages_own():
    scripts = pyproject()["scripts"]
    assert scripts == {"course-hub": "course_hub.runner:main", "course-hub-passwords": "course_hub.passwords:main"}
    assert all(defined(target) for target in scripts.values())


def test_the_image_carries_jupyterhub_at_the_hubs_version():
    def pin(path):
        text = open(os.path.join(CHECKOUT, path)).read()
        return re.search(r"^jupyterhub==(\S+)", text, re.M).group(1)
    assert pin("requirements-jupyter.txt") == pin("requirements-hub.txt")
