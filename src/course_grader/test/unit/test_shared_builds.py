"""Builds shared between submissions with the same build inputs (`grade --share-builds`): which
files a build reads, and a real catkin devel space copied to another path that still runs."""
import os
import shutil
import subprocess
import threading

import pytest
from hypothesis import given, settings, strategies as st

from course_grader import shared_builds, workspace

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2"><name>demo</name><version>0.0.1</version><description>d</description>
<maintainer email="ta@example.org">a</maintainer><license>MIT</license>
<buildtool_depend>catkin</buildtool_depend><exec_depend>rospy</exec_depend></package>
"""
CMAKE = """cmake_minimum_required(VERSION 3.0.2)
project(demo)
find_package(catkin REQUIRED)
catkin_python_setup()
catkin_package()
catkin_install_python(PROGRAMS scripts/talker nodes/hello.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
"""
SETUP_PY = """from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup
setup(**generate_distutils_setup(packages=["demo"], package_dir={"": "src"}))
"""


def make_package(root, talker="print('one')\n"):
    pkg = root / "src" / "demo"
    for sub in ("scripts", "nodes", "src/demo", "launch"):
        (pkg / sub).mkdir(parents=True, exist_ok=True)
    (pkg / "package.xml").write_text(PACKAGE_XML)
    (pkg / "CMakeLists.txt").write_text(CMAKE)
    (pkg / "setup.py").write_text(SETUP_PY)
    (pkg / "scripts" / "talker").write_text("#!/usr/bin/env python3\nimport demo.words\n" + talker)
    (pkg / "nodes" / "hello.py").write_text("#!/usr/bin/env python3\nprint('hello')\n")
    (pkg / "src" / "demo" / "__init__.py").write_text("")
    (pkg / "src" / "demo" / "words.py").write_text("WORD = 'one'\n")
    (pkg / "launch" / "x.launch").write_text("<launch/>\n")
    for script in ("scripts/talker", "nodes/hello.py"):
        os.chmod(pkg / script, 0o755)
    return pkg


def test_python_and_launch_files_run_from_source_and_the_rest_is_built():
    assert shared_builds.runs_from_source("demo/nodes/hello.py", b"")
    assert shared_builds.runs_from_source("demo/scripts/talker", b"#!/usr/bin/env python3\nimport x")
    assert shared_builds.runs_from_source("demo/launch/x.launch", b"<launch/>")
    assert not shared_builds.runs_from_source("demo/scripts/run.sh", b"#!/bin/sh\necho python")
    assert not shared_builds.runs_from_source("demo/setup.py", b"from setuptools import setup")
    assert not shared_builds.runs_from_source("demo/cfg/Speed.cfg", b"#!/usr/bin/env python3\n")
    assert not shared_builds.runs_from_source("demo/cfg/gen.py", b"")  # dynamic_reconfigure runs cfg/ at build time
    assert not shared_builds.runs_from_source("demo/CMakeLists.txt", b"")
    assert not shared_builds.runs_from_source("demo/src/talker.cpp", b"#include <ros/ros.h>")


def test_the_key_ignores_python_content_and_sees_everything_the_build_reads(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    make_package(a)
    make_package(b, talker="print('two')\n")
    key = shared_builds.inputs_key(str(a / "src"))
    assert shared_builds.inputs_key(str(b / "src")) == key  # a Python line changed
    (b / "src/demo/launch/x.launch").write_text("<launch><node pkg='demo' type='talker' name='t'/></launch>\n")
    assert shared_builds.inputs_key(str(b / "src")) == key  # a launch file changed
    changes = [
        lambda p: (p / "CMakeLists.txt").write_text(CMAKE.replace("scripts/talker ", "")),
        lambda p: (p / "package.xml").write_text(PACKAGE_XML.replace("0.0.1", "0.0.2")),
        lambda p: os.chmod(p / "nodes" / "hello.py", 0o644),  # the relay is made from the mode too
        lambda p: (p / "nodes" / "bye.py").write_text("print('bye')\n"),  # a new file: catkin may glob
        lambda p: os.remove(p / "nodes" / "hello.py"),
        lambda p: os.symlink("hello.py", p / "nodes" / "link.py"),
        lambda p: (p / "msg").mkdir() or (p / "msg" / "Num.msg").write_text("int64 num\n"),
    ]
    for change in changes:
        c = tmp_path / "c"
        shutil.rmtree(c, ignore_errors=True)
        make_package(c)
        change(c / "src" / "demo")
        assert shared_builds.inputs_key(str(c / "src")) != key, change


@settings(max_examples=50, deadline=None)
@given(st.binary(max_size=300))
def test_a_python_files_content_never_changes_the_key(tmp_path_factory, content):
    root = tmp_path_factory.mktemp("ws")
    make_package(root)
    key = shared_builds.inputs_key(str(root / "src"))
    (root / "src/demo/src/demo/words.py").write_bytes(content)
    assert shared_builds.inputs_key(str(root / "src")) == key


def test_a_binary_holding_the_path_is_not_copied(tmp_path):
    donor, ws = tmp_path / "donor" / "ws", tmp_path / "other" / "ws"
    (donor / "devel" / "lib").mkdir(parents=True)
    (donor / "devel" / "setup.sh").write_text("CATKIN=%s/devel\n" % donor)
    (donor / "devel" / "lib" / "libx.so").write_bytes(b"\x7fELF\0rpath=" + str(donor).encode() + b"/devel/lib\0")
    (ws / "src").mkdir(parents=True)
    why = shared_builds.relocate(str(donor), str(ws))
    assert "binary" in why and "libx.so" in why
    assert not (ws / "devel").exists()  # nothing half-copied is left


def test_links_are_copied_as_links_and_never_written_through(tmp_path):
    donor, ws = tmp_path / "donor" / "ws", tmp_path / "other" / "ws"
    (donor / "devel").mkdir(parents=True)
    outside = tmp_path / "outside.txt"
    outside.write_text("path %s\n" % donor)
    os.symlink(outside, donor / "devel" / "link")
    (donor / "devel" / ".catkin").write_text(str(donor / "src"))
    (ws / "src").mkdir(parents=True)
    assert shared_builds.relocate(str(donor), str(ws)) is None
    assert os.path.islink(ws / "devel" / "link")
    assert outside.read_text() == "path %s\n" % donor
    assert (ws / "devel" / ".catkin").read_text() == str(ws / "src")


def test_the_first_builds_and_the_others_wait_for_it():
    share = shared_builds.BuildShare()
    assert share.claim("k", "/a") == (True, None)
    got = []
    waiter = threading.Thread(target=lambda: got.append(share.claim("k", "/b")))
    waiter.start()
    waiter.join(0.2)
    assert waiter.is_alive()  # it waits for the first build
    share.done("k", "/a", True)
    waiter.join(10)
    assert got == [(False, "/a")]
    assert share.claim("other", "/c") == (True, None)
    share.done("other", "/c", False)
    assert share.claim("other", "/d") == (True, None)  # a failed build is not shared: build yourself


def sourced(setup, command):
    return subprocess.run(["bash", "-c", "source %s && %s" % (setup, command)], capture_output=True, text=True,
                          timeout=120, env={k: v for k, v in os.environ.items() if not k.startswith("ROS_")} |
                          {"HOME": os.environ.get("HOME", "/root")})


def test_a_real_devel_space_copied_elsewhere_runs_the_new_workspaces_sources(course, tmp_path):
    donor, ws = tmp_path / "one" / "ws", tmp_path / "two" / "ws"
    make_package(donor)
    make_package(ws, talker="print(demo.words.WORD, 'two')\n")
    assert shared_builds.inputs_key(str(donor / "src")) == shared_builds.inputs_key(str(ws / "src"))
    built = sourced(course, "cd %s && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3" % donor)
    assert built.returncode == 0, built.stdout[-2000:] + built.stderr[-2000:]
    assert shared_builds.relocate(str(donor), str(ws)) is None
    shutil.rmtree(donor)  # nothing of the copy may still point there
    run = sourced(ws / "devel" / "setup.bash", "rospack find demo && rosrun demo talker && "
                  "python3 -c 'import demo.words, sys; print(demo.words.__file__)'")
    assert run.returncode == 0, run.stderr
    found, said, module = run.stdout.splitlines()[:3]
    assert found == str(ws / "src" / "demo")
    assert said == "one two"  # the mutated source of the new workspace ran
    assert module.startswith(str(ws / "src" / "demo"))
    listed = sourced(ws / "devel" / "setup.bash", "echo $CMAKE_PREFIX_PATH; echo $ROS_PACKAGE_PATH")
    assert str(tmp_path / "one") not in listed.stdout
