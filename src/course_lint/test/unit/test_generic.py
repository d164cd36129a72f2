"""--mutmut: generic Python mutants from mutmut 2 where it is installed, else a clear refusal."""
import ast
import importlib.util

import pytest

from course_lint import generic
from course_lint.mutants import PYTHON

TALKER = '''import rospy
from std_msgs.msg import String

pub = rospy.Publisher("chatter", String, queue_size=10)
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    pub.publish("hello %d" % (1 + 2))
    rate.sleep()
'''


def mutmut_2() -> bool:
    try:
        generic.load_mutmut()
        return True
    except generic.Unavailable:
        return False


@pytest.mark.skipif(not mutmut_2(), reason='mutmut 2 is not installed (pip install "mutmut<3")')
def test_mutmut_mutants_differ_and_parse():
    texts = generic.operator().sites[PYTHON](TALKER)
    assert len(texts) >= 4 and TALKER not in texts
    for text in texts:
        ast.parse(text)
    assert any('"XXchatterXX"' in t for t in texts)
    assert generic.operator().sites[PYTHON]("def (:\n") == []


@pytest.mark.skipif(importlib.util.find_spec("mutmut") is not None, reason="mutmut is installed")
def test_without_mutmut_it_says_how_to_install_it():
    with pytest.raises(generic.Unavailable, match='mutmut<3'):
        generic.operator()
