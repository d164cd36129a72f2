"""A value a call saves, named by later steps as ${NAME} (course_format.saved): resolved with its own
type when a string is only the reference, as text inside a longer one, escaped in a regular
expression; the loader says where a reference names nothing saved before it. No ROS."""
import re

import pytest
from hypothesis import given, strategies as st

from course_format import course_file, saved

SAVED = {"first": "turtle2", "second": "turtle3", "x": 2.5, "count": 3}


def test_a_whole_reference_is_the_value_a_longer_string_its_text():
    assert saved.resolve("${x}", SAVED) == 2.5 and saved.resolve("${count}", SAVED) == 3
    assert saved.resolve("/${first}/pose", SAVED) == "/turtle2/pose"
    assert saved.resolve("${first} and ${second} at ${x}", SAVED) == "turtle2 and turtle3 at 2.5"
    assert saved.resolve({"a": ["${first}", 1, {"b": "${second}"}]}, SAVED) == {"a": ["turtle2", 1, {"b": "turtle3"}]}
    assert saved.resolve("no $reference {here}", SAVED) == "no $reference {here}"


def test_in_a_regular_expression_a_saved_value_matches_only_itself():
    assert saved.resolve("^spawned ${v}$", {"v": "a.b(c"}, regex=True) == r"^spawned a\.b\(c$"
    step = saved.resolve_step("prints", {"pattern": "${v}", "node": "${n}"}, {"v": "x+", "n": "talker"})
    assert step == {"pattern": r"x\+", "node": "talker"}
    call = saved.resolve_step("call", {"expect": {"name": {"matches": "^${v}", "differs": "${v}"}},
                                       "request": {"name": "${v}"}}, {"v": "t.1"})
    assert call == {"expect": {"name": {"matches": r"^t\.1", "differs": "t.1"}}, "request": {"name": "t.1"}}
    assert saved.resolve_predicates("param_is", {"equals": "${v}"}, {"v": 7}) == {"equals": 7}


def test_a_parameter_resolved_later_is_left_as_it_is_and_an_unknown_name_is_said():
    later = saved.resolve_step("call", {"expect": {"name2": {"differs": "${first}"}}}, {}, later=("expect",))
    assert later == {"expect": {"name2": {"differs": "${first}"}}}
    with pytest.raises(saved.Unknown) as error:
        saved.resolve("/${frist}/pose", SAVED)
    assert str(error.value) == "${frist}"


@given(st.recursive(st.none() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=12),
                    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=4), inner, max_size=3),
                    max_leaves=8))
def test_a_value_without_references_is_unchanged(value):
    if saved.references(value):
        return
    assert saved.resolve(value, {}) == (list(value) if isinstance(value, tuple) else value)


def test_references_are_found_anywhere_in_a_value_once_each():
    assert saved.references({"a": "${x} ${y}", "b": ["${x}", {"c": "${z}"}], "d": 3}) == ["x", "y", "z"]


COURSE = """name: t
title: t
milestones:
  - id: a
    title: a
    text: a
    packages: [turtle_motions]
    world: [turtlesim]
    steps:
      - call:
          service: /spawn_two
          request: {x1: 2, y1: 3, x2: 8, y2: 9}
          save: {first: name1, second: name2}
          expect: {name1: {nonempty: true}, name2: {differs: "${first}"}}
      - stops_at: {turtle: "${first}", x: 2, y: 3}
      - prints: {node: /x, pattern: "killed ${second}$"}
%s"""


def test_the_loader_takes_saved_values_named_after_their_call(tmp_path):
    path = tmp_path / "course.yaml"
    path.write_text(COURSE % "")
    steps = course_file.load(str(path)).milestones[0].steps
    assert steps[0].params["save"] == {"first": "name1", "second": "name2"}
    assert steps[1].params["turtle"] == "${first}"  # resolved when the step runs (steps.run)


def test_a_reference_to_nothing_saved_before_it_is_an_error_with_its_line(tmp_path):
    path = tmp_path / "course.yaml"
    wrong = ['stops_at: {turtle: "${frist}", x: 1, y: 1}',
             'call: {service: /s, expect: {a: {equals: "${later}"}}}',
             'call: {service: /s, save: {later: a, 2bad: b, empty: ""}}',
             'call: {service: /s, request: {a: "${later}"}, save: {mine: a}}']
    path.write_text(COURSE % "".join("      - %s\n" % step for step in wrong))
    with pytest.raises(course_file.CourseError) as error:
        course_file.load(str(path))
    said = str(error.value)
    assert re.search(r"course.yaml:17: milestones\[0\].steps\[3\].stops_at.turtle: \$\{frist\}: no step before this "
                     r"one saves a value of that name \(did you mean first\?\) \(saved: first, second\)", said), said
    assert "steps[4].call.expect: ${later}: no step before this one saves" in said
    assert "steps[5].call.save.2bad: '2bad': a saved value's name is letters, digits and _" in said
    assert "steps[5].call.save.empty: expected the answer's field" in said
    assert "steps[6].call" not in said  # ${later} is saved by steps[5] (its own errors are its own)
