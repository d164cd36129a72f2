"""launch_files reads a launch file as roslaunch does: its parameters, and how to start one of its nodes."""
import os

from course_milestones import launch_files as lf

LAUNCH = """<launch>
  <param name="linear_scale" value="1.0"/>
  <param name="angular_scale" value="0.5"/>
  <param name="cmd_vel_topic_name" value="/cmd_vel"/>
  <group ns="bot">
    <node pkg="turtlesim" type="turtlesim_node" name="teleop" args="--x 1" output="screen">
      <param name="linear_scale" value="3.0"/>
      <remap from="a" to="b"/>
    </node>
  </group>
</launch>
"""


def test_params_and_node(tmp_path):
    path = tmp_path / "t.launch"
    path.write_text(LAUNCH)
    config = lf.load(str(path))
    assert lf.params_named(config, "linear_scale") == {"/linear_scale": 1.0, "/bot/teleop/linear_scale": 3.0}
    assert lf.params_with_value(config, ("cmd_vel", "/cmd_vel")) == {"/cmd_vel_topic_name": "/cmd_vel"}
    assert set(lf.params(config)) == {"/linear_scale", "/angular_scale", "/cmd_vel_topic_name",
                                      "/bot/teleop/linear_scale"}
    node = lf.node_named(config, "/bot/teleop")
    assert node is not None and lf.node_named(config, "/teleop") is None
    command, env = lf.node_command(node)
    assert os.path.basename(command[0]) == "turtlesim_node"
    assert command[1:] == ["--x", "1", "a:=b", "__name:=teleop"]
    assert env == {"ROS_NAMESPACE": "/bot/"} or env == {"ROS_NAMESPACE": "/bot"}


def test_resolve_names_the_missing_file():
    path, reason = lf.resolve("turtlesim", "no_such.launch")
    assert path is None and "no_such.launch" in reason
