import math

import pytest
from hypothesis import given, strategies as st

from course_introspection.plot_fields import PlotField, PlotPathError, Step, expand_shorthand, message_class, \
    fields_of, parse_steps, resolve, split_topic, value_of

NAMES = st.from_regex(r"[A-Za-z][A-Za-z0-9_]{0,8}", fullmatch=True)
STEPS = st.lists(st.builds(Step, NAMES, st.none() | st.integers(0, 999)), min_size=1, max_size=5)
TOPICS = st.lists(NAMES, min_size=1, max_size=3).map(lambda parts: "/" + "/".join(parts))


def labels(fields):
    return [f.label for f in fields]


# --- the argument shorthands -------------------------------------------------------------------

def test_plain_paths_stay():
    assert expand_shorthand(["/turtle1/pose/x", "/turtle1/pose/y"]) == ["/turtle1/pose/x", "/turtle1/pose/y"]


def test_colon_names_sibling_fields():
    assert expand_shorthand(["/turtle1/pose/x:y:theta"]) == [
        "/turtle1/pose/x", "/turtle1/pose/y", "/turtle1/pose/theta"]


def test_comma_joins_several_paths_and_colons_inside():
    assert expand_shorthand(["/a/x:y,/b/z", "/c/w"]) == ["/a/x", "/a/y", "/b/z", "/c/w"]


def test_colon_without_topic_is_an_error():
    with pytest.raises(PlotPathError, match="must start with a topic"):
        expand_shorthand(["x:y"])


@given(TOPICS, st.lists(NAMES, min_size=1, max_size=4))
def test_colon_shorthand_is_the_long_form(topic, fields):
    assert expand_shorthand(["%s/%s" % (topic, ":".join(fields))]) == ["%s/%s" % (topic, f) for f in fields]


@given(st.lists(TOPICS, min_size=1, max_size=5))
def test_comma_joined_paths_split_back(paths):
    assert expand_shorthand([",".join(paths)]) == paths


# --- field path syntax ------------------------------------------------------------------------

def test_steps_with_index():
    assert parse_steps("position[0]") == (Step("position", 0),)
    assert parse_steps("/pose/pose/position/x") == (Step("pose"), Step("pose"), Step("position"), Step("x"))
    assert parse_steps("") == ()


@pytest.mark.parametrize("bad", ["x[", "x]", "x[-1]", "1x", "x[a]", "x.y", "x[0][1]"])
def test_bad_step_is_an_error(bad):
    with pytest.raises(PlotPathError, match="is not a field name"):
        parse_steps("pose/" + bad)


@given(STEPS)
def test_steps_round_trip(steps):
    assert parse_steps("/".join(str(s) for s in steps)) == tuple(steps)


# --- the topic is the longest advertised prefix -----------------------------------------------

def test_longest_topic_wins():
    topics = ["/odom", "/odom/pose", "/turtle1/pose"]
    assert split_topic("/odom/pose/pose/position/x", topics) == ("/odom/pose", "pose/position/x")
    assert split_topic("/odom/twist/twist/linear/x", topics) == ("/odom", "twist/twist/linear/x")
    assert split_topic("/turtle1/pose", topics) == ("/turtle1/pose", "")
    assert split_topic("/nowhere/x", topics) is None


def test_prefix_must_end_at_a_slash():
    assert split_topic("/turtle10/pose/x", ["/turtle1"]) is None


@given(st.lists(TOPICS, min_size=1, max_size=6), STEPS, st.data())
def test_split_finds_longest_segment_prefix(topics, steps, data):
    topic = data.draw(st.sampled_from(topics))
    path = topic + "/" + "/".join(str(s) for s in steps)
    found, rest = split_topic(path, topics)
    assert path.startswith(found + "/") and found in topics
    assert not any(len(t) > len(found) and path.startswith(t + "/") for t in topics)
    assert found + "/" + rest == path


# --- checking paths against message types -----------------------------------------------------

def test_numeric_field():
    assert labels(resolve("/turtle1/pose", "turtlesim/Pose", "x")) == ["/turtle1/pose/x"]


def test_message_means_its_numeric_fields():
    assert labels(resolve("/turtle1/pose", "turtlesim/Pose", "")) == [
        "/turtle1/pose/x", "/turtle1/pose/y", "/turtle1/pose/theta",
        "/turtle1/pose/linear_velocity", "/turtle1/pose/angular_velocity"]


def test_nested_field():
    fields = resolve("/odom", "nav_msgs/Odometry", "pose/pose/position/x")
    assert fields == [PlotField("/odom", (Step("pose"), Step("pose"), Step("position"), Step("x")))]


def test_fixed_array_means_each_element():
    fields = resolve("/odom", "nav_msgs/Odometry", "pose/covariance")
    assert len(fields) == 36 and fields[35].label == "/odom/pose/covariance[35]"


def test_array_element():
    assert labels(resolve("/joint_states", "sensor_msgs/JointState", "position[0]")) == [
        "/joint_states/position[0]"]


def test_time_is_numeric():
    assert labels(resolve("/rosout", "rosgraph_msgs/Log", "header/stamp")) == ["/rosout/header/stamp"]


@pytest.mark.parametrize("topic, type_name, path, message", [
    ("/rosout", "rosgraph_msgs/Log", "name", "/rosout/name is not numeric"),
    ("/rosout", "rosgraph_msgs/Log", "topics", "is not numeric \\(it is a list of strings\\)"),
    ("/turtle1/pose", "turtlesim/Pose", "z", "has no field z \\(turtlesim/Pose has: x, y"),
    ("/turtle1/pose", "turtlesim/Pose", "x/y", "has no field y: /turtle1/pose/x is float32"),
    ("/turtle1/pose", "turtlesim/Pose", "x[0]", "x is float32, not an array"),
    ("/joint_states", "sensor_msgs/JointState", "position", "variable-size array .* like "
                                                            "/joint_states/position\\[0\\]"),
    ("/odom", "nav_msgs/Odometry", "pose/covariance[36]", "has only 36 elements"),
    ("/odom", "nav_msgs/Odometry", "pose", "not numeric .* name one of its fields: pose, covariance"),
    ("/tf", "tf2_msgs/TFMessage", "transforms/transform", "is an array .* give an element"),
    ("/x", "nope_msgs/Nope", "a", "message type nope_msgs/Nope is unknown"),
])
def test_unplottable_paths_say_why(topic, type_name, path, message):
    with pytest.raises(PlotPathError, match=message):
        resolve(topic, type_name, path)


# --- reading the numbers ----------------------------------------------------------------------

def test_values_from_messages():
    odom = message_class("nav_msgs/Odometry")()
    odom.pose.pose.position.x = 2.5
    odom.header.stamp.secs, odom.header.stamp.nsecs = 3, 500000000
    assert value_of(odom, parse_steps("pose/pose/position/x")) == 2.5
    assert value_of(odom, parse_steps("header/stamp")) == 3.5
    joints = message_class("sensor_msgs/JointState")(position=[0.25, -1.0])
    assert value_of(joints, parse_steps("position[1]")) == -1.0
    assert value_of(joints, parse_steps("position[2]")) is None


def test_bool_and_nan_values():
    flag = message_class("std_msgs/Bool")(data=True)
    assert value_of(flag, parse_steps("data")) == 1.0
    number = message_class("std_msgs/Float64")(data=float("nan"))
    assert math.isnan(value_of(number, parse_steps("data")))


TOPICS = {"/turtle1/pose": "turtlesim/Pose", "/rosout": "rosgraph_msgs/Log"}


def test_fields_grouped_by_topic_in_given_order():
    by_topic = fields_of(["/turtle1/pose/y", "/rosout/level", "/turtle1/pose/x"], TOPICS)
    assert {t: [f.label for f in fields] for t, fields in by_topic.items()} == {
        "/turtle1/pose": ["/turtle1/pose/y", "/turtle1/pose/x"], "/rosout": ["/rosout/level"]}


def test_a_field_named_twice_is_plotted_once():
    by_topic = fields_of(["/turtle1/pose/x", "/turtle1/pose", "/turtle1/pose/x"], TOPICS)
    assert [f.label for f in by_topic["/turtle1/pose"]] == [
        "/turtle1/pose/x", "/turtle1/pose/y", "/turtle1/pose/theta", "/turtle1/pose/linear_velocity",
        "/turtle1/pose/angular_velocity"]


def test_a_path_on_no_topic_is_refused():
    with pytest.raises(PlotPathError, match="topic /nowhere/x does not exist"):
        fields_of(["/nowhere/x"], TOPICS)
