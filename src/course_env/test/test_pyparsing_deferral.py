"""rospy's processes start without pyparsing, and catkin_pkg's conditions still evaluate as upstream's.

Every rospy process imports roslib, hence catkin_pkg.package and catkin_pkg.condition, whose
`import pyparsing` course_env's usercustomize answers with a stand-in until a condition is
evaluated (docs/rospy_limits.md). Fresh interpreters, with the hook and without it
(course_testkit.python_startup): removing the hook makes these tests fail.
"""
from __future__ import annotations

import shutil
from pathlib import Path
from typing import Dict, Iterator

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from course_testkit.python_startup import (DEBIAN_PYTHON, HOOK_STATE, SETUP, Oracle, facts, hooked,  # noqa: F401
                                           upstream, without_hook)

ORACLE = Path(__file__).resolve().parent / "condition_oracle.py"

pytestmark = pytest.mark.skipif(not SETUP.exists(), reason="workspace not built")


@pytest.mark.parametrize("interpreter", ["debian", "workspace"])
@pytest.mark.parametrize("module", ["rospy", "roslaunch", "rostest", "catkin_pkg.package", "roslib.packages"])
def test_rospy_and_its_tools_load_without_pyparsing(hooked, module, interpreter):
    exe = DEBIAN_PYTHON if interpreter == "debian" else shutil.which("python3", path=hooked["PATH"])
    got = facts(hooked, "import %s, catkin_pkg.condition\n%s" % (module, HOOK_STATE), exe)
    assert got["hook_loaded"]
    assert not got["pyparsing"], "%s loaded pyparsing" % module
    assert "PyparsingDeferral" not in got["finders"], "the finder leaves once catkin_pkg.condition is loaded"


def test_without_the_hook_pyparsing_is_loaded(upstream):
    """The control: the same import without the folder loads pyparsing."""
    got = facts(upstream, "import rospy\n" + HOOK_STATE)
    assert got["pyparsing"] and not got["hook_loaded"]


def test_the_first_condition_loads_pyparsing_into_the_module(hooked):
    got = facts(hooked, """
import catkin_pkg.condition as c
facts['none'] = c.evaluate_condition(None, {})
facts['before'] = 'pyparsing' in sys.modules
facts['yes'] = c.evaluate_condition('$ROS_VERSION == 1', {'ROS_VERSION': '1'})
import pyparsing
facts['pp'] = c.pp is pyparsing
facts['infix'] = c.infixNotation is getattr(pyparsing, 'infixNotation')
facts['names'] = sorted(n for n in vars(c) if not n.startswith('__'))
""")
    upstream_names = facts(without_hook(hooked), """
import catkin_pkg.condition as c
facts['names'] = sorted(n for n in vars(c) if not n.startswith('__'))
""")["names"]
    assert got["none"] is True and got["before"] is False, "a None condition needs no pyparsing"
    assert got["yes"] is True and got["pp"] and got["infix"]
    assert got["names"] == upstream_names


def test_pyparsing_first_leaves_condition_as_upstream_has_it(hooked):
    got = facts(hooked, """
import pyparsing
import catkin_pkg.condition as c
facts['pp'] = c.pp is pyparsing
""" + HOOK_STATE)
    assert got["hook_loaded"] and got["pp"]
    assert "PyparsingDeferral" not in got["finders"]


PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>conditional</name>
  <version>0.1.0</version>
  <description>d</description>
  <maintainer email="ta@example.org">TA</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <depend condition="$ROS_VERSION == 1">rospy</depend>
  <depend condition="$ROS_VERSION == 2">rclpy</depend>
  <exec_depend condition="$ROS_PYTHON_VERSION == 3 and $ROS_DISTRO != melodic">python3-yaml</exec_depend>
  <exec_depend>std_msgs</exec_depend>
</package>
"""
EVALUATED = """
from catkin_pkg.package import parse_package_string
package = parse_package_string(%r)
package.evaluate_conditions({'ROS_VERSION': '1', 'ROS_PYTHON_VERSION': '3', 'ROS_DISTRO': 'noetic'})
facts['deps'] = sorted((d.name, d.evaluated_condition) for d in package.exec_depends + package.build_depends)
""" % PACKAGE_XML


def test_a_package_xml_with_conditions_evaluates_as_upstream(hooked, upstream):
    assert facts(hooked, EVALUATED)["deps"] == facts(upstream, EVALUATED)["deps"]
    assert ["python3-yaml", True] in facts(hooked, EVALUATED)["deps"]


@pytest.fixture(scope="module")
def oracles(hooked, upstream) -> Iterator[Dict[str, Oracle]]:
    made = {"hooked": Oracle(ORACLE, hooked, "hooked"), "upstream": Oracle(ORACLE, upstream, "upstream")}
    yield made
    assert {name: oracle.close() for name, oracle in made.items()} == {"hooked": [], "upstream": []}


def test_the_oracles_load_catkin_pkg_as_intended(oracles):
    assert oracles["hooked"].state == {"pyparsing_loaded": False}
    assert oracles["upstream"].state == {"pyparsing_loaded": True}


NAMES = ("A", "B", "ROS_VERSION")
TERMS = st.one_of(st.sampled_from(["$A", "$B", "$ROS_VERSION", "$", "$1x"]),
                  st.sampled_from(["1", "2", "noetic", "a_b-c", '"two words"', "'q'", '""']))
OPERATORS = st.sampled_from(["==", "!=", "<", "<=", ">", ">=", "=", "==="])
COMPARISONS = st.builds(lambda a, op, b: "%s %s %s" % (a, op, b), TERMS, OPERATORS, TERMS)
CONDITIONS = st.one_of(
    st.none(),
    COMPARISONS,
    st.recursive(COMPARISONS, lambda inner: st.one_of(
        st.builds(lambda a, op, b: "%s %s %s" % (a, op, b), inner, st.sampled_from(["and", "or", "AND", "&&"]), inner),
        inner.map(lambda c: "(%s)" % c)), max_leaves=4),
    st.text(max_size=12))
CONTEXTS = st.dictionaries(st.sampled_from(NAMES), st.sampled_from(["1", "2", "noetic", "", "two words"]))


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(condition=CONDITIONS, context=CONTEXTS)
def test_evaluate_condition_says_what_upstream_says(oracles, condition, context):
    assert oracles["hooked"].ask(condition, context) == oracles["upstream"].ask(condition, context)


# A broken hook never stops a start

SABOTAGE = {
    # the finder's state broken before catkin_pkg.condition is looked for
    "finding": "finder = next(f for f in sys.meta_path if type(f).__name__ == 'PyparsingDeferral')\n"
               "finder.modules = None\n",
    # the stand-in cannot be made: the loader's own exec_module runs
    "loading": "import usercustomize\nusercustomize.DependencyStandin = None\n",
}


@pytest.mark.parametrize("where", sorted(SABOTAGE))
def test_an_error_inside_the_hook_falls_back_to_upstream(hooked, where):
    got = facts(hooked, SABOTAGE[where] + """
import rospy
import catkin_pkg.condition as c
facts['yes'] = c.evaluate_condition('$X == 1', {'X': '1'})
""" + HOOK_STATE)
    assert got["hook_loaded"] and got["pyparsing"] and got["yes"] is True
    assert "PyparsingDeferral" not in got["finders"]
