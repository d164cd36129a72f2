"""A data milestone's mutants come from the files its steps start: scripts by name, C++
executables by their sources, launch files and the package's nodes they start, CMakeLists.txt."""
from course_format.milestone import Milestone, Step

from course_lint import used_files
from course_lint.lint import step_names

CMAKE = """project(beginner_tutorials)
add_executable(talker src/talker.cpp)
add_executable(listener EXCLUDE_FROM_ALL src/listener.cpp src/common.cpp)
add_executable(${PROJECT_NAME}_node src/node.cpp)
"""
LAUNCH = """<launch>
  <node pkg="turtlesim" type="turtlesim_node" name="sim"/>
  <node pkg="beginner_tutorials" type="talker.py" name="talker"/>
</launch>
"""
FILES = [("CMakeLists.txt", "cmake", CMAKE), ("launch/demo.launch", "launch", LAUNCH),
         ("scripts/talker.py", "python", ""), ("scripts/listener.py", "python", ""),
         ("src/talker.cpp", "cpp", ""), ("src/listener.cpp", "cpp", ""), ("src/common.cpp", "cpp", "")]


def test_executables_and_launched_nodes():
    assert used_files.executables(CMAKE) == {"talker": ["src/talker.cpp"],
                                             "listener": ["src/listener.cpp", "src/common.cpp"],
                                             "${PROJECT_NAME}_node": ["src/node.cpp"]}
    assert used_files.launched(LAUNCH, "beginner_tutorials") == {"talker.py"}


def test_used_by_script_executable_and_launch_file():
    pkg = "beginner_tutorials"
    assert used_files.used(FILES, {"listener.py"}, pkg) == {"scripts/listener.py", "CMakeLists.txt"}
    assert used_files.used(FILES, {"listener"}, pkg) == {"src/listener.cpp", "src/common.cpp", "CMakeLists.txt"}
    assert used_files.used(FILES, {"demo.launch"}, pkg) == {"launch/demo.launch", "scripts/talker.py", "CMakeLists.txt"}
    assert used_files.used(FILES, {"somebody_elses.py"}, pkg) is None


def test_step_names_are_what_start_steps_run():
    def start(**params):
        return Step("start", dict(params, **{"as": "talker", "find": {"publishes": "/chatter"}}), "course.yaml:3")
    data = Milestone("pubsub", "t", "x", "", ("beginner_tutorials",),
                     steps=(start(rosrun="beginner_tutorials talker.py"), start(roslaunch="beginner_tutorials demo.launch"),
                            Step("publishes", {"topic": "/chatter", "node": "talker"}, "course.yaml:4")))
    assert step_names(data) == {"talker.py", "demo.launch"}
    assert step_names(Milestone("chatter", "t", "x", "chatter.test", ("chatter",))) == set()


def test_a_data_milestone_that_starts_nothing_is_linted_on_its_build_only():
    """interfaces: one `generated` step; the package's nodes are no part of it."""
    built = Milestone("interfaces", "t", "x", "", ("pkg_interfaces",),
                      steps=(Step("generated", {"messages": ["pkg_interfaces/Person"]}, "course.yaml:3"),))
    assert step_names(built) == {"CMakeLists.txt"}
    files = [("CMakeLists.txt", "cmake", "add_message_files(FILES Person.msg)"), ("nodes/add_server", "python", "")]
    assert used_files.used(files, step_names(built), "pkg_interfaces") == {"CMakeLists.txt"}


def test_a_file_left_out_of_the_build_is_a_mutant_only_where_the_steps_use_the_package_s_types():
    from course_lint.lint import names_own_types
    talk = Milestone("pubsub", "t", "x", "", ("beginner_tutorials",),
                     steps=(Step("publishes", {"topic": "/chatter", "type": "std_msgs/String"}, "c:1"),))
    add = Milestone("add", "t", "x", "", ("beginner_tutorials",),
                    steps=(Step("generated", {"services": ["beginner_tutorials/AddTwoInts"]}, "c:1"),))
    assert not names_own_types(talk, "beginner_tutorials") and names_own_types(add, "beginner_tutorials")
