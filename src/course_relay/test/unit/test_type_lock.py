"""The relay forwards the first type it sees and warns, throttled per type, about the others."""
from hypothesis import given, settings, strategies as st

from course_relay.type_lock import TypeLock

STRING = {"type": "std_msgs/String", "md5sum": "992ce8a1687cec8c8bd883ec73ca41d1"}
FLOAT64 = {"type": "std_msgs/Float64", "md5sum": "fdb28210bfa9d7c91146260178d9a584"}
TWIST = {"type": "geometry_msgs/Twist", "md5sum": "9f195f881246fdfa2798d1d3eebca84a"}
STRING_CHANGED = {"type": "std_msgs/String", "md5sum": "0" * 32}


def test_locks_onto_the_first_type():
    lock = TypeLock(5.0)
    assert lock.admits(STRING)
    assert not lock.admits(FLOAT64)
    assert not lock.admits(STRING_CHANGED)  # same name, other definition
    assert lock.admits(STRING)


def test_warnings_throttled_per_type():
    lock = TypeLock(5.0)
    lock.admits(STRING)
    assert lock.warning_due(FLOAT64, 100.0)
    assert not lock.warning_due(FLOAT64, 104.9)
    assert lock.warning_due(TWIST, 104.9)  # another type is reported at once
    assert lock.warning_due(FLOAT64, 105.0)


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.lists(st.tuples(st.sampled_from([STRING, FLOAT64, TWIST, STRING_CHANGED]),
                          st.floats(0, 3)), min_size=1, max_size=40))
def test_admits_exactly_the_first_type(arrivals):
    """For any arrival sequence: only the first type passes, and warnings per type are >= a period apart."""
    lock, now, warned = TypeLock(5.0), 0.0, {}
    first = arrivals[0][0]
    for header, gap in arrivals:
        now += gap
        assert lock.admits(header) == (header == first)
        if header != first and lock.warning_due(header, now):
            key = header["md5sum"]
            assert now - warned.get(key, -10.0) >= 5.0
            warned[key] = now
