"""Fresh interpreters with and without course_env's usercustomize, for the tests that compare them.

course_env's env hook puts lib/course_env/python_startup on PYTHONPATH; its usercustomize defers
numpy (for genpy.message) and pyparsing (for catkin_pkg.condition). `hooked_env()` is the
environment a new shell has after `source catkin_ws/devel/setup.bash`, started from this process's
environment with the hook's folder taken out, so that removing the hook (the module or the env
hook's lines) makes the tests fail; `without_hook()` of it is upstream's environment.
"""
from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Dict, List

import pytest

from course_checks.isolation import sourced_env
from course_sandbox.env_paths import drop_entries

CHECKOUT = Path(__file__).resolve().parents[4]  # <checkout>/src/course_testkit/src/course_testkit/
SETUP = CHECKOUT / "catkin_ws" / "devel" / "setup.bash"
SOLUTIONS_SETUP = CHECKOUT / "solutions_ws" / "devel" / "setup.bash"
STARTUP = str(CHECKOUT / "catkin_ws" / "devel" / "lib" / "course_env" / "python_startup")
DEBIAN_PYTHON = "/usr/bin/python3"
TIMEOUT_S = 120.0
# What a `facts` snippet can add to report on the hook.
HOOK_STATE = ("facts['numpy'] = 'numpy' in sys.modules\n"
              "facts['pyparsing'] = 'pyparsing' in sys.modules\n"
              "facts['hook_loaded'] = 'usercustomize' in sys.modules\n"
              "facts['finders'] = [type(f).__name__ for f in sys.meta_path]\n")


def without_hook(env: Dict[str, str]) -> Dict[str, str]:
    """`env` with no course_env python_startup folder on PYTHONPATH (any workspace's)."""
    clean = drop_entries(env, lambda p: p.rstrip("/").endswith(os.path.join("course_env", "python_startup")))
    clean.pop("PYTHONNOUSERSITE", None)
    return clean


def hooked_env() -> Dict[str, str]:
    """A new shell's environment after sourcing the course workspace."""
    return sourced_env(SETUP, without_hook(dict(os.environ)))


@pytest.fixture(scope="module")
def hooked() -> Dict[str, str]:
    """Fixture (import it into a test module): hooked_env(), once per module."""
    return hooked_env()


@pytest.fixture(scope="module")
def upstream(hooked: Dict[str, str]) -> Dict[str, str]:
    """Fixture: the hooked environment without the hook."""
    return without_hook(hooked)


def python(env: Dict[str, str], code: str, interpreter: str = DEBIAN_PYTHON) -> subprocess.CompletedProcess:
    return subprocess.run([interpreter, "-c", code], env=env, capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, timeout=TIMEOUT_S, cwd=str(CHECKOUT))


def facts(env: Dict[str, str], code: str, interpreter: str = DEBIAN_PYTHON) -> dict:
    """What `code` leaves in its `facts` dict, with sys imported, in a fresh interpreter."""
    done = python(env, "import json, sys\nfacts = {}\n%s\nprint(json.dumps(facts))" % code, interpreter)
    assert done.returncode == 0, done.stderr
    assert done.stderr == "", done.stderr
    return json.loads(done.stdout.splitlines()[-1])


class Oracle:
    """A process answering one JSON line per JSON line asked (an oracle script of a property
    test), its first line its state."""

    def __init__(self, script: Path, env: Dict[str, str], mode: str) -> None:
        self.proc = subprocess.Popen([DEBIAN_PYTHON, str(script), mode], env=env, stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, text=True, cwd=str(CHECKOUT))
        self.state = json.loads(self.proc.stdout.readline())

    def ask(self, *question: object) -> object:
        self.proc.stdin.write(json.dumps(list(question)) + "\n")
        self.proc.stdin.flush()
        return json.loads(self.proc.stdout.readline())

    def close(self) -> List[object]:
        """End it; whatever it said after the last question."""
        self.proc.stdin.close()
        rest = [json.loads(line) for line in self.proc.stdout]
        self.proc.wait(timeout=TIMEOUT_S)
        return rest
