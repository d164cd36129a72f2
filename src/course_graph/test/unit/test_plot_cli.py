import pytest

from course_graph.plot_cli import PlotError, output_path, parse_args, requested_paths
from course_introspection.plot_fields import PlotPathError

def test_defaults():
    args = parse_args(["/turtle1/pose/x"])
    assert (args.output, args.seconds, args.wait) == (None, 10.0, 5.0)


@pytest.mark.parametrize("bad", [["--seconds", "0", "/a/x"], ["--span", "-1", "/a/x"], []])
def test_bad_arguments_exit_2(bad, capsys):
    with pytest.raises(SystemExit) as ended:
        parse_args(bad)
    assert ended.value.code == 2


def test_relative_names_resolve_in_the_namespace(monkeypatch):
    monkeypatch.setenv("ROS_NAMESPACE", "/robot1")
    assert requested_paths(["turtle1/pose/x:y", "/abs/z"]) == [
        "/robot1/turtle1/pose/x", "/robot1/turtle1/pose/y", "/abs/z"]


def test_syntax_errors_come_before_any_wait():
    with pytest.raises(PlotPathError):
        requested_paths(["/turtle1/pose/x["])


def test_output_folder_and_format_checked_first(tmp_path):
    assert output_path(str(tmp_path / "p.png")) == tmp_path / "p.png"
    with pytest.raises(PlotError, match="no folder"):
        output_path(str(tmp_path / "missing" / "p.png"))
    with pytest.raises(PlotError, match="cannot write .xyz"):
        output_path(str(tmp_path / "p.xyz"))
