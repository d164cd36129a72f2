"""Which topic names the relay accepts: those topic_tools relay (roscpp) accepts, minus the ones
the master refuses (empty, the global namespace); every other one ends the program with a message."""
import pytest
import rosgraph.names
from hypothesis import given, settings, strategies as st

from course_relay.args import parse_relay_args
from course_relay.names import topic_name_problem
from course_testkit.fuzz import wild_names

# What Debian's /usr/lib/topic_tools/relay did with each name as OUT_TOPIC (roscpp's validation).
TOPIC_TOOLS_VALID = ["/turtle1/cmd_vel", "turtle1/cmd_vel", "chatter", "~private", "a//b", "a/", "a/_b", "A1_b/c2"]
TOPIC_TOOLS_INVALID = ["a b", "1a", "a-b", "\u00fc", "_a", "a~b", "a.b", "a\nb"]
MASTER_REFUSES = ["", "/", "//"]


@pytest.mark.parametrize("name", TOPIC_TOOLS_VALID)
def test_names_topic_tools_accepts(name):
    assert topic_name_problem(name) is None


@pytest.mark.parametrize("name", TOPIC_TOOLS_INVALID + MASTER_REFUSES)
def test_names_refused_with_a_reason(name):
    assert topic_name_problem(name)


def test_wording_follows_roscpp():
    assert topic_name_problem("a b") == ("Character [ ] at element [1] is not valid in Graph Resource Name "
                                         "[a b]. Valid characters are a-z, A-Z, 0-9, / and _.")
    assert topic_name_problem("1a").startswith("Character [1] is not valid as the first character")


@pytest.mark.parametrize("argv, role", [(["a b", "/out"], "IN_TOPIC"), (["/in", "1a"], "OUT_TOPIC"),
                                        (["/"], "IN_TOPIC")])
def test_cli_exits_with_the_bad_name(argv, role):
    with pytest.raises(SystemExit, match=r"%s \[.*\] is not a valid topic name" % role):
        parse_relay_args(argv)


def names():
    """Wild names, and valid-looking ones with namespaces, ~, doubled and trailing slashes."""
    parts = st.lists(st.from_regex(r"\A[A-Za-z][A-Za-z0-9_]{0,8}\Z"), min_size=1, max_size=3)
    shaped = st.tuples(st.sampled_from(["", "/", "~", "//"]), parts, st.sampled_from(["/", "//"]),
                       st.sampled_from(["", "/"])).map(lambda t: t[0] + t[2].join(t[1]) + t[3])
    return st.one_of(wild_names(), shaped)


@settings(max_examples=500, deadline=None, derandomize=True)
@given(names())
def test_accepted_names_resolve_to_names_the_master_takes(name):
    """Whatever we accept, rospy resolves to a legal name that is not the global namespace."""
    if topic_name_problem(name) is None:
        resolved = rosgraph.names.resolve_name(name, "/ns/relay_1")
        assert rosgraph.names.is_legal_name(resolved) and resolved != "/" and resolved.isascii()


@settings(max_examples=300, deadline=None, derandomize=True)
@given(names(), names())
def test_cli_accepts_or_exits_with_a_message(in_name, out_name):
    argv = [in_name, out_name]
    if ":=" in in_name + out_name:
        return  # a remapping, not a name
    if topic_name_problem(in_name) is None and topic_name_problem(out_name) is None:
        assert parse_relay_args(argv) == (in_name, out_name)
    else:
        with pytest.raises(SystemExit, match="is not a valid topic name"):
            parse_relay_args(argv)


@settings(max_examples=200, deadline=None, derandomize=True)
@given(names())
def test_default_output_of_a_valid_input_is_valid(name):
    if topic_name_problem(name) is None and ":=" not in name:
        assert topic_name_problem(parse_relay_args([name])[1]) is None
