"""The reason a failed catkin_make gives a student: the compiler's and linker's own lines first,
with the student's paths, then a hint for the usual mistakes; warnings never count."""
from hypothesis import given, settings
from hypothesis import strategies as st

from course_grader.build_errors import message_packages, package_format, relative_paths, summarise

WS = "/tmp/grades/_work/carol/ws"

LINK_LOG = """-- +++ processing catkin package: 'my_robot_controller'
[ 50%%] Building CXX object my_robot_controller/CMakeFiles/pose_subscriber.dir/src/pose_subscriber.cpp.o
[100%%] Linking CXX executable %(ws)s/devel/lib/my_robot_controller/pose_subscriber
/usr/bin/ld: CMakeFiles/pose_subscriber.dir/src/pose_subscriber.cpp.o: in function `main':
pose_subscriber.cpp:(.text+0x6d): undefined reference to `ros::init(int&, char**, std::__cxx11::basic_string<char, std::char_traits<char>, std::allocator<char> > const&, unsigned int)'
/usr/bin/ld: pose_subscriber.cpp:(.text+0xc1): undefined reference to `ros::NodeHandle::NodeHandle()'
/usr/bin/ld: pose_subscriber.cpp:(.text+0xd5): undefined reference to `ros::init(int&, char**, std::__cxx11::basic_string<char, std::char_traits<char>, std::allocator<char> > const&, unsigned int)'
/usr/bin/ld: pose_subscriber.cpp:(.text+0x1a2): undefined reference to `ros::spin()'
/usr/bin/ld: warning: creating DT_TEXTREL in a PIE
collect2: error: ld returned 1 exit status
make[2]: *** [my_robot_controller/CMakeFiles/pose_subscriber.dir/build.make:97: %(ws)s/devel/lib/my_robot_controller/pose_subscriber] Error 1
make[1]: *** [CMakeFiles/Makefile2:476: my_robot_controller/CMakeFiles/pose_subscriber.dir/all] Error 2
make: *** [Makefile:146: all] Error 2
Invoking "make -j2 -l2" failed
""" % {"ws": WS}

COMPILE_LOG = """[ 50%%] Building CXX object chat/CMakeFiles/talker.dir/src/talker.cpp.o
%(ws)s/src/chat/src/talker.cpp: In function 'int main(int, char**)':
%(ws)s/src/chat/src/talker.cpp:9:14: error: 'count' was not declared in this scope; did you mean 'std::count'?
    9 |   msg.data = count;
      |              ^~~~~
In file included from /usr/include/ros/ros.h:38,
/usr/include/c++/12/pstl/glue_algorithm_defs.h:101:1: note: 'std::count' declared here
%(ws)s/src/chat/src/talker.cpp:6:7: warning: unused variable 'unused' [-Wunused-variable]
    6 |   int unused = 3;
      |       ^~~~~~
make[2]: *** [chat/CMakeFiles/talker.dir/build.make:76: chat/CMakeFiles/talker.dir/src/talker.cpp.o] Error 1
make: *** [Makefile:146: all] Error 2
""" % {"ws": WS}

RACE_LOG = """-- my_chatter: 1 messages, 0 services
%(ws)s/src/my_chatter/src/user_pub.cpp:2:10: fatal error: my_chatter/TimestampString.h: No such file or directory
    2 | #include "my_chatter/TimestampString.h"
      |          ^~~~~~~~~~~~~~~~~~~~~~~~~~~~~~
compilation terminated.
make[2]: *** [my_chatter/CMakeFiles/user_pub.dir/build.make:76: my_chatter/CMakeFiles/user_pub.dir/src/user_pub.cpp.o] Error 1
make: *** [Makefile:146: all] Error 2
""" % {"ws": WS}


def test_undefined_references_are_named_once_with_the_student_path_and_a_hint():
    summary = summarise(LINK_LOG, WS)
    lines = summary.splitlines()
    assert lines[0] == ("my_robot_controller/src/pose_subscriber.cpp: undefined reference to "
                        "`ros::init(int&, char**, std::string const&, unsigned int)'")
    assert sum("ros::init" in line for line in lines) == 1
    assert "`ros::spin()'" in summary and "collect2: error: ld returned 1 exit status" in summary
    assert WS not in summary and "DT_TEXTREL" not in summary
    assert lines[-1].startswith("hint: pose_subscriber is not linked with the ROS libraries")
    assert "target_link_libraries(pose_subscriber ${catkin_LIBRARIES})" in lines[-1]
    assert "my_robot_controller/CMakeLists.txt" in lines[-1] and "roscpp" in lines[-1]


def test_a_compile_error_comes_with_its_source_line_and_no_warning():
    lines = summarise(COMPILE_LOG, WS).splitlines()
    assert lines[0] == "chat/src/talker.cpp: In function 'int main(int, char**)':"
    assert lines[1].startswith("chat/src/talker.cpp:9:14: error: 'count' was not declared")
    assert lines[2].strip().startswith("9 |")
    assert not any("warning" in line or "unused" in line for line in lines)
    assert not any(line.startswith("hint") for line in lines)


def test_a_header_of_the_own_messages_compiled_too_early_gets_the_add_dependencies_hint():
    summary = summarise(RACE_LOG, WS)
    assert summary.startswith("my_chatter/src/user_pub.cpp:2:10: fatal error: my_chatter/TimestampString.h")
    assert ("add_dependencies(user_pub ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})"
            in summary.splitlines()[-1])


def test_a_header_of_a_package_not_found_gets_the_find_package_hint():
    log = RACE_LOG.replace("-- my_chatter: 1 messages, 0 services\n", "").replace(
        "my_chatter/TimestampString.h", "geometry_msg/Twist.h")
    hint = summarise(log, WS).splitlines()[-1]
    assert hint.startswith("hint: no package found provides geometry_msg/Twist.h")
    assert "find_package(catkin REQUIRED COMPONENTS ...)" in hint and "<depend>geometry_msg</depend>" in hint


def test_cmake_cannot_find_a_package_keeps_cmake_words_and_hints_at_the_spelling():
    log = """CMake Error at /usr/share/catkin/cmake/catkinConfig.cmake:82 (find_package):
  Could not find a package configuration file provided by "std_msg" with any
  of the following names:

    std_msgConfig.cmake
Call Stack (most recent call first):
  chatter/CMakeLists.txt:3 (find_package)

-- Configuring incomplete, errors occurred!
"""
    lines = summarise(log, WS).splitlines()
    assert lines[0].startswith("CMake Error at") and "std_msgConfig.cmake" in "\n".join(lines)
    assert lines[-1].startswith("hint: std_msg is neither a package of this machine")


def test_a_log_without_a_known_error_gives_its_last_lines():
    assert summarise("a\nb\nc\n", WS, lines=2) == "b\nc"


def test_paths_are_the_students():
    assert relative_paths("%s/src/pkg/a.cpp:1:2 and %s/devel/lib/pkg/x" % (WS, WS), WS) == "pkg/a.cpp:1:2 and devel/lib/pkg/x"
    assert message_packages("-- my_chatter: 1 messages, 0 services\n-- turtle_patrol: 0 messages, 1 services\n") == {
        "my_chatter", "turtle_patrol"}


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(LINK_LOG.splitlines() + COMPILE_LOG.splitlines() + RACE_LOG.splitlines()
                                + ["", "error:", ": error: ", "undefined reference to `'", "make[2]: *** [", "\x1b[31m"]))
       | st.lists(st.text(max_size=80), max_size=40))
def test_any_log_gives_a_bounded_summary(lines):
    summary = summarise("\n".join(lines), WS, lines=10)
    assert isinstance(summary, str)
    assert len([line for line in summary.splitlines() if not line.startswith("hint:")]) <= 10


def test_the_functions_the_student_called_come_before_the_macros_plumbing():
    log = LINK_LOG.replace(
        "/usr/bin/ld: CMakeFiles/pose_subscriber.dir/src/pose_subscriber.cpp.o: in function `main':\n",
        "/usr/bin/ld: CMakeFiles/pose_subscriber.dir/src/pose_subscriber.cpp.o: in function `on_pose':\n"
        "pose_subscriber.cpp:(.text+0x1d): undefined reference to `ros::console::g_initialized'\n"
        "/usr/bin/ld: CMakeFiles/pose_subscriber.dir/src/pose_subscriber.cpp.o: in function `main':\n")
    lines = summarise(log, WS).splitlines()
    assert "`ros::init(" in lines[0]
    assert "ros::console::g_initialized" in lines[3]


# Code written for ROS Noetic that Debian 12 still does not compile (docs/noetic_cxx.md), as g++
# reports it in a UTF-8 locale (‘’) and in the C locale ('').
AMBIGUOUS_LOG = """[ 50%%] Building CXX object relay/CMakeFiles/relay.dir/src/relay.cpp.o
%(ws)s/src/relay/src/relay.cpp: In function ‘int main(int, char**)’:
%(ws)s/src/relay/src/relay.cpp:14:62: error: reference to ‘_1’ is ambiguous
   14 |   auto cb = std::bind(&Relay::forward, &relay, _1);
      |                                                ^~
/usr/include/c++/12/functional:285:34: note: candidates are: ‘const std::_Placeholder<1> std::placeholders::_1’
/usr/include/boost/bind/placeholders.hpp:46:38: note:                 ‘constexpr const boost::arg<1> boost::placeholders::_1’
make[2]: *** [relay/CMakeFiles/relay.dir/build.make:76: relay/CMakeFiles/relay.dir/src/relay.cpp.o] Error 1
""" % {"ws": WS}

UNDECLARED_LOG = """%(ws)s/src/fib/src/client.cpp: In constructor 'Client::Client()':
%(ws)s/src/fib/src/client.cpp:25:52: error: '_1' was not declared in this scope
   25 |     ac_.sendGoal(goal, boost::bind(&Client::done, this, _1, _2));
      |                                                    ^~
%(ws)s/src/fib/src/client.cpp:25:56: error: '_2' was not declared in this scope
   25 |     ac_.sendGoal(goal, boost::bind(&Client::done, this, _1, _2));
      |                                                        ^~
make[2]: *** [fib/CMakeFiles/client.dir/build.make:76: fib/CMakeFiles/client.dir/src/client.cpp.o] Error 1
""" % {"ws": WS}


def test_an_ambiguous_placeholder_gets_the_qualify_it_hint():
    lines = summarise(AMBIGUOUS_LOG, WS).splitlines()
    assert lines[1] == "relay/src/relay.cpp:14:62: error: reference to ‘_1’ is ambiguous"
    hints = [line for line in lines if line.startswith("hint:")]
    assert len(hints) == 1 and "std::placeholders::_1 in std::bind" in hints[0]
    assert "using namespace std::placeholders;" in hints[0] and "ROS Noetic" in hints[0]


def test_undeclared_placeholders_get_one_hint_naming_the_first():
    hints = [line for line in summarise(UNDECLARED_LOG, WS).splitlines() if line.startswith("hint:")]
    assert len(hints) == 1, hints
    assert "write boost::placeholders::_1" in hints[0] and "devel/setup.bash" in hints[0]


def test_a_logging_macro_without_its_header_gets_the_include_hint():
    log = UNDECLARED_LOG.replace("'_1' was not declared", "'ROS_INFO' was not declared").replace(
        "'_2' was not declared", "'ROS_ERROR' was not declared")
    hints = [line for line in summarise(log, WS).splitlines() if line.startswith("hint:")]
    assert hints == [hints[0]] and hints[0].startswith("hint: ROS_INFO comes from ros/console.h: add #include <ros/ros.h>")


def test_a_dynamic_exception_specification_gets_the_noexcept_hint():
    log = COMPILE_LOG.replace("'count' was not declared in this scope; did you mean 'std::count'?",
                              "ISO C++17 does not allow dynamic exception specifications")
    hint = summarise(log, WS).splitlines()[-1]
    assert hint.startswith("hint: GCC 12 compiles C++17") and "noexcept" in hint


def test_a_noetic_pluginlib_header_name_gets_its_hpp():
    log = RACE_LOG.replace("-- my_chatter: 1 messages, 0 services\n", "").replace(
        "my_chatter/TimestampString.h", "pluginlib/class_list_macros.h")
    hint = summarise(log, WS).splitlines()[-1]
    assert hint.startswith("hint: Debian 12's pluginlib has no pluginlib/class_list_macros.h")
    assert hint.endswith("#include <pluginlib/class_list_macros.hpp>")


def test_a_name_that_only_looks_like_a_placeholder_gets_no_noetic_hint():
    for name in ("_10", "x_1", "_1a", "ROS"):
        log = UNDECLARED_LOG.replace("'_1'", "'%s'" % name).replace("'_2'", "'%s'" % name)
        assert not [line for line in summarise(log, WS).splitlines() if line.startswith("hint:")], name


FORMAT1_TAGS_LOG = """Base path: %(ws)s
Source space: %(ws)s/src
Creating symlink "%(ws)s/src/CMakeLists.txt" pointing to "/usr/share/catkin/cmake/toplevel.cmake"
Error(s) in package '%(ws)s/src/lab2/src/chatter/package.xml':
Error(s):
- The manifest of package "chatter" (with format version 1) must not contain the following tags: depend, exec_depend
""" % {"ws": WS}

NOT_BUILD_DEPEND_LOG = """-- +++ processing catkin package: 'chatter'
-- ==> add_subdirectory(chatter)
CMake Error at /usr/share/catkin/cmake/catkin_package.cmake:198 (message):
  catkin_package() the catkin package 'rospy' has been find_package()-ed but
  is not listed as a build dependency in the package.xml
Call Stack (most recent call first):
  /usr/share/catkin/cmake/catkin_package.cmake:102 (_catkin_package)
  %(ws)s/src/chatter/CMakeLists.txt:4 (catkin_package)


-- Configuring incomplete, errors occurred!
Invoking "cmake" failed
""" % {"ws": WS}

FORMAT1 = """<?xml version="1.0"?>
<package>
  <name>chatter</name>
  <buildtool_depend>catkin</buildtool_depend>
  <build_depend>std_msgs</build_depend>
  <run_depend>rospy</run_depend>
</package>
"""


def test_format1_tags_of_format2_get_the_format_attribute_hint():
    reason = summarise(FORMAT1_TAGS_LOG, WS)
    assert reason.cause == "package_xml"
    assert "must not contain the following tags: depend, exec_depend" in reason  # catkin's own words kept
    assert "hint: lab2/src/chatter/package.xml is read as format 1" in reason
    assert 'write <package format="2">' in reason and "<depend>, <exec_depend>" in reason
    assert WS not in reason


def test_a_format1_manifest_missing_a_build_dependency_gets_the_format1_tags(tmp_path):
    (tmp_path / "src" / "chatter").mkdir(parents=True)
    (tmp_path / "src" / "chatter" / "package.xml").write_text(FORMAT1)
    reason = summarise(NOT_BUILD_DEPEND_LOG.replace(WS, str(tmp_path)), str(tmp_path))
    assert reason.cause == "package_xml"
    assert "hint: chatter/package.xml is format 1" in reason
    assert "add <build_depend>rospy</build_depend> next to its <run_depend>rospy</run_depend>" in reason


def test_a_format2_manifest_missing_a_dependency_gets_depend(tmp_path):
    (tmp_path / "src" / "chatter").mkdir(parents=True)
    (tmp_path / "src" / "chatter" / "package.xml").write_text(FORMAT1.replace("<package>", '<package format="2">'))
    reason = summarise(NOT_BUILD_DEPEND_LOG.replace(WS, str(tmp_path)), str(tmp_path))
    assert "(format 2) does not list it: add <depend>rospy</depend>" in reason


def test_a_manifest_that_is_a_link_is_not_read_and_both_forms_are_given(tmp_path):
    secret = tmp_path / "secret.xml"
    secret.write_text(FORMAT1.replace("<package>", '<package format="3">'))
    (tmp_path / "ws" / "src" / "chatter").mkdir(parents=True)
    (tmp_path / "ws" / "src" / "chatter" / "package.xml").symlink_to(secret)
    ws = str(tmp_path / "ws")
    reason = summarise(NOT_BUILD_DEPEND_LOG.replace(WS, ws), ws)
    assert "format 3" not in reason
    assert "<depend>rospy</depend> in a <package format=\"2\">, or <build_depend>rospy</build_depend>" in reason


@given(st.text(max_size=300))
@settings(max_examples=200, deadline=None)
def test_any_package_xml_gives_a_format_or_none(text):
    form = package_format(text)
    assert form is None or form >= 0
