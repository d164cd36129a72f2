"""A C++ target that includes a header of the workspace's own messages must wait for their
generation: found from CMake's Makefile2 and the compiler's .o.d files, never through a link."""
import os

from course_grader.build_order import closure, included_headers, unordered, waits_for

MAKEFILE2 = """# Target rules for target my_chatter/CMakeFiles/user_pub.dir
my_chatter/CMakeFiles/user_pub.dir/all: my_chatter/CMakeFiles/std_msgs_generate_messages_cpp.dir/all
my_chatter/CMakeFiles/user_pub.dir/all:
\t$(MAKE) -f my_chatter/CMakeFiles/user_pub.dir/build.make my_chatter/CMakeFiles/user_pub.dir/depend
my_chatter/CMakeFiles/user_sub.dir/all: my_chatter/CMakeFiles/helpers.dir/all
my_chatter/CMakeFiles/helpers.dir/all: my_chatter/CMakeFiles/my_chatter_generate_messages_cpp.dir/all
my_chatter/CMakeFiles/my_chatter_generate_messages_cpp.dir/all: my_chatter/CMakeFiles/_my_chatter_check_deps.dir/all
my_chatter/CMakeFiles/my_chatter_generate_messages_cpp.dir/all:
"""


def depfile(ws, header):
    return ("my_chatter/CMakeFiles/x.dir/src/x.cpp.o: %s/src/my_chatter/src/x.cpp \\\n"
            " /usr/include/ros/ros.h %s/devel/include/%s \\\n /usr/include/std_msgs/String.h\n" % (ws, ws, header))


def build_tree(ws, headers):
    (ws / "build" / "CMakeFiles").mkdir(parents=True)
    (ws / "build" / "CMakeFiles" / "Makefile2").write_text(MAKEFILE2)
    for target, header in headers.items():
        folder = ws / "build" / "my_chatter" / "CMakeFiles" / (target + ".dir") / "src"
        folder.mkdir(parents=True)
        (folder / (target + ".cpp.o.d")).write_text(depfile(ws, header))


def test_the_graph_and_its_closure():
    graph = waits_for(MAKEFILE2)
    assert graph["my_chatter/CMakeFiles/user_pub"] == {"my_chatter/CMakeFiles/std_msgs_generate_messages_cpp"}
    assert "my_chatter/CMakeFiles/my_chatter_generate_messages_cpp" in closure(graph, "my_chatter/CMakeFiles/user_sub")
    assert included_headers(depfile("/w", "my_chatter/TimestampString.h"), ["/w/devel/include"]) == {
        "my_chatter/TimestampString.h"}


def test_a_target_that_does_not_wait_is_found_and_one_that_waits_through_a_library_is_not(tmp_path):
    ws = tmp_path / "ws"
    build_tree(ws, {"user_pub": "my_chatter/TimestampString.h", "user_sub": "my_chatter/TimestampString.h"})
    found = unordered(str(ws))
    assert [(u.package, u.target, u.header) for u in found] == [
        ("my_chatter", "user_pub", "my_chatter/TimestampString.h")]
    reason = found[0].reason()
    assert "add_dependencies(user_pub ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})" in reason
    assert "my_chatter/CMakeLists.txt" in reason


def test_headers_of_packages_not_generated_here_do_not_count(tmp_path):
    ws = tmp_path / "ws"
    build_tree(ws, {"user_pub": "turtlesim/Pose.h"})
    assert unordered(str(ws)) == []


def test_no_link_is_followed(tmp_path):
    ws = tmp_path / "ws"
    elsewhere = tmp_path / "elsewhere"
    build_tree(elsewhere, {"user_pub": "my_chatter/TimestampString.h"})
    ws.mkdir()
    os.symlink(elsewhere / "build", ws / "build")
    assert unordered(str(ws)) == []
    (ws / "build").unlink()
    (ws / "build" / "CMakeFiles").mkdir(parents=True)
    os.symlink(elsewhere / "build" / "CMakeFiles" / "Makefile2", ws / "build" / "CMakeFiles" / "Makefile2")
    os.symlink(elsewhere / "build" / "my_chatter", ws / "build" / "my_chatter")
    assert unordered(str(ws)) == []


def test_an_empty_or_missing_build_finds_nothing(tmp_path):
    assert unordered(str(tmp_path / "nothing")) == []
    (tmp_path / "ws" / "build" / "CMakeFiles").mkdir(parents=True)
    (tmp_path / "ws" / "build" / "CMakeFiles" / "Makefile2").write_bytes(b"\xff\xfe garbage : \n")
    assert unordered(str(tmp_path / "ws")) == []
