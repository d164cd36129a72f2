"""launch_files reads a launch file as roslaunch does (its parameters, how to start one of its
nodes), in a process of its own: the file's $(eval) and <param command> never run in the check's
process, and what that process answers is checked as untrusted data."""
import json
import os
import signal

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from course_milestones import launch_files as lf
from course_milestones.launch_dump import FORMAT
from course_checks.waiting import wait_for

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


def test_roslaunch_args_are_passed(tmp_path):
    path = tmp_path / "args.launch"
    path.write_text('<launch><arg name="scale" default="1.0"/><param name="s" value="$(arg scale)"/></launch>')
    assert lf.params(lf.load(str(path))) == {"/s": 1.0}
    assert lf.params(lf.load(str(path), ["scale:=2.5"])) == {"/s": 2.5}


def writer_pid(path) -> int:
    """The pid a marker file holds, 0 when there is no marker."""
    return int(path.read_text().split()[0]) if path.exists() else 0


def test_the_files_code_never_runs_in_our_process(tmp_path):
    """$(eval) writes its process's pid, <param command> its parent's (the loader's): neither may be ours.
    Sandboxed, the markers may not even be in our /tmp; unsandboxed, another process wrote them."""
    evaluated, commanded = tmp_path / "eval_pid", tmp_path / "command_pid"
    path = tmp_path / "evil.launch"
    path.write_text("""<launch>
  <param name="evaluated" value="$(eval open('%s', 'w').write(open('/proc/self/stat').read().split()[0]))"/>
  <param name="commanded" command="sh -c 'echo $PPID &gt; %s; echo done'"/>
</launch>""" % (evaluated, commanded))
    found = lf.params(lf.load(str(path)))
    assert set(found) == {"/evaluated", "/commanded"} and found["/commanded"].strip() == "done"
    pids = {writer_pid(evaluated), writer_pid(commanded)}
    assert os.getpid() not in pids
    assert pids == {0} or (len(pids) == 1 and 0 not in pids)  # a sandbox's own /tmp, or both by the loader


def test_a_file_roslaunch_refuses_is_a_sentence(tmp_path):
    path = tmp_path / "broken.launch"
    path.write_text('<launch><param name="x" value="$(eval 1/0)"/></launch>')
    with pytest.raises(lf.LaunchFileError, match="roslaunch cannot load broken.launch: .*division by zero"):
        lf.load(str(path))
    path.write_text("<launch><node pkg=")
    with pytest.raises(lf.LaunchFileError, match="roslaunch cannot load broken.launch"):
        lf.load(str(path))


def test_a_command_that_never_ends_is_a_time_out_and_is_ended(tmp_path, monkeypatch):
    seconds = "987.%d" % os.getpid()  # a sleep nobody else runs
    path = tmp_path / "hang.launch"
    path.write_text('<launch><param name="x" command="sleep %s"/></launch>' % seconds)
    monkeypatch.setattr(lf, "LOAD_TIMEOUT_S", 2.0)
    with pytest.raises(lf.LaunchFileError, match="took more than 2 s"):
        lf.load(str(path))
    # killed with SIGKILL when the time is up. A killed process only goes once it is scheduled,
    # which under the suite's fork-bomb samples can take seconds: a SIGKILL pending counts as ended.
    ended = wait_for(lambda: not [pid for pid in os.listdir("/proc")
                                  if pid.isdigit() and sleeping(pid, seconds) and not kill_pending(pid)], 5)
    assert ended, "the command's sleep is still running, not killed, 5 s after the time-out"


def kill_pending(pid: str) -> bool:
    """Whether the process has a SIGKILL waiting to be taken (it dies when next scheduled)."""
    bit = 1 << (signal.SIGKILL - 1)
    try:
        with open("/proc/%s/status" % pid) as f:
            return any(line.startswith(("SigPnd:", "ShdPnd:")) and int(line.split()[1], 16) & bit for line in f)
    except (OSError, ValueError, IndexError):
        return True  # gone


def sleeping(pid: str, seconds: str) -> bool:
    try:
        with open("/proc/%s/cmdline" % pid, "rb") as f:
            return f.read().split(b"\0")[:2] == [b"sleep", seconds.encode()]
    except OSError:
        return False


@pytest.mark.parametrize("code, output, words", [
    (None, b"", "took more than"),
    (0, b"x" * lf.MAX_DUMP_BYTES, "more than"),
    (0, b"", "no answer"),
    (1, b"Traceback ...", "ended with code 1 and no answer"),
    (0, b'{"format": "other/1", "params": {}, "nodes": []}', "no answer"),
    (2, json.dumps({"format": FORMAT, "error": "bad\n  tag"}).encode(), "cannot load the launch file: bad tag"),
    (3, json.dumps({"format": FORMAT, "params": {}, "nodes": []}).encode(), "ended with code 3"),
    (0, json.dumps({"format": FORMAT, "params": {"x": 1}, "nodes": []}).encode(), "not a table of /names"),
    (0, json.dumps({"format": FORMAT, "params": {}, "nodes": {}}).encode(), "not a list"),
    (0, json.dumps({"format": FORMAT, "params": {}, "nodes": [{"package": "p"}]}).encode(), "node 1"),
    (0, b"[" * 100000 + b"]" * 100000, "no answer"),
])
def test_answers_other_than_a_dump_are_sentences(code, output, words):
    with pytest.raises(lf.LaunchFileError) as err:
        lf.parse_dump(code, output)
    assert words in str(err.value)


def good_node(**change):
    node = {"package": "turtlesim", "type": "turtlesim_node", "name": "sim", "namespace": "/a/", "args": "",
            "remap_args": [["x", "y"]], "env_args": []}
    node.update(change)
    return node


@pytest.mark.parametrize("change", [{"package": "../x"}, {"package": ""}, {"type": "../../bin/sh"}, {"type": ".."},
                                    {"name": 3}, {"args": None}, {"remap_args": [["a"]]}, {"env_args": [[1, 2]]},
                                    {"namespace": "a\0b"}])
def test_a_node_with_fields_of_other_types_is_refused(change):
    output = json.dumps({"format": FORMAT, "params": {}, "nodes": [good_node(), good_node(**change)]}).encode()
    with pytest.raises(lf.LaunchFileError, match="node 2 read from"):
        lf.parse_dump(0, output)


def check_valid(config) -> None:
    """What the callers rely on when parse_dump answers."""
    assert isinstance(config, lf.LaunchConfig) and all(k.startswith("/") for k in config.params)
    for node in config.nodes:
        assert all(isinstance(getattr(node, f), str) for f in ("package", "type", "name", "namespace", "args"))
        assert all(isinstance(p, tuple) and len(p) == 2 for p in node.remap_args + node.env_args)


def parse_or_sentence(code, output) -> None:
    try:
        config = lf.parse_dump(code, output)
    except lf.LaunchFileError as err:
        assert str(err)
    else:
        check_valid(config)


@settings(max_examples=300, deadline=None)
@given(st.one_of(st.none(), st.integers(-300, 300)), st.binary(max_size=3000))
def test_any_bytes_are_a_config_or_a_sentence(code, output):
    parse_or_sentence(code, output)


JSON = st.recursive(st.none() | st.booleans() | st.floats() | st.integers() | st.text(max_size=10),
                    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=5), inner, max_size=4),
                    max_leaves=12)
NODE = st.one_of(st.builds(good_node), st.builds(lambda key, value: good_node(**{key: value}),
                                                 st.sampled_from(sorted(good_node())), JSON))


def dump_of(form, params, nodes, error):
    """A launch_dump answer; `error` None leaves the key out."""
    answer = {"format": form, "params": params, "nodes": nodes}
    if error is not None:
        answer["error"] = error
    return answer


DUMP = st.builds(dump_of, st.sampled_from([FORMAT] * 4 + [FORMAT + "x"]),
                 st.one_of(st.dictionaries(st.text(max_size=8).map("/".__add__), JSON, max_size=4), JSON),
                 st.one_of(st.lists(NODE, max_size=3), JSON),
                 st.one_of(st.none(), st.none(), st.none(), JSON))


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from([0, 0, 0, 1, 2]), DUMP)
def test_any_json_is_a_config_or_a_sentence(code, dump):
    parse_or_sentence(code, json.dumps(dump).encode())


def test_dump_values_are_json_whatever_roslaunch_holds():
    """A binfile's bytes, a YAML date, a list holding itself: JSON values, bounded."""
    import datetime
    import xmlrpc.client
    from course_milestones.launch_dump import MAX_DEPTH, plain
    looped = [1]
    looped.append(looped)
    value = plain({"bin": xmlrpc.client.Binary(b"\0\1"), "when": datetime.date(2024, 1, 2), 3: (1.5, None),
                   "looped": looped})
    assert json.loads(json.dumps(value)) == value
    assert value["bin"].startswith("<xmlrpc.client.Binary") and value["when"] == "datetime.date(2024, 1, 2)"
    assert value["3"] == [1.5, None]
    depth, inner = 0, value["looped"]
    while isinstance(inner, list):
        depth, inner = depth + 1, inner[1]
    assert depth == MAX_DEPTH - 1 and isinstance(inner, str)
