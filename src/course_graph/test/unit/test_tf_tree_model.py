import pytest

from course_graph.tf_tree_model import frames_of, parse_frames_yaml, roots_of, tree_edges, tree_text

# Shape of tf2_ros.Buffer.all_frames_as_yaml() for the follow demo plus the static A -> B.
YAML = """
turtle1:
  parent: 'world'
  broadcaster: '/broadcaster1'
  rate: 62.5
  most_recent_transform: 100.5
  oldest_transform: 90.5
  buffer_length: 10.0
turtle2:
  parent: 'world'
  broadcaster: '/broadcaster2'
  rate: 62.4
  most_recent_transform: 100.5
  oldest_transform: 90.5
  buffer_length: 10.0
B:
  parent: 'A'
  broadcaster: '/static_a_b'
  rate: 10000.0
  most_recent_transform: 0.0
  oldest_transform: 0.0
  buffer_length: 0.0
"""


def test_parse_and_roots():
    links = parse_frames_yaml(YAML)
    assert [link.child for link in links] == ["B", "turtle1", "turtle2"]
    assert frames_of(links) == {"A", "B", "world", "turtle1", "turtle2"}
    assert roots_of(links) == ["A", "world"]


def test_edges_say_who_broadcasts_and_how_often():
    edges = tree_edges(parse_frames_yaml(YAML))
    assert ("A", "B", "/static_a_b\nstatic") in edges
    assert ("world", "turtle1", "/broadcaster1\n62.5 Hz") in edges


def test_text_tree():
    assert tree_text(parse_frames_yaml(YAML)) == "A\n  B\nworld\n  turtle1\n  turtle2\n"


@pytest.mark.parametrize("empty", ["", "[]", "{}", "  \n"])
def test_empty_buffer(empty):
    assert parse_frames_yaml(empty) == []
    assert tree_text([]) == ""


def test_not_a_mapping():
    with pytest.raises(ValueError):
        parse_frames_yaml("- a\n- b\n")
