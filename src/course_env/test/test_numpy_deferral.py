"""rospy's processes start without numpy, and genpy's check_type() still says what upstream says.

course_env's env hook puts lib/course_env/python_startup on PYTHONPATH; its usercustomize lets
genpy.message load without numpy when numpy is not loaded yet (docs/rospy_limits.md). Every check
runs fresh interpreters in the environment a new shell has after `source catkin_ws/devel/setup.bash`,
started from this process's environment with the hook's folder taken out, so that removing the
hook (the module or the env hook's lines) makes these tests fail. Upstream's behaviour is that of
the same environment without the folder.
"""
from __future__ import annotations

import json
import os
import pwd
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Dict, Iterator

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from course_sandbox import levels
from course_sandbox.policy import DEFAULT_USER, Policy
from course_sandbox.run import RunSandbox
from course_testkit.python_startup import (DEBIAN_PYTHON, HOOK_STATE, SETUP, SOLUTIONS_SETUP, STARTUP, TIMEOUT_S,  # noqa: F401
                                           Oracle, facts, hooked, upstream, without_hook)

ROOT = Path(__file__).resolve().parents[3]
ORACLE = Path(__file__).resolve().parent / "check_type_oracle.py"

pytestmark = pytest.mark.skipif(not SETUP.exists(), reason="workspace not built")


# The path, sourced again and chained


def test_the_folder_is_on_pythonpath_once_however_often_sourced():
    start = without_hook(dict(os.environ))
    steps = [SETUP, SETUP] + ([SOLUTIONS_SETUP, SOLUTIONS_SETUP, SETUP, SOLUTIONS_SETUP]
                              if SOLUTIONS_SETUP.exists() else [])
    script = "".join('source "%s" >/dev/null; echo "$PYTHONPATH"; ' % step for step in steps)
    done = subprocess.run(["bash", "-c", script], env=start, capture_output=True, text=True, timeout=TIMEOUT_S)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert len(lines) == len(steps)
    for step, line in zip(steps, lines):
        entries = line.split(os.pathsep)
        assert entries.count(STARTUP) == 1, "after sourcing %s: %s" % (step, line)
        assert [e for e in entries if e.endswith("python_startup")] == [STARTUP], line
    assert set(os.listdir(STARTUP)) - {"__pycache__"} == {"usercustomize.py"}, "the folder holds usercustomize alone"


# rospy's processes without numpy


@pytest.mark.parametrize("interpreter", ["debian", "workspace"])
@pytest.mark.parametrize("module", ["rospy", "rostopic", "roslaunch", "rosservice", "rosnode", "std_msgs.msg"])
def test_rospy_and_its_tools_load_without_numpy(hooked, module, interpreter):
    exe = DEBIAN_PYTHON if interpreter == "debian" else shutil.which("python3", path=hooked["PATH"])
    got = facts(hooked, "import %s, genpy.message\n%s" % (module, HOOK_STATE), exe)
    assert got["hook_loaded"]
    assert not got["numpy"], "%s loaded numpy" % module
    assert "NumpyDeferral" not in got["finders"], "the finder leaves once genpy.message is loaded"


MODULE_FACE = """
import inspect
import genpy.message as m
facts['face'] = [type(m.__loader__).__name__, type(m.__spec__.loader).__name__, m.__file__, m.__cached__,
                 inspect.getsource(m.check_type).splitlines()[0], sorted(n for n in vars(m) if n != 'np')]
"""


def test_genpy_message_looks_as_upstream_has_it(hooked, upstream):
    """Its loader, file, cache and source are upstream's; its names too, but numpy's `np`."""
    later = facts(hooked, "import genpy.message\n" + HOOK_STATE + MODULE_FACE)
    first = facts(upstream, MODULE_FACE)
    assert not later["numpy"]
    assert later["face"] == first["face"]
    assert later["face"][0] == "SourceFileLoader"


def test_without_the_hook_numpy_is_loaded(upstream):
    """The control: the same import in the environment without the folder loads numpy."""
    got = facts(upstream, "import rospy\n" + HOOK_STATE)
    assert got["numpy"] and not got["hook_loaded"]


def test_messages_serialise_and_bad_values_are_reported(hooked):
    got = facts(hooked, """
import io
import genpy
from geometry_msgs.msg import Twist
from std_msgs.msg import Float64, String
buff = io.BytesIO()
Twist().serialize(buff)
Float64(2.5).serialize(buff)
String('hi').serialize(buff)
facts['bytes'] = len(buff.getvalue())
try:
    Float64('2.5').serialize(io.BytesIO())
except genpy.SerializationError as error:
    facts['error'] = str(error)
""" + HOOK_STATE)
    assert got["bytes"] == 48 + 8 + 6
    assert "field data must be float type" in got["error"]
    assert not got["numpy"]


def test_numpy_imported_after_rospy_works_and_its_floats_are_accepted(hooked):
    got = facts(hooked, """
import io
import rospy
import genpy.message
facts['numpy_before'] = 'numpy' in sys.modules
import numpy as np
from std_msgs.msg import Float32, Float64MultiArray
facts['sum'] = float(np.arange(4.0).sum())
genpy.message.check_type('x', 'float32', np.float32(1.5))
genpy.message.check_type('x', 'float64', np.int16(3))
buff = io.BytesIO()
Float32(np.float32(2.5)).serialize(buff)
Float64MultiArray(data=np.array([1.0, 2.0])).serialize_numpy(buff, np)
facts['bytes'] = len(buff.getvalue())
try:
    genpy.message.check_type('x', 'float32', np.float16(1.5))
except genpy.message.SerializationError:
    facts['float16'] = 'refused'
facts['float_types'] = type(genpy.message._valid_float_types).__name__
""")
    assert got["numpy_before"] is False
    assert got["sum"] == 6.0
    assert got["bytes"] == 4 + 28, "Float32, then the array's empty layout (8) and its data (4 + 16)"
    assert got["float16"] == "refused", "float16 is not in upstream's list"
    assert got["float_types"] == "FloatTypes"


def test_numpy_first_leaves_genpy_as_upstream_has_it(hooked):
    got = facts(hooked, """
import numpy as np
import rospy
import genpy.message
facts['float_types'] = type(genpy.message._valid_float_types).__name__
facts['float32'] = np.float32 in genpy.message._valid_float_types
""" + HOOK_STATE)
    assert got["hook_loaded"], "the hook was there, and did nothing"
    assert got["float_types"] == "list" and got["float32"]
    assert "NumpyDeferral" not in got["finders"]


# check_type's verdicts: upstream's


ALL_NUMPY_SCALARS = """
import numpy as np
import genpy.message
types = {t for t in np.sctypeDict.values()} | {getattr(np, n) for n in dir(np) if isinstance(getattr(np, n), type)
                                                  and issubclass(getattr(np, n), np.generic)}
facts['accepted'] = sorted(repr(t) for t in types if t in genpy.message._valid_float_types)
facts['count'] = len(types)
"""


def test_every_numpy_scalar_type_gets_upstreams_verdict(hooked, upstream):
    later = facts(hooked, "import genpy.message\n" + ALL_NUMPY_SCALARS)
    first = facts(upstream, ALL_NUMPY_SCALARS)
    assert later["count"] == first["count"] > 20
    assert later["accepted"] == first["accepted"]
    assert len(first["accepted"]) == 10


@pytest.fixture(scope="module")
def oracles(hooked, upstream) -> Iterator[Dict[str, Oracle]]:
    made = {"upstream": Oracle(ORACLE, upstream, "numpy-first"), "numpy-later": Oracle(ORACLE, hooked, "numpy-later"),
            "no-numpy": Oracle(ORACLE, hooked, "no-numpy")}
    yield made
    leftovers = {name: oracle.close() for name, oracle in made.items()}
    assert leftovers == {"upstream": [], "numpy-later": [], "no-numpy": []}


NUMPY_SCALARS = ("bool_", "int8", "int16", "int32", "int64", "uint8", "uint16", "uint32", "uint64",
                 "intc", "uintc", "longlong", "ulonglong", "float16", "float32", "float64", "longdouble",
                 "complex64", "complex128")
PYTHON_SCALARS = st.one_of(
    st.floats().map(lambda x: ["float", x]),
    st.integers(-2 ** 70, 2 ** 70).map(lambda n: ["int", n]),
    st.booleans().map(lambda b: ["bool", b]),
    st.text(max_size=4).map(lambda s: ["str", s]),
    st.just(["none"]),
    st.floats(allow_nan=False).map(lambda x: ["float_subclass", x]))
NUMPY_VALUES = st.tuples(st.sampled_from(NUMPY_SCALARS), st.integers(0, 127)).map(lambda t: ["np", t[0], t[1]])
# Half of them the float types, whose check reads _valid_float_types.
FIELD_TYPES = st.one_of(st.sampled_from(["float32", "float64", "float64[]", "float32[3]"]),
                        st.sampled_from(["int8", "int32", "int64", "uint8", "uint64", "bool", "string", "int32[]"]))


def values(scalars: st.SearchStrategy) -> st.SearchStrategy:
    return st.one_of(scalars, st.lists(scalars, max_size=4).map(lambda v: ["list", v]),
                     st.lists(scalars, max_size=3).map(lambda v: ["tuple", v]))


def test_the_oracles_load_genpy_as_intended(oracles):
    assert oracles["upstream"].state == {"numpy_before_genpy": True, "float_types": "list"}
    assert oracles["numpy-later"].state == {"numpy_before_genpy": False, "float_types": "FloatTypes"}
    assert oracles["no-numpy"].state == {"numpy_before_genpy": False, "float_types": "FloatTypes"}


@settings(max_examples=1000, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(field_type=FIELD_TYPES, value=values(st.one_of(NUMPY_VALUES, PYTHON_SCALARS)))
def test_check_type_with_numpy_loaded_later_says_what_upstream_says(oracles, field_type, value):
    assert oracles["numpy-later"].ask(field_type, value) == oracles["upstream"].ask(field_type, value)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(field_type=FIELD_TYPES, value=values(PYTHON_SCALARS))
def test_check_type_without_numpy_says_what_upstream_says(oracles, field_type, value):
    assert oracles["no-numpy"].ask(field_type, value) == oracles["upstream"].ask(field_type, value)


# A broken hook never stops a start


SABOTAGE = {
    # the finder's state broken before genpy.message is looked for
    "finding": "finder = next(f for f in sys.meta_path if type(f).__name__ == 'NumpyDeferral')\n"
               "finder.modules = None\n",
    # the check of genpy.message's code broken: the loader's own exec_module runs
    "loading": "import usercustomize\nusercustomize.numpy_only_builds_the_list = None\n",
    # the refusal broken: genpy.message's `import numpy` succeeds
    "refusing": "import usercustomize\nusercustomize.importer_name = None\n",
}


@pytest.mark.parametrize("where", sorted(SABOTAGE))
def test_an_error_inside_the_hook_falls_back_to_upstream(hooked, where):
    got = facts(hooked, SABOTAGE[where] + """
import rospy
import genpy.message
import numpy as np
facts['float32'] = np.float32 in genpy.message._valid_float_types
""" + HOOK_STATE)
    assert got["hook_loaded"] and got["numpy"] and got["float32"]
    assert "NumpyDeferral" not in got["finders"]


def test_an_error_while_installing_does_not_stop_the_start(hooked, tmp_path):
    """A sitecustomize (run before usercustomize) makes sys.meta_path refuse insertions."""
    (tmp_path / "sitecustomize.py").write_text(
        "import sys\n"
        "class Refusing(list):\n"
        "    def insert(self, index, item):\n"
        "        raise RuntimeError('no insertions')\n"
        "sys.meta_path = Refusing(sys.meta_path)\n")
    env = dict(hooked, PYTHONPATH="%s%s%s" % (tmp_path, os.pathsep, hooked["PYTHONPATH"]))
    got = facts(env, "import rospy\nfacts['patched'] = type(sys.meta_path).__name__\n" + HOOK_STATE)
    assert got["patched"] == "Refusing", "the sabotage ran"
    assert got["hook_loaded"] and got["numpy"]


# The grading sandbox


@pytest.mark.skipif(not levels.uses_namespaces(levels.detect(DEFAULT_USER)),
                    reason="this machine refuses namespaces")
def test_a_student_process_in_the_grading_sandbox_loads_rospy_without_numpy(hooked):
    """As a check starts a student's node: the sandbox user, a home of its own, the course read-only."""
    place = Path(tempfile.mkdtemp(prefix="numpy-deferral-"))
    try:
        os.chmod(place, 0o755)
        home = place / "student"
        home.mkdir()
        if os.geteuid() == 0:
            entry = pwd.getpwnam(DEFAULT_USER)
            os.chown(home, entry.pw_uid, entry.pw_gid)
        level = levels.detect(DEFAULT_USER)
        box = RunSandbox(Policy(level, DEFAULT_USER, [str(home)], [], [str(ROOT)], str(home), student_env=hooked))
        try:
            code, out = box.run_captured([DEBIAN_PYTHON, "-c", "import json, os, sys, rospy\n"
                                          "print(json.dumps([os.getuid(), 'numpy' in sys.modules,"
                                          " 'usercustomize' in sys.modules]))"], TIMEOUT_S)
        finally:
            box.close()
    finally:
        shutil.rmtree(place, ignore_errors=True)
    assert code == 0, out
    uid, numpy_loaded, hook_loaded = json.loads(out.decode().splitlines()[-1])
    if os.geteuid() == 0:
        assert uid == pwd.getpwnam(DEFAULT_USER).pw_uid
    assert hook_loaded and not numpy_loaded
