"""course_web.introspect: the answers behind /api/graph, /api/topics and /api/plot, from a fake master."""
from __future__ import annotations

import pytest
from hypothesis import given, settings, strategies as st

from course_web import introspect

STATE = [
    [["/turtle1/pose", ["/turtlesim"]], ["/rosout", ["/turtlesim", "/teleop"]], ["/turtle1/cmd_vel", ["/teleop"]],
     ["/rosout_agg", ["/rosout"]]],
    [["/turtle1/cmd_vel", ["/turtlesim"]], ["/rosout", ["/rosout"]]],
    [],
]
TYPES = {"/turtle1/pose": "turtlesim/Pose", "/turtle1/cmd_vel": "geometry_msgs/Twist",
         "/rosout": "rosgraph_msgs/Log", "/rosout_agg": "rosgraph_msgs/Log",
         "/joint_states": "sensor_msgs/JointState", "/turtlesim/image": "sensor_msgs/Image"}


class FakeMaster:
    dead = ()  # nodes registered that do not answer

    def system_state(self):
        return STATE

    def topic_types(self):
        return dict(TYPES)

    def node_answers(self, name):
        return name not in self.dead


def test_graph_is_rqt_graphs_default_view():
    answer = introspect.graph(FakeMaster())
    assert answer["nodes"] == ["/teleop", "/turtlesim"]
    assert answer["topics"] == [{"name": "/turtle1/cmd_vel", "type": "geometry_msgs/Twist"},
                                {"name": "/turtle1/pose", "type": "turtlesim/Pose"}]
    assert {(e["from"], e["to"]) for e in answer["edges"]} == {
        ("/teleop", "/turtle1/cmd_vel"), ("/turtle1/cmd_vel", "/turtlesim"), ("/turtlesim", "/turtle1/pose")}


def test_graph_shows_rosout_when_asked():
    answer = introspect.graph(FakeMaster(), show_debug=True)
    assert "/rosout" in answer["nodes"] and {"name": "/rosout", "type": "rosgraph_msgs/Log"} in answer["topics"]


def test_topics_are_sorted_with_their_types():
    names = [t["name"] for t in introspect.topics(FakeMaster())["topics"]]
    assert names == sorted(TYPES)


def test_plot_expands_rqt_plots_shorthand():
    fields = introspect.plot_fields(FakeMaster(), "/turtle1/pose/x:y")["fields"]
    assert [(f["topic"], f["label"], f["steps"]) for f in fields] == [
        ("/turtle1/pose", "/turtle1/pose/x", [["x", None]]), ("/turtle1/pose", "/turtle1/pose/y", [["y", None]])]
    assert fields[0]["type"] == "turtlesim/Pose"


def test_plot_takes_several_paths_relative_names_and_indexes():
    fields = introspect.plot_fields(FakeMaster(), "turtle1/cmd_vel/linear/x, /joint_states/position[1]")["fields"]
    assert [f["label"] for f in fields] == ["/turtle1/cmd_vel/linear/x", "/joint_states/position[1]"]
    assert fields[1]["steps"] == [["position", 1]]


def test_a_whole_message_means_its_numbers():
    labels = [f["label"] for f in introspect.plot_fields(FakeMaster(), "/turtle1/pose")["fields"]]
    assert labels == ["/turtle1/pose/%s" % n for n in ("x", "y", "theta", "linear_velocity", "angular_velocity")]


@pytest.mark.parametrize("spec, complaint", [
    ("", "give a field"),
    ("   ", "give a field"),
    (" , ,", "give a field"),
    ("/nowhere/x", "does not exist"),
    ("/turtle1/pose/z", "has no field z"),
    ("/rosout/msg", "not numeric"),
    ("/joint_states/position", "variable-size array"),
    ("/turtle1/pose/x[", "not a field name"),
    ("x:y", "must start with a topic"),
    ("/turtle1/pose/x " * 200, "too long"),
])
def test_bad_plot_requests_say_why(spec, complaint):
    with pytest.raises(introspect.ApiError, match=complaint) as raised:
        introspect.plot_fields(FakeMaster(), spec)
    assert raised.value.status == 400


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=120))
def test_any_plot_text_gives_fields_or_an_api_error(spec):
    try:
        answer = introspect.plot_fields(FakeMaster(), spec)
    except introspect.ApiError as err:
        assert str(err)
    else:
        assert 0 < len(answer["fields"]) <= introspect.MAX_PLOT_FIELDS


class DownMaster:
    def system_state(self):
        raise introspect.ApiError("the ROS master at http://localhost:11311 does not answer: [Errno 111] refused", 503)


class NoTurtlesim(FakeMaster):
    def system_state(self):
        return [[row for row in STATE[0] if row[0] != "/turtlesim/scene"], STATE[1], STATE[2]]


def test_health_says_in_words_that_the_master_or_turtlesim_is_gone():
    with_image = [STATE[0] + [["/turtlesim/scene", ["/turtlesim"]]], STATE[1], STATE[2]]
    master = FakeMaster()
    master.system_state = lambda: with_image
    assert introspect.health(master, "/turtlesim/scene") == {
        "state": "ok", "topic": "/turtlesim/scene", "says": "", "publishers": ["/turtlesim"]}
    assert introspect.health(master, "")["state"] == "ok"  # the canvas's default topic
    gone = introspect.health(NoTurtlesim(), "turtlesim/scene")
    assert gone["state"] == "no-publisher" and gone["topic"] == "/turtlesim/scene"
    assert "turtlesim is not running" in gone["says"] and "rosrun turtlesim turtlesim_node" in gone["says"]
    master.dead = ("/turtlesim",)  # killed by a signal rospy does not catch: registered, silent
    silent = introspect.health(master, "/turtlesim/scene")
    assert silent["state"] == "no-publisher" and "/turtlesim is still registered, but does not answer" in silent["says"]
    down = introspect.health(DownMaster(), "/turtlesim/scene")
    assert down["state"] == "no-master"
    assert down["says"].startswith("The ROS master at http://localhost:11311 does not answer")
    assert "roscore" in down["says"]


def test_health_passes_on_other_failures():
    class Refusing:
        def system_state(self):
            raise introspect.ApiError("not this", 400)
    with pytest.raises(introspect.ApiError):
        introspect.health(Refusing(), "/turtlesim/scene")
