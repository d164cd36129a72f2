from course_milestones.fields import field_problems

PERSON = {"name": "string", "age": "int32", "height": "float64"}


def test_same_fields_in_any_order_match():
    assert field_problems("Person", PERSON, [("height", "float64"), ("name", "string"), ("age", "int32")]) == []


def test_wrong_type_missing_and_extra_fields_are_named():
    problems = field_problems("Person", PERSON, [("name", "string"), ("age", "float32"), ("weight", "float64")])
    assert "Person: age is float32, the text says int32" in problems
    assert "Person has no field height (float64 height)" in problems
    assert "Person has fields the text does not give: weight" in problems
