"""two_sims: which of the two namespaced turtlesims a launch file started, and the cause when one is missing."""
from course_format import causes

import two_sims


def test_missing_simulators_is_a_wrong_launch():
    assert causes.of(two_sims.missing_simulators({})) == "wrong_launch"
    assert two_sims.missing_simulators(dict.fromkeys(two_sims.NAMESPACES, "/sim")) == ""
