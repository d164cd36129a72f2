"""The mutant operators on small, realistic sources: each mutates where it should, keeps the rest,
and a Python mutant still parses; on any text they neither raise nor return the original."""
import ast
import os

from hypothesis import given, settings, strategies as st

from course_lint import mutants, python_sites as py, text_sites as tx

TALKER = '''#!/usr/bin/env python3
import rospy
from std_msgs.msg import String


def talker():
    pub = rospy.Publisher("chatter", String, queue_size=10)
    rate = rospy.Rate(10)  # 10 Hz
    while not rospy.is_shutdown():
        pub.publish("hello world %s" % rospy.get_time())  # one message
        rate.sleep()


if __name__ == "__main__":
    rospy.init_node("talker", anonymous=True)
    talker()
'''

LISTENER = '''#!/usr/bin/env python3
import rospy
from std_msgs.msg import String

TOPIC = "/chatter"


def callback(msg):
    rospy.loginfo("I heard %s", msg.data)


rospy.init_node("listener")
rospy.Subscriber(TOPIC, String, callback)
rospy.spin()
'''

SERVER = '''#!/usr/bin/env python3
import rospy
from beginner_tutorials.srv import AddTwoInts, AddTwoIntsResponse


def handle_add_two_ints(req):
    return AddTwoIntsResponse(req.a + req.b)


def add_two_ints_server():
    rospy.init_node("add_two_ints_server")
    rospy.Service("add_two_ints", AddTwoInts, handle_add_two_ints)
    rospy.spin()


add_two_ints_server()
'''

TURTLE = '''#!/usr/bin/env python3
import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose
from turtlesim.srv import SetPen


class Drawer:
    def __init__(self):
        self.speed = rospy.get_param("~speed", 2.0)
        self.pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        self.set_pen = rospy.ServiceProxy("/turtle1/set_pen", SetPen)
        rospy.Subscriber("/turtle1/pose", Pose, self.on_pose)

    def on_pose(self, pose):
        if pose.x > 9.0 or pose.y > 9.0:
            self.set_pen(255, 0, 0, 3, 0)
        rospy.loginfo("at %.1f %.1f", pose.x, pose.y)
        cmd = Twist()
        cmd.linear.x = self.speed
        self.pub.publish(cmd)
'''

CPP_TALKER = '''#include "ros/ros.h"
#include "std_msgs/String.h"

int main(int argc, char **argv) {
  ros::init(argc, argv, "talker");
  ros::NodeHandle n;
  ros::Publisher chatter_pub = n.advertise<std_msgs::String>("chatter", 1000);
  ros::Subscriber sub = n.subscribe("/turtle1/pose", 10, poseCallback);
  ros::Rate loop_rate(10);
  while (ros::ok()) {
    std_msgs::String msg;
    msg.data = "hello world";
    chatter_pub.publish(msg);
    ros::spinOnce();
    loop_rate.sleep();
  }
  ros::spin();
  return 0;
}
'''

CMAKE = '''cmake_minimum_required(VERSION 3.0.2)
project(pkg_interfaces)
find_package(catkin REQUIRED COMPONENTS message_generation std_msgs actionlib_msgs)
add_message_files(FILES Person.msg Num.msg)
add_service_files(
  FILES
  Add.srv
)
generate_messages(DEPENDENCIES std_msgs actionlib_msgs)
'''

LAUNCH = '''<launch>
  <!-- <remap from="a" to="commented_out"/> -->
  <node pkg="turtlesim" type="turtlesim_node" name="sim">
    <remap from="/turtle1/cmd_vel" to="/cmd_vel"/>
    <param name="background_r" value="255"/>
    <param name="scale" value="0.5"/>
    <param name="enabled" type="bool" value="true"/>
    <param name="frame" value="odom"/>
  </node>
</launch>
'''


def changed_lines(old: str, new: str):
    return [(a, b) for a, b in zip(old.splitlines(), new.splitlines()) if a != b]


def python_ok(texts):
    for text in texts:
        ast.parse(text)
    return texts


def test_topic_renamed_python_literal_constant_and_format():
    pub, = python_ok(py.topic_renamed(TALKER))
    assert changed_lines(TALKER, pub) == [(
        '    pub = rospy.Publisher("chatter", String, queue_size=10)',
        '    pub = rospy.Publisher("chatter_mutant", String, queue_size=10)')]
    sub, = python_ok(py.topic_renamed(LISTENER))
    assert 'TOPIC = "/chatter_mutant"' in sub
    formatted = python_ok(py.topic_renamed('rospy.Publisher("/%s/cmd_vel" % name, Twist)\n'
                                           "rospy.Service(f'/{n}/patrol', Patrol, handle)\n"))
    assert '"/%s/cmd_vel_mutant" % name' in formatted[0] and "f'/{n}/patrol_mutant'" in formatted[1]


def test_topic_renamed_turtle_names_every_registration():
    renamed = python_ok(py.topic_renamed(TURTLE))
    assert ['"/turtle1/cmd_vel_mutant"' in t for t in renamed] == [True, False, False]
    assert '"/turtle1/set_pen_mutant"' in renamed[1] and '"/turtle1/pose_mutant"' in renamed[2]


def test_type_changed():
    pub, = python_ok(py.type_changed(TALKER))
    assert 'rospy.Publisher("chatter", __import__("std_msgs.msg").msg.Empty, queue_size=10)' in pub
    empty, = python_ok(py.type_changed('rospy.Subscriber("a", data_class=Empty, callback=cb)\n'))
    assert "data_class=__import__(\"std_msgs.msg\").msg.String" in empty


def test_exit_after_one_keeps_the_indentation_and_the_comment():
    exits, = python_ok(py.exit_after_one(TALKER))
    lines = exits.splitlines()
    at = lines.index('        pub.publish("hello world %s" % rospy.get_time())  # one message')
    assert lines[at + 1] == "        " + py.EXIT_NOW
    assert py.exit_after_one("if ok: pub.publish(m)\n") == []  # not a line of its own
    assert py.exit_after_one("pub.publish(m); x = 1\n") == []


def test_publish_removed_and_no_spin():
    removed, = python_ok(py.publish_removed(TALKER))
    assert changed_lines(TALKER, removed) == [(
        '        pub.publish("hello world %s" % rospy.get_time())  # one message', "        pass  # one message")]
    no_spin, = python_ok(py.no_spin(LISTENER))
    assert no_spin.endswith("callback)\npass\n")
    assert py.no_spin(TALKER) == []


def test_rate_div10():
    slow, = python_ok(py.rate_div10(TALKER))
    assert "rate = rospy.Rate(1.0)  # 10 Hz" in slow
    expr, = python_ok(py.rate_div10("r = rospy.Rate(hz=1.0 / period)\n"))
    assert expr == "r = rospy.Rate(hz=(1.0 / period) / 10)\n"


def test_swap_xy_per_line_and_not_in_a_log_of_a_node_that_acts():
    swapped = python_ok(py.swap_xy(TURTLE))
    assert [changed_lines(TURTLE, s) for s in swapped] == [
        [("        if pose.x > 9.0 or pose.y > 9.0:", "        if pose.y > 9.0 or pose.x > 9.0:")],
        [("        cmd.linear.x = self.speed", "        cmd.linear.y = self.speed")]]
    printer = 'rospy.loginfo("X: %.2f, Y: %.2f" % (msg.x, msg.y))\n'
    assert py.swap_xy(printer) == ['rospy.loginfo("X: %.2f, Y: %.2f" % (msg.y, msg.x))\n']


def test_pen_off_inverts_the_colour():
    off, = python_ok(py.pen_off(TURTLE))
    assert "self.set_pen(0, 255, 255, 3, 0)" in off
    keywords, = python_ok(py.pen_off("set_pen(r=red, g=0, b=blue, width=2, off=0)\n"))
    assert keywords == "set_pen(r=255 - (red), g=255, b=255 - (blue), width=2, off=0)\n"
    assert py.pen_off("items.append(3)\nf = open('x')\n") == []


def test_param_ignored_uses_the_default():
    ignored, = python_ok(py.param_ignored(TURTLE))
    assert "self.speed = (2.0)" in ignored
    assert py.param_ignored('name = rospy.get_param("~name")\n') == []


def test_service_wrong_answers_an_empty_response():
    wrong, = python_ok(py.service_wrong(SERVER))
    assert changed_lines(SERVER, wrong) == [("    return AddTwoIntsResponse(req.a + req.b)", "    return AddTwoIntsResponse()")]
    plain, = python_ok(py.service_wrong('class S:\n    def h(self, req):\n        return req.a + req.b\n'
                                        '    def go(self):\n        rospy.Service("s", Add, self.h)\n'))
    assert "return type(req.a + req.b)()" in plain
    assert py.service_wrong('def h(req):\n    return EmptyResponse()\nrospy.Service("e", Empty, h)\n') == []


def test_cpp_operators():
    renamed = tx.cpp_topic_renamed(CPP_TALKER)
    assert 'advertise<std_msgs::String>("chatter_mutant", 1000)' in renamed[0]
    assert 'subscribe("/turtle1/pose_mutant", 10' in renamed[1]
    slow, = tx.cpp_rate_div10(CPP_TALKER)
    assert "ros::Rate loop_rate((10) / 10.0);" in slow
    no_spin, = tx.cpp_no_spin(CPP_TALKER)
    assert "ros::spin();" not in no_spin and "ros::spinOnce();" in no_spin
    exits, = tx.cpp_exit_after_one(CPP_TALKER)
    assert "chatter_pub.publish(msg); std::exit(0);" in exits
    removed, = tx.cpp_publish_removed(CPP_TALKER)
    assert changed_lines(CPP_TALKER, removed) == [("    chatter_pub.publish(msg);", "    ;  // course-lint: publish removed")]
    assert tx.cpp_swap_xy("p.x = q->y;\nz = p.x();\n") == ["p.y = q->x;\nz = p.x();\n"]


def test_msg_left_out_removes_one_file_each():
    left_out = tx.msg_left_out(CMAKE)
    assert len(left_out) == 3
    assert "add_message_files(FILES Num.msg)" in left_out[0]
    assert "add_message_files(FILES Person.msg)" in left_out[1]
    assert "add_service_files(\n  FILES\n)" in left_out[2]
    assert tx.msg_left_out("add_message_files(DIRECTORY msg)\n") == []


def test_launch_remap_and_params():
    remapped, = tx.remap_renamed(LAUNCH)
    assert '<remap from="/turtle1/cmd_vel" to="/cmd_vel_mutant"/>' in remapped
    assert 'to="commented_out"' in remapped
    changed = tx.param_changed(LAUNCH)
    assert ['value="155"' in changed[0], 'value="1.0"' in changed[1], 'value="false"' in changed[2],
            'value="odom_mutant"' in changed[3]] == [True] * 4


def test_a_launch_files_nodes_are_left_out_one_at_a_time_with_their_bodies():
    text = """<launch>
  <!-- <node pkg="x" type="commented" name="c"/> -->
  <node name='teleop' pkg='turtlesim' type='turtle_teleop_key' output="screen"/>
  <group ns="turtlesim1">
    <node pkg="turtlesim" type="turtlesim_node" name="turtlesim">
      <param name="background_r" value="255"/>
    </node>
    <node pkg="topic_tools" type="relay" name="relay" args="/turtle1/cmd_vel /turtlesim1/turtle1/cmd_vel"/>
  </group>
</launch>
"""
    found = tx.node_left_out(text)
    assert len(found) == 3  # the commented-out node is no site
    assert "turtle_teleop_key" not in found[0] and "turtlesim_node" in found[0]
    assert "turtlesim_node" not in found[1] and "background_r" not in found[1] and "</group>" in found[1]
    assert "relay" not in found[2].split("-->", 1)[1] and "turtle_teleop_key" in found[2]
    for mutant in found:
        assert mutant.count("\n") < text.count("\n")  # whole lines go, no blank line is left
        assert "<launch>" in mutant and "</launch>" in mutant


def write(folder, path, text, mode=0o644):
    full = os.path.join(folder, path)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, "w") as f:
        f.write(text)
    os.chmod(full, mode)


def test_package_mutants_walks_kinds_caps_and_notes(tmp_path):
    pkg = str(tmp_path / "demo")
    write(pkg, "nodes/talker", TALKER, 0o755)  # a script found by its shebang
    write(pkg, "src/listener.py", LISTENER)
    write(pkg, "src/talker.cpp", CPP_TALKER)
    write(pkg, "CMakeLists.txt", CMAKE)
    write(pkg, "launch/sim.launch", LAUNCH)
    write(pkg, "scripts/broken.py", "def (:\n")
    write(pkg, "test/test_talker.py", TALKER)  # tests are no code a milestone runs
    write(pkg, "setup.py", TALKER)
    found, notes = mutants.package_mutants(pkg)
    assert notes == ["demo/scripts/broken.py: not Python that parses: no Python mutants"]
    by_op = {}
    for m in found:
        by_op.setdefault(m.operator.name, []).append(m)
    assert all(len(ms) <= mutants.CAP for ms in by_op.values())
    assert {m.path for m in found} == {"nodes/talker", "src/listener.py", "src/talker.cpp", "CMakeLists.txt",
                                       "launch/sim.launch"}
    assert [(m.path, m.line) for m in by_op["topic_renamed"]] == [
        ("launch/sim.launch", 4), ("src/listener.py", 5), ("src/talker.cpp", 8)]  # 5 sites, spread
    assert by_op["msg_left_out"][0].changed == "add_message_files(FILES Num.msg)"
    only, _ = mutants.package_mutants(pkg, mutants.by_names(["no_spin"]))
    assert [(m.path, m.changed) for m in only] == [("src/listener.py", "pass"), ("src/talker.cpp", "/* course-lint: no spin */;")]


def test_unknown_operator_is_named():
    try:
        mutants.by_names(["no_spin", "teleport"])
    except ValueError as err:
        assert "teleport" in str(err)
    else:
        raise AssertionError("no error for an unknown operator")


SOURCES = st.one_of(st.text(max_size=300), st.sampled_from([TALKER, LISTENER, SERVER, TURTLE, CPP_TALKER, CMAKE, LAUNCH]),
                    st.lists(st.sampled_from(TURTLE.splitlines(keepends=True) + CPP_TALKER.splitlines(keepends=True)
                                             + LAUNCH.splitlines(keepends=True)), max_size=12).map("".join))


@settings(max_examples=150, deadline=None)
@given(SOURCES, st.sampled_from([mutants.PYTHON, mutants.CPP, mutants.CMAKE, mutants.LAUNCH]))
def test_operators_never_raise_and_never_return_the_original(text, kind):
    for operator in mutants.OPERATORS:
        for new in mutants.mutated_texts(operator, kind, text):
            assert new != text
            if kind == mutants.PYTHON:
                ast.parse(new)
