"""The course's environment alone: whatever workspace was sourced before the grader started (the
reference solutions' overlay, as `make test` has it), no reference folder is left on any path."""
import os

import pytest

from course_grader import workspace
from course_sandbox import env_paths


def test_the_course_environment_has_no_reference_folder_on_any_path(course, tmp_path):
    root = workspace.course_root(course)
    devel = os.path.dirname(course)
    solutions_devel = os.path.join(root, workspace.SOLUTIONS_WS, "devel")
    sourced = dict(os.environ,  # what `source solutions_ws/devel/setup.bash` gives
                   ROS_PACKAGE_PATH="%s:%s" % (os.path.join(root, workspace.SOLUTIONS_WS, "src"),
                                               os.path.join(os.path.dirname(devel), "src")),
                   CMAKE_PREFIX_PATH="%s:%s" % (solutions_devel, devel),
                   PYTHONPATH="%s/lib/python3/dist-packages:%s/lib/python3/dist-packages" % (solutions_devel, devel),
                   LD_LIBRARY_PATH="%s/lib:%s/lib" % (solutions_devel, devel),
                   PATH="%s/bin:%s" % (solutions_devel, os.environ["PATH"]))
    env = workspace.course_environment(course, sourced)
    for var in env_paths.FOLDER_LISTS:
        leaked = [p for p in env.get(var, "").split(os.pathsep)
                  if p and any(os.path.realpath(p).startswith(os.path.realpath(f)) for f in workspace.reference_folders(course))]
        assert not leaked, "%s keeps %s" % (var, leaked)
    assert devel in env["CMAKE_PREFIX_PATH"].split(os.pathsep)
    assert env["ROS_PACKAGE_PATH"].split(os.pathsep)[0] == os.path.join(os.path.dirname(devel), "src")


def test_folder_lists_lose_the_entries_inside_given_folders(tmp_path):
    inside, outside = tmp_path / "solutions" / "a", tmp_path / "course" / "b"
    env = {"PATH": "%s:%s:/usr/bin" % (inside, outside), "HOME": str(inside)}
    clean = workspace.without_folders(env, [str(tmp_path / "solutions")])
    assert clean == {"PATH": "%s:/usr/bin" % outside, "HOME": str(inside)}  # only folder lists change


def test_every_course_folders_answers_are_reference_folders(tmp_path):
    setup = tmp_path / "catkin_ws" / "devel" / "setup.bash"
    setup.parent.mkdir(parents=True)
    setup.write_text("")
    for course in ("robotics_labs", "mine"):
        for kind in ("solution", "samples", "starter", "checks"):
            (tmp_path / "courses" / course / kind).mkdir(parents=True)
    folders = workspace.reference_folders(str(setup))
    assert folders[0] == str(tmp_path / workspace.SOLUTIONS_WS)
    assert sorted(folders[1:]) == sorted(str(tmp_path / "courses" / c / k) for c in ("robotics_labs", "mine")
                                         for k in ("solution", "samples"))  # starter/ and checks/ are no answers
