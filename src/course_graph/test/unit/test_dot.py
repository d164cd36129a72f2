import shutil
from pathlib import Path

import pytest

from course_graph.dot import format_of, graph_to_dot, quote, render, tree_to_dot
from course_introspection.graph_model import Graph


def test_quote_escapes():
    assert quote('a"b\\c\nd') == '"a\\"b\\\\c\\nd"'


def test_graph_to_dot_shapes_and_edges():
    graph = Graph(nodes={"/relay"}, topics={"/turtle1/cmd_vel"}, edges={("/turtle1/cmd_vel", "/relay", "")})
    text = graph_to_dot(graph)
    assert '"/relay" [shape=ellipse];' in text
    assert '"/turtle1/cmd_vel" [shape=box];' in text
    assert '"/turtle1/cmd_vel" -> "/relay";' in text


def test_tree_to_dot_labels():
    text = tree_to_dot([("world", "turtle1", "/broadcaster1\n62.5 Hz")], {"world", "turtle1"}, "TF tree")
    assert '"world" -> "turtle1" [label="/broadcaster1\\n62.5 Hz"];' in text


def test_format_of_refuses_unknown_extensions():
    assert format_of(Path("x.SVG")) == "svg"
    with pytest.raises(ValueError, match=".png"):
        format_of(Path("x.jpg"))


@pytest.mark.skipif(shutil.which("dot") is None, reason="graphviz not installed")
@pytest.mark.parametrize("ext, magic", [("png", b"\x89PNG"), ("svg", b"<?xml"), ("dot", b"digraph")])
def test_render_writes_each_format(tmp_path, ext, magic):
    graph = Graph(nodes={"/a"}, topics={"/t"}, edges={("/a", "/t", "")})
    out = render(graph_to_dot(graph), tmp_path / ("g." + ext))
    assert out.read_bytes().startswith(magic)
