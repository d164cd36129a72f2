import pytest

from course_introspection.graph_model import GraphOptions, SystemState, build_graph, in_namespace

# What getSystemState() answers for two_turtles.launch plus a teleop on /turtle1/cmd_vel.
MASTER_STATE = [
    [["/rosout", ["/turtlesim1/turtlesim", "/turtlesim2/turtlesim", "/turtlesim1/relay", "/turtlesim2/relay",
                  "/teleop"]],
     ["/rosout_agg", ["/rosout"]],
     ["/turtle1/cmd_vel", ["/teleop"]],
     ["/turtlesim1/turtle1/cmd_vel", ["/turtlesim1/relay"]],
     ["/turtlesim2/turtle1/cmd_vel", ["/turtlesim2/relay"]],
     ["/turtlesim1/turtle1/pose", ["/turtlesim1/turtlesim"]],
     ["/turtlesim2/turtle1/pose", ["/turtlesim2/turtlesim"]]],
    [["/rosout", ["/rosout"]],
     ["/turtle1/cmd_vel", ["/turtlesim1/relay", "/turtlesim2/relay"]],
     ["/turtlesim1/turtle1/cmd_vel", ["/turtlesim1/turtlesim"]],
     ["/turtlesim2/turtle1/cmd_vel", ["/turtlesim2/turtlesim"]]],
    [["/turtlesim1/spawn", ["/turtlesim1/turtlesim"]]],
]
STATE = SystemState.from_master(MASTER_STATE)


def test_default_view_has_nodes_topics_and_directed_edges():
    graph = build_graph(STATE)
    assert graph.nodes == {"/turtlesim1/turtlesim", "/turtlesim2/turtlesim", "/turtlesim1/relay",
                           "/turtlesim2/relay", "/teleop"}
    assert "/turtle1/cmd_vel" in graph.topics
    assert ("/teleop", "/turtle1/cmd_vel", "") in graph.edges
    assert ("/turtle1/cmd_vel", "/turtlesim1/relay", "") in graph.edges
    assert ("/turtlesim1/relay", "/turtlesim1/turtle1/cmd_vel", "") in graph.edges


def test_debug_is_hidden_unless_asked():
    assert "/rosout" not in build_graph(STATE).nodes | build_graph(STATE).topics
    shown = build_graph(STATE, GraphOptions(hide_debug=False))
    assert "/rosout" in shown.nodes and "/rosout_agg" in shown.topics


def test_active_only_drops_topics_nobody_reads():
    graph = build_graph(STATE, GraphOptions(active_only=True))
    assert "/turtlesim1/turtle1/pose" not in graph.topics
    assert "/turtlesim1/turtle1/cmd_vel" in graph.topics


def test_nodes_only_labels_edges_with_topics():
    graph = build_graph(STATE, GraphOptions(nodes_only=True))
    assert graph.topics == set()
    assert ("/teleop", "/turtlesim2/relay", "/turtle1/cmd_vel") in graph.edges
    assert ("/turtlesim1/relay", "/turtlesim1/turtlesim", "/turtlesim1/turtle1/cmd_vel") in graph.edges
    assert len(graph.edges) == 4


def test_topics_only_links_topics_through_relays():
    graph = build_graph(STATE, GraphOptions(topics_only=True))
    assert graph.nodes == set()
    assert ("/turtle1/cmd_vel", "/turtlesim1/turtle1/cmd_vel", "/turtlesim1/relay") in graph.edges
    assert ("/turtle1/cmd_vel", "/turtlesim2/turtle1/cmd_vel", "/turtlesim2/relay") in graph.edges
    # turtlesim itself turns cmd_vel into pose
    assert ("/turtlesim1/turtle1/cmd_vel", "/turtlesim1/turtle1/pose", "/turtlesim1/turtlesim") in graph.edges
    assert len(graph.edges) == 4


def test_namespace_filter_keeps_the_namespace_and_its_inputs():
    graph = build_graph(STATE, GraphOptions(namespaces=("turtlesim1",)))
    assert graph.nodes == {"/turtlesim1/turtlesim", "/turtlesim1/relay"}
    assert "/turtle1/cmd_vel" in graph.topics  # the relay's input, outside the namespace
    assert not any("/turtlesim2" in a or "/turtlesim2" in b for a, b, _ in graph.edges)
    assert ("/teleop", "/turtle1/cmd_vel", "") not in graph.edges


def test_in_namespace_matches_whole_segments():
    assert in_namespace("/turtlesim1/relay", ["/turtlesim1/"])
    assert not in_namespace("/turtlesim10/relay", ["turtlesim1"])
    assert in_namespace("/anything", [])
    assert in_namespace("/anything", ["/"])


def test_the_two_views_exclude_each_other():
    with pytest.raises(ValueError, match="choose one"):
        GraphOptions(nodes_only=True, topics_only=True)


def test_empty_master():
    graph = build_graph(SystemState.from_master([[], [], []]))
    assert (graph.nodes, graph.topics, graph.edges) == (set(), set(), set())
