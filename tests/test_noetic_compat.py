"""Code written for ROS Noetic builds and runs as an overlay on the course workspace (docs/noetic_cxx.md).

The samples in tests/noetic_compat/ (ours, written the way Noetic's tutorials write it) are built
the way the grader builds a student's packages: a fresh shell (no CPLUS_INCLUDE_PATH of its own)
sources the course's devel/setup.bash, then `catkin_make`. Then:
- the roscpp node that subscribes with `boost::bind(&on_number, _1, ...)` relays scaled numbers
  through its C helper, on a private master;
- the pluginlib loader finds both plugins exported with <pluginlib/class_list_macros.h> and
  prints their areas;
- the angles sample gives the same numbers from C++ and from Python as the formula does;
- the same translation units, compiled by the overlay's own compile commands without the
  course's hook, fail the way Debian 12 fails them (so the hook is what builds them);
- `using namespace std::placeholders;` and the other spellings of `_1` compile, or fail, exactly
  as they do beside Noetic's <boost/bind.hpp>;
- course_env's install space sets the same include path, pointing into the install space.
"""
from __future__ import annotations

import json
import math
import os
import shlex
import shutil
import subprocess
from pathlib import Path
from typing import Dict, List, NamedTuple, Optional, Tuple

import pytest

from course_checks.isolation import sourced_env
from course_testkit.master import PrivateMaster
from course_checks.waiting import wait_for

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ROOT / "tests" / "noetic_compat"
COURSE_SETUP = ROOT / "catkin_ws" / "devel" / "setup.bash"
PACKAGES = ("noetic_bind", "noetic_plugins", "noetic_angles")
BUILD_TIMEOUT_S = 600.0
NODE_TIMEOUT_S = 60.0

def shell_env() -> Dict[str, str]:
    """A new terminal's environment: ours without the include path the course's hook sets, so
    only sourcing a setup.bash can set it."""
    return {k: v for k, v in os.environ.items() if k != "CPLUS_INCLUDE_PATH"}


def run(command: List[str], env: Dict[str, str], cwd: Optional[Path] = None, timeout: float = NODE_TIMEOUT_S):
    if cwd is not None:
        env = dict(env, PWD=str(cwd))  # catkin_make takes its workspace from PWD
    return subprocess.run(command, env=env, cwd=str(cwd) if cwd else None, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, universal_newlines=True, timeout=timeout)


class Overlay(NamedTuple):
    ws: Path
    env: Dict[str, str]  # after `source <overlay>/devel/setup.bash`
    compile_commands: List[dict]


@pytest.fixture(scope="module")
def overlay(tmp_path_factory) -> Overlay:
    ws = tmp_path_factory.mktemp("noetic_ws")
    (ws / "src").mkdir()
    for name in PACKAGES:
        (ws / "src" / name).symlink_to(SAMPLES / name)
    build = run(["bash", "-c", 'source "$1" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 '
                 '-DCMAKE_EXPORT_COMPILE_COMMANDS=ON', "bash", str(COURSE_SETUP)],
                shell_env(), cwd=ws, timeout=BUILD_TIMEOUT_S)
    assert build.returncode == 0, build.stdout[-5000:]
    commands = json.loads((ws / "build" / "compile_commands.json").read_text())
    return Overlay(ws, sourced_env(ws / "devel" / "setup.bash", shell_env()), commands)


def compile_command(overlay: Overlay, source: str) -> List[str]:
    """The overlay's own compile command for `source` (a path below src/), checking syntax only."""
    for entry in overlay.compile_commands:
        if entry["file"].endswith("/" + source):
            words = shlex.split(entry["command"])
            out = words.index("-o")
            return words[:out] + words[out + 2:] + ["-fsyntax-only"]
    raise AssertionError("%s is not in compile_commands.json" % source)


def test_the_c_source_is_compiled_by_the_c_compiler(overlay):
    command = compile_command(overlay, "noetic_bind/src/scale.c")
    assert os.path.basename(command[0]) in ("cc", "gcc"), command[0]


def test_the_boost_bind_node_relays_scaled_numbers(overlay):
    with PrivateMaster(env=overlay.env, timeout=NODE_TIMEOUT_S) as master:
        relay = master.start(["rosrun", "noetic_bind", "scale_relay", "_factor:=4"], "scale_relay")
        echo = master.start(["rostopic", "echo", "-n", "1", "/scaled"], "echo")
        master.start(["rostopic", "pub", "-r", "5", "/numbers", "std_msgs/Int32", "data: 21"], "pub")
        assert wait_for(lambda: "data: 84" in echo.output() or not relay.running(), timeout=NODE_TIMEOUT_S,
                        interval=0.1)
        assert "data: 84" in echo.output(), relay.output() + echo.output()


def test_the_plugins_load_by_name(overlay):
    done = run(["rosrun", "noetic_plugins", "shape_loader", "2.0"], overlay.env)
    assert done.returncode == 0, done.stdout
    assert "area of noetic_plugins/square: 4.0000" in done.stdout, done.stdout
    assert "area of noetic_plugins/disc: %.4f" % (math.pi * 4) in done.stdout, done.stdout
    assert "2 shapes declared, 0 failed" in done.stdout, done.stdout


def expected_angles(pairs) -> str:
    """normalize_angle to [-pi, pi) and the shortest turn, by the formula."""
    def normal(a: float) -> float:
        return math.fmod(math.fmod(a + math.pi, 2 * math.pi) + 2 * math.pi, 2 * math.pi) - math.pi
    return "".join("%.6f %.6f\n" % (normal(a), normal(b - a)) for a, b in pairs)


@pytest.mark.parametrize("program", ["angle_report", "angle_report.py"])
def test_angles_from_cpp_and_python(overlay, program):
    pairs = [(7.0, -3.5), (-10.0, 0.25), (3.0, -3.0)]
    args = [str(v) for pair in pairs for v in pair]
    done = run(["rosrun", "noetic_angles", program] + args, overlay.env)
    assert done.returncode == 0, done.stdout
    assert done.stdout == expected_angles(pairs)


@pytest.mark.parametrize("source, debian_says", [
    ("noetic_bind/src/scale_relay.cpp", "'_1' was not declared in this scope"),
    ("noetic_plugins/src/shapes.cpp", "pluginlib/class_list_macros.h: No such file or directory"),
    ("noetic_plugins/src/shape_loader.cpp", "pluginlib/class_loader.h: No such file or directory"),
])
def test_without_the_hook_debian_does_not_compile_them(overlay, source, debian_says):
    command = compile_command(overlay, source)
    without = {k: v for k, v in overlay.env.items() if k != "CPLUS_INCLUDE_PATH"}
    bare = run(command, dict(without, LC_ALL="C"), cwd=overlay.ws / "build")
    assert bare.returncode != 0 and debian_says in bare.stdout, bare.stdout[-3000:]
    assert run(command, overlay.env, cwd=overlay.ws / "build").returncode == 0


SPELLINGS = {
    "boost::bind, _1 unqualified": "boost::function<void(int)> g = boost::bind(&f, _1, 2);",
    "using namespace std::placeholders": "using namespace std::placeholders;\nauto g = std::bind(&f, _1, 2);",
    "using namespace std::placeholders in a function":
        "void h() { using namespace std::placeholders; auto g = std::bind(&f, _1, 2); g(1); }",
    "using std::placeholders::_1 in a function":
        "void h() { using std::placeholders::_1; auto g = std::bind(&f, _1, 2); g(1); }",
    "std::placeholders::_1 in full": "auto g = std::bind(&f, std::placeholders::_1, 2);",
}


def start_compile(name: str, header: str, body: str, env: Dict[str, str], folder: Path,
                  defines: List[str]) -> subprocess.Popen:
    """g++ checking a file that includes `header`, then holds `body` (its messages in ASCII quotes)."""
    path = folder / ("%s.cpp" % name)
    path.write_text("#include %s\n#include <functional>\n#include <boost/function.hpp>\n"
                    "static void f(int, int) {}\n%s\nint main() { return 0; }\n" % (header, body))
    return subprocess.Popen(["g++", "-fsyntax-only"] + defines + [str(path)], env=dict(env, LC_ALL="C"),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, universal_newlines=True)


def finish(compile: subprocess.Popen) -> Tuple[bool, str]:
    """(compiled, what g++ said)."""
    _, said = compile.communicate(timeout=NODE_TIMEOUT_S)
    return compile.returncode == 0, said


def test_placeholders_behave_as_beside_noetics_boost_bind_hpp(overlay, tmp_path):
    """Noetic's roscpp headers included <boost/bind.hpp> (Boost 1.71 printed no deprecation
    message, hence the define): each spelling must compile here, with ros/ros.h, exactly when it
    compiles beside that, and `using namespace std::placeholders;` is ambiguous in both."""
    without = {k: v for k, v in overlay.env.items() if k != "CPLUS_INCLUDE_PATH"}
    noetic, here = {}, {}
    for i, (name, body) in enumerate(SPELLINGS.items()):  # two compilers at a time, one per core
        beside = start_compile("noetic%d" % i, "<boost/bind.hpp>", body, without, tmp_path,
                               ["-DBOOST_BIND_GLOBAL_PLACEHOLDERS"])
        ours = start_compile("here%d" % i, "<ros/ros.h>", body, overlay.env, tmp_path, [])
        noetic[name], here[name] = finish(beside), finish(ours)
    assert {n: ok for n, (ok, _) in here.items()} == {n: ok for n, (ok, _) in noetic.items()}, here
    compiled, said = here["using namespace std::placeholders"]
    assert not compiled and "reference to '_1' is ambiguous" in said, said
    assert here["boost::bind, _1 unqualified"][0] and here["std::placeholders::_1 in full"][0], here


def test_the_install_space_sets_the_same_include_path(tmp_path):
    """course_env alone, installed: its hook points at the installed headers (no link back into
    src/), and a roscpp file using boost::bind's _1 compiles with them."""
    ws = tmp_path / "ws"
    (ws / "src").mkdir(parents=True)
    (ws / "src" / "course_env").symlink_to(ROOT / "src" / "course_env")
    start = {k: v for k, v in shell_env().items()
             if not k.startswith(("ROS_", "CMAKE_PREFIX_PATH", "PYTHONPATH", "PKG_CONFIG_PATH"))}
    built = run(["catkin_make", "-DPYTHON_EXECUTABLE=/usr/bin/python3", "install"], start, cwd=ws,
                timeout=BUILD_TIMEOUT_S)
    assert built.returncode == 0, built.stdout[-4000:]
    env = sourced_env(ws / "install" / "setup.bash", start)
    folder = ws / "install" / "share" / "course_env" / "noetic_include"
    assert env["CPLUS_INCLUDE_PATH"].split(":")[0] == str(folder)
    assert (folder / "boost" / "bind" / "bind.hpp").is_file() and not folder.is_symlink()
    compiled, said = finish(start_compile("probe", "<ros/ros.h>", SPELLINGS["boost::bind, _1 unqualified"],
                                          env, tmp_path, []))
    assert compiled, said


def test_two_course_workspaces_on_the_include_path_still_compile(overlay, tmp_path):
    """Two course checkouts sourced one after the other put two copies of noetic_include on
    CPLUS_INCLUDE_PATH: the first copy's #include_next reaches the second, which must still pass
    the include on to Boost's own (a guard before it left boost::placeholders undeclared)."""
    first = overlay.env["CPLUS_INCLUDE_PATH"].split(":")[0]
    second = tmp_path / "other_checkout" / "noetic_include"
    shutil.copytree(first, second)
    env = dict(overlay.env, CPLUS_INCLUDE_PATH="%s:%s" % (first, second))
    compiled, said = finish(start_compile("two", "<ros/ros.h>", SPELLINGS["boost::bind, _1 unqualified"],
                                          env, tmp_path, []))
    assert compiled, said
