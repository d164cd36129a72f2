"""How the text's call fills a student's patrol request: five numbers in the text's order, and the
turtle's name in the one string field of a shared service."""
from hypothesis import given
from hypothesis import strategies as st

from circles import PatrolRequest
from patrol import NUMBER_TYPES, call_words, layout

REQ = PatrolRequest(1.5, -1.0, 8.0, 8.0, -1.0)


def test_a_per_turtle_request_takes_the_five_numbers_in_order_whatever_their_names():
    plan, problem = layout(("v", "w", "px", "py", "heading"), ("float32",) * 5, named_by_service=True)
    assert not problem
    assert plan.arguments("turtle2", REQ) == [1.5, -1.0, 8.0, 8.0, -1.0]
    assert call_words("/turtle2/patrol", plan, "turtle2", REQ) == "rosservice call /turtle2/patrol 1.5 -1 8 8 -1"


def test_a_shared_service_takes_the_name_where_its_string_field_is():
    slots = ("vel", "omega", "name", "x", "y", "theta")
    plan, problem = layout(slots, ("float64", "float64", "string", "float64", "float64", "float64"), False)
    assert not problem and plan.name_field == "name"
    assert plan.arguments("turtle3", REQ) == [1.5, -1.0, "turtle3", 8.0, 8.0, -1.0]
    assert call_words("/patrol", plan, "turtle3", REQ) == "rosservice call /patrol 1.5 -1 turtle3 8 8 -1"


def test_a_shared_service_without_a_name_says_what_its_request_has():
    plan, problem = layout(("vel", "omega", "x", "y", "theta"), ("float32",) * 5, named_by_service=False)
    assert plan is None
    assert problem.startswith("its request names no turtle (vel (float32), omega (float32)")
    assert "/<turtle>/patrol as the text calls it" in problem


def test_a_per_turtle_request_with_other_fields_is_named_field_by_field():
    plan, problem = layout(("vel", "omega"), ("float32", "float32"), named_by_service=True)
    assert plan is None and "vel (float32), omega (float32): the text's call gives it five numbers" in problem


@given(st.lists(st.tuples(st.sampled_from(["a", "b", "c", "d", "e", "f", "g"]),
                          st.sampled_from(NUMBER_TYPES + ("string", "bool", "geometry_msgs/Pose"))),
                max_size=8, unique_by=lambda f: f[0]),
       st.booleans())
def test_any_request_gives_a_plan_that_fills_every_field_or_a_reason(fields, by_service):
    slots, types = [f[0] for f in fields], [f[1] for f in fields]
    plan, problem = layout(slots, types, by_service)
    if plan is None:
        assert problem
        return
    values = plan.arguments("turtle1", REQ)
    assert len(values) == len(slots)
    assert [v for v in values if not isinstance(v, str)] == list(REQ)
    assert values.count("turtle1") == (0 if by_service else 1)
