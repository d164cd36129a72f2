"""tools/dockerfile_chroot.py without a chroot: its Dockerfile parser and .dockerignore matcher.

`make docker-check` proves docker/Dockerfile by replaying it in a debootstrap chroot (root,
~15 min); these checks keep the two pieces that must follow Docker's rules honest in a second:
continuations and comments, ENV's two forms, the JSON vs shell CMD, and .dockerignore's `*`,
`**`, leading `/` and `!` exceptions (Docker's, not .gitignore's: `*.pyc` is top-level only).
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TOOL = ROOT / "tools" / "dockerfile_chroot.py"


@pytest.fixture(scope="module")
def tool():
    spec = importlib.util.spec_from_file_location("dockerfile_chroot", TOOL)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while the file runs
    spec.loader.exec_module(module)
    yield module
    sys.modules.pop(spec.name, None)


def keywords(tool, text):
    return [(i.line, i.keyword, i.args) for i in tool.parse_dockerfile(text)]


def test_continuations_join_and_comments_inside_them_vanish(tool):
    text = ("# syntax comment\n"
            "FROM debian:bookworm\n"
            "\n"
            "RUN apt-get update \\\n"
            "# a comment inside the continuation\n"
            "\n"
            " && apt-get install -y make \\   \n"
            " && true\n"
            "run echo lower-case keyword\n")
    assert keywords(tool, text) == [
        (2, "FROM", "debian:bookworm"),
        (4, "RUN", "apt-get update  && apt-get install -y make  && true"),
        (9, "RUN", "echo lower-case keyword"),
    ]


def test_a_trailing_continuation_at_the_end_still_makes_an_instruction(tool):
    assert keywords(tool, "FROM debian:12\nCMD make \\\n") == [(1, "FROM", "debian:12"), (2, "CMD", "make")]


def test_env_key_value_pairs_with_quotes_escapes_and_variables(tool):
    env = {"BASE": "/opt"}
    pairs = tool.env_pairs('A=1 B="two words" C=\'$BASE\' D=$BASE/x E=${BASE}y F=a\\ b G=${NOPE:-dflt}', env)
    assert pairs == [("A", "1"), ("B", "two words"), ("C", "$BASE"), ("D", "/opt/x"), ("E", "/opty"),
                     ("F", "a b"), ("G", "dflt")]


def test_env_legacy_form_keeps_the_rest_of_the_line_as_the_value(tool):
    assert tool.env_pairs("GREETING hello  big world", {}) == [("GREETING", "hello  big world")]


def test_env_rejects_a_word_without_equals_after_pairs(tool):
    with pytest.raises(tool.DockerfileError):
        tool.env_pairs("A=1 B", {})


def test_cmd_json_form_is_an_argv_and_anything_else_is_shell_form(tool):
    assert tool.json_form('["make", "demo"]') == ["make", "demo"]
    assert tool.json_form("make demo") is None
    assert tool.json_form("[ -f x ] && make") is None  # not JSON: a shell test
    assert tool.json_form('["make", 1]') is None  # not all strings: Docker runs it in a shell


def test_unknown_instruction_is_refused_with_its_line(tool):
    instructions = tool.parse_dockerfile("FROM debian:bookworm\nRUN true\nEXPOSE 80\n")
    with pytest.raises(tool.DockerfileError, match="line 3: unsupported instruction EXPOSE"):
        tool.check_instructions(instructions)


def test_only_arg_may_come_before_the_single_from(tool):
    tool.check_instructions(tool.parse_dockerfile("ARG V=1\nFROM debian:bookworm\n"))
    with pytest.raises(tool.DockerfileError, match="line 1: RUN before FROM"):
        tool.check_instructions(tool.parse_dockerfile("RUN true\nFROM debian:bookworm\n"))
    with pytest.raises(tool.DockerfileError, match="one FROM"):
        tool.check_instructions(tool.parse_dockerfile("FROM debian:bookworm\nFROM debian:12\n"))


def test_the_course_dockerfile_parses_with_a_non_root_build_and_the_demo(tool):
    instructions = tool.parse_dockerfile((ROOT / "docker" / "Dockerfile").read_text())
    tool.check_instructions(instructions)
    order = [i.keyword for i in instructions]
    user = order.index("USER")
    assert instructions[user].args != "root" and "RUN" in order[user:]
    assert tool.json_form(instructions[-1].args) == ["make", "demo"]


IGNORE = """\
# comment
.git
/output
**/__pycache__
**/*.pyc
*.log
catkin_ws/build
docs/*.md
!docs/keep.md
data?
"""


@pytest.mark.parametrize("path, excluded", [
    (".git", True),
    (".git/objects/ab/cdef", True),  # a pattern that matches a folder leaves out all it holds
    ("output/demo.png", True),  # leading `/` is the context root
    ("src/output", False),
    ("src/pkg/__pycache__/m.cpython-311.pyc", True),
    ("__pycache__", True),  # `**/` also matches no folder at all
    ("a/b/c.pyc", True),
    ("build.log", True),
    ("catkin_ws/build.log", False),  # `*` stays within one folder: Docker's rule, not .gitignore's
    ("catkin_ws/build/x/y.o", True),
    ("catkin_ws/build_other", False),
    ("docs/guide.md", True),
    ("docs/keep.md", False),  # `!` exception: the last matching pattern decides
    ("docs/sub/guide.md", False),
    ("data1", True),
    ("data12", False),
    ("src/main.py", False),
])
def test_dockerignore_follows_dockers_matching(tool, path, excluded):
    assert tool.DockerIgnore.parse(IGNORE).excluded(path) is excluded


def test_an_exception_reincludes_a_file_inside_an_excluded_folder(tool, tmp_path):
    for name in ("build/a.o", "build/keep/readme", "src/x.py", "src/x.pyc"):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(name)
    ignore = tool.DockerIgnore.parse("build\n!build/keep\n**/*.pyc\n")
    assert sorted(tool.context_paths(tmp_path, ignore)) == ["build/keep", "build/keep/readme", "src", "src/x.py"]


def test_the_course_dockerignore_leaves_out_git_install_and_build_products(tool):
    ignore = tool.DockerIgnore.for_context(ROOT)
    for path in (".git/HEAD", "install/setup.bash", "catkin_ws/install/setup.bash", "catkin_ws/build/Makefile",
                 "catkin_ws/devel/setup.bash", ".venv/bin/python3", "output/demo.png", "grades/report.html",
                 "src/turtlesim/src/turtlesim/__pycache__/x.pyc", "src/turtlebot3_description/MUJOCO_LOG.TXT"):
        assert ignore.excluded(path), path
    for path in ("Makefile", "tools/deps.sh", "tools/apt-packages.txt", "requirements.txt", "catkin_ws/src",
                 "src/turtlesim/package.xml", "docker/Dockerfile"):
        assert not ignore.excluded(path), path


def test_the_context_snapshot_keeps_symlinks_and_leaves_out_ignored_paths(tool, tmp_path):
    context = tmp_path / "context"
    for name in ("src/pkg/a.py", "src/pkg/__pycache__/a.pyc", ".git/HEAD"):
        (context / name).parent.mkdir(parents=True, exist_ok=True)
        (context / name).write_text(name)
    (context / "ws").mkdir()
    (context / "ws" / "src").symlink_to("../src")
    ignore = tool.DockerIgnore.parse(".git\n**/__pycache__\n")
    snapshot = tool.snapshot_context(context, ignore, tmp_path / "snapshot")
    assert sorted(str(p.relative_to(snapshot)) for p in snapshot.rglob("*")) == [
        "src", "src/pkg", "src/pkg/a.py", "ws", "ws/src"]
    assert (snapshot / "ws" / "src").readlink() == Path("../src")
