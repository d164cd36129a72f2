"""discovery.list_executables: a package's executables found where rosrun finds them (no master needed)."""
import os

import pytest

from course_format import causes
from course_milestones.discovery import list_executables
from course_milestones.scripts import script_problems

PKG = "kept_in_msg_pkg"  # a name no workspace of this checkout has


def _write(path, text, mode=0o644):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    path.chmod(mode)


@pytest.fixture
def package(tmp_path, monkeypatch):
    """PKG in a source folder of its own and its devel space, the only ones rospkg and catkin see."""
    src = tmp_path / "src" / PKG
    _write(src / "package.xml", "<package format=\"2\"><name>%s</name></package>\n" % PKG)
    devel = tmp_path / "devel"
    _write(devel / ".catkin", str(tmp_path / "src"))
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "src"))
    monkeypatch.setenv("CMAKE_PREFIX_PATH", str(devel))
    return src, devel


def test_nodes_kept_next_to_the_message_are_found_as_rosrun_finds_them(package):
    src, devel = package
    node = "#!/usr/bin/env python3\nimport rospy\n"
    _write(src / "msg" / "TimestampString.msg", "string message\nfloat64 timestamp\n", 0o755)  # a Windows zip's bits
    _write(src / "msg" / "user_pub.py", node, 0o755)
    _write(src / "srv" / "server.py", node, 0o755)
    _write(src / "cfg" / "turtle_node.py", node, 0o755)
    _write(src / "cfg" / "Speed.cfg", "#!/usr/bin/env python3\nfrom dynamic_reconfigure.parameter_generator_catkin "
                                      "import *\n", 0o755)  # generates code: never a node
    _write(src / "action" / "mover", node, 0o755)
    _write(src / "test" / "helper_pub.py", node, 0o755)  # a test's helper would be taken for the student's node
    _write(src / "tests" / "fake_sub.py", node, 0o755)
    _write(src / "build" / "gen.py", node, 0o755)
    _write(src / "CMakeFiles" / "probe", node, 0o755)
    _write(src / ".git" / "hooks" / "pre-commit", node, 0o755)
    _write(src / "setup.py", node, 0o755)
    _write(src / "src" / "user_sub.py", node, 0o644)  # not executable: rosrun cannot start it either
    _write(devel / "lib" / PKG / "cpp_node", "\x7fELF", 0o755)  # a C++ node, where catkin puts it
    found = list_executables(PKG)
    assert [os.path.relpath(p, src.parent.parent) for p in found] == [  # by name, as rosrun <TAB> lists them
        "devel/lib/%s/cpp_node" % PKG, "src/%s/action/mover" % PKG, "src/%s/srv/server.py" % PKG,
        "src/%s/cfg/turtle_node.py" % PKG, "src/%s/msg/user_pub.py" % PKG]


def test_script_problems_look_where_the_nodes_are_looked_for(package):
    src, _ = package
    _write(src / "msg" / "user_pub.py", "#!/usr/bin/env python3\nimport rospy\n")  # in msg/, without chmod +x
    _write(src / "test" / "helper.py", "#!/usr/bin/env python3\nprint 'x'\n")  # never started: not its cause
    problems = script_problems(str(src))
    assert [causes.of(p) for p in problems] == ["not_executable"], problems
    assert problems[0].startswith("%s/msg/user_pub.py starts with #! but is not executable" % PKG)
    assert list_executables(PKG) == []
