"""A student's overlay workspace, chained on the course workspace, the way a student builds it:
`source <course>/devel/setup.bash; catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3`.

The course workspace is the one this package runs from (found from this module's location,
then CMAKE_PREFIX_PATH), never a hard-coded path. It holds the course's infrastructure only
(turtlesim, the simulator, the course_* packages). The reference solutions live apart, in
`courses/<course>/solution` (the built-in course's built as an overlay, `solutions_ws`): a grading
runs in the course's environment alone (course_environment), and grades the reference as one
more overlay, built and run like a student's.
"""
from __future__ import annotations

import functools
import glob
import importlib.util
import os
import shlex
import shutil
from typing import Dict, Iterable, List, NamedTuple, Optional, Sequence, Set

from course_format import causes
from course_sandbox import env_paths
from course_sandbox.run import LimitHits, capture_oneshot, run_oneshot
from course_checks import run_gate
from course_checks.isolation import sourced_env

from course_grader import build_errors, build_order, shared_builds
from course_grader.sandboxing import SandboxPlan, overlay_paths, parse_env
from course_grader.submissions import Package

BUILD_TIMEOUT_S = 600.0
PYTHON = "/usr/bin/python3"
SETUP_ENV = "COURSE_WS_SETUP"  # override: the setup.bash of the course workspace
# The built-in course's reference solution is built as an overlay of its own (absent from the student image).
SOLUTIONS_WS = "solutions_ws"


class BuildResult(NamedTuple):
    ok: bool
    log_path: str
    summary: str  # the lines that say why it failed ("" when ok)
    env: Optional[Dict[str, str]]  # the trusted side's environment for the overlay, when ok
    student_env: Optional[Dict[str, str]] = None  # the overlay's own, for the student's processes


def course_setup() -> str:
    """The course workspace's setup.bash: $COURSE_WS_SETUP, else the devel space this package is
    imported from, else the first CMAKE_PREFIX_PATH entry that holds course_grader."""
    import course_grader  # in a devel space, its __init__ is the devel space's shim

    explicit = os.environ.get(SETUP_ENV)
    if explicit:
        return explicit
    folder = os.path.dirname(os.path.abspath(course_grader.__file__))
    while folder != os.path.dirname(folder):
        candidate = os.path.join(folder, "setup.bash")
        if os.path.isfile(candidate) and os.path.isfile(os.path.join(folder, ".catkin")):
            return candidate
        folder = os.path.dirname(folder)
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        candidate = os.path.join(prefix, "setup.bash")
        if prefix and os.path.isfile(candidate) and os.path.exists(
                os.path.join(prefix, "share", "course_grader")):
            return candidate
    raise FileNotFoundError("cannot find the course workspace's setup.bash: set %s" % SETUP_ENV)


def course_site(setup_bash: str) -> str:
    """The Python modules folder of the course workspace whose setup.bash this is."""
    found = glob.glob(os.path.join(os.path.dirname(setup_bash), "lib", "python3*", "dist-packages"))
    return found[0] if found else ""


def populate(ws: str, packages: Sequence[Package]) -> None:
    """ws/src holds a copy of each package folder (nothing else of the submission)."""
    src = os.path.join(ws, "src")
    if os.path.exists(ws):
        shutil.rmtree(ws)
    os.makedirs(src)
    used: Dict[str, int] = {}
    for package in packages:
        base = os.path.basename(package.path.rstrip("/")) or "package"
        used[base] = used.get(base, 0) + 1
        target = os.path.join(src, base if used[base] == 1 else "%s_%d" % (base, used[base]))
        shutil.copytree(package.path, target, symlinks=True)


def course_root(setup_bash: str) -> str:
    """The course checkout: the folder above the workspace whose devel/setup.bash this is (it
    holds the workspace, the venv and the sources the devel space links to)."""
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(setup_bash))))


def reference_folders(setup_bash: str) -> List[str]:
    """The checkout's answers: every course folder's solution and samples (docs/course_format.md),
    and the overlay the built-in course's solution is built in (whether or not they exist)."""
    root = course_root(setup_bash)
    answers = sorted(glob.glob(os.path.join(root, "courses", "*", "solution"))
                     + glob.glob(os.path.join(root, "courses", "*", "samples")))
    return [os.path.join(root, SOLUTIONS_WS)] + answers


def _inside(path: str, folders: Sequence[str]) -> bool:
    real = os.path.realpath(path)
    return any(real == f or real.startswith(f + os.sep) for f in folders)


def without_folders(env: Dict[str, str], folders: Sequence[str]) -> Dict[str, str]:
    """`env` with every entry of its folder lists (course_sandbox.env_paths) that lies in one of
    `folders` dropped."""
    real = [os.path.realpath(f) for f in folders]
    return env_paths.drop_entries(env, lambda p: _inside(p, real))


def course_environment(setup_bash: str, env: Optional[Dict[str, str]] = None) -> Dict[str, str]:
    """The environment of the course workspace alone: `env` (default: this process's) with the
    course's setup.bash sourced the way a user does, which takes back what any other catkin
    workspace sourced before it had added (the reference overlay of `make test`), then with any
    entry left in the reference folders dropped. A student's build and processes, the checks and
    the grader itself run in it: no reference package is on any of their paths."""
    return without_folders(sourced_env(setup_bash, env), reference_folders(setup_bash))


def trusted_base_env() -> Dict[str, str]:
    """The grader's environment less what no build or run should inherit."""
    env = dict(os.environ)
    for key in ("ROS_MASTER_URI", "COURSE_ARTIFACTS_DIR", "COURSE_SANDBOX_POLICY", run_gate.ENV_VAR, "DISPLAY"):
        env.pop(key, None)
    return env


def trusted_env(ws: str) -> Dict[str, str]:
    """The environment of the trusted side (rostest, the checks) for the overlay `ws`: computed
    from the path alone, so a run started before the build ends (early_runs) gets the same."""
    return overlay_paths(trusted_base_env(), ws)


def build(ws: str, setup_bash: str, plan: SandboxPlan, home: str, log_path: str,
          timeout: float = BUILD_TIMEOUT_S) -> BuildResult:
    """catkin_make in `ws` on top of the course workspace, in a sandbox of its own (CMake runs
    whatever the student's CMakeLists.txt says): writable are only `ws` and `home`, and the
    folder holding `ws` (the student's work folder) is bounded on disk in total. If it builds,
    the overlay's environment for the trusted side (computed) and for the student's own processes
    (sourced inside a sandbox: the overlay's setup.bash and env hooks are the student's). The log
    goes to `log_path`, outside `ws`: the trusted side never opens a path the student could
    have made a link."""
    plan.give(ws)
    plan.give(home)
    policy = plan.policy([ws, home], home, disk_folder=os.path.dirname(ws))
    env = dict(trusted_base_env(), HOME=home)
    command = "source %s && catkin_make -DPYTHON_EXECUTABLE=%s" % (shlex.quote(setup_bash), PYTHON)
    hits = LimitHits()
    code = run_oneshot(policy, ["bash", "-c", command], ws, env, log_path, timeout, hits)
    if "disk" in hits.hits:
        return BuildResult(False, log_path, "sandbox limit: %s" % hits.hits["disk"], None)
    text = _tail(log_path)
    if code is None:
        return BuildResult(False, log_path, "catkin_make did not finish within %.0f s" % timeout, None)
    if code != 0:
        return BuildResult(False, log_path, build_errors.summarise(text, ws), None)
    unordered = build_order.unordered(ws)
    if unordered:
        return BuildResult(False, log_path, causes.finding("no_add_dependencies",
                                                           "\n".join(u.reason() for u in unordered)), None)
    return _overlay(ws, policy, env, log_path)


def _overlay(ws: str, policy, env: Dict[str, str], log_path: str) -> BuildResult:
    """The built overlay's environments: the student's sourced inside the sandbox (its setup.bash
    and env hooks are the student's), the trusted side's computed."""
    source = "source %s >/dev/null 2>&1; exec env -0" % shlex.quote(os.path.join(ws, "devel", "setup.bash"))
    code, out = capture_oneshot(policy, ["bash", "-c", source], ws, env)
    student_env = parse_env(out) if code == 0 else None
    if not student_env:
        return BuildResult(False, log_path, "sourcing the overlay's devel/setup.bash failed (exit code %s)" % code, None)
    return BuildResult(True, log_path, "", trusted_env(ws), student_env)


def reuse(donor: str, ws: str, plan: SandboxPlan, home: str, log_path: str) -> Optional[BuildResult]:
    """`ws` built by copying the build of `donor`, a workspace with the same build inputs
    (course_grader.shared_builds: only for `grade --share-builds`); None when it cannot be copied
    (build `ws` as usual). Its log says so, then holds the donor's."""
    why = shared_builds.relocate(donor, ws)
    if why:
        return None
    plan.give(ws)
    plan.give(home)
    with open(log_path, "w") as out:
        out.write("not built: the build of %s, whose build inputs are the same, copied (grade --share-builds)\n"
                  % donor)
        try:
            with open(os.path.join(os.path.dirname(donor), os.path.basename(log_path)), errors="replace") as f:
                shutil.copyfileobj(f, out)
        except OSError:
            pass
    policy = plan.policy([ws, home], home, disk_folder=os.path.dirname(ws))
    return _overlay(ws, policy, dict(trusted_base_env(), HOME=home), log_path)


def _tail(path: str, size: int = 200_000) -> str:
    """The end of a log file the trusted side wrote."""
    with open(path, "rb") as f:
        f.seek(max(0, os.path.getsize(path) - size))
        return f.read().decode("utf-8", errors="replace")


def course_packages() -> Set[str]:
    """Every ROS package the grader's environment (the course workspace and the system) has."""
    import rospkg
    return set(rospkg.RosPack().list())


def shadowed_modules(ws: str, protected: Iterable[str], course_site: str) -> List[str]:
    """Python modules the overlay installs (devel/lib/python3/dist-packages) that would replace one
    the checks rely on: a module of a protected course package (course_testkit, turtlesim, ...)
    or any module the grader's own Python finds outside the course workspace (rospy, rostest, ...).
    Modules of the reference solutions (my_chatter, ...) are the student's to replace."""
    protected = set(protected)
    course_modules = set(os.listdir(course_site)) if os.path.isdir(course_site) else set()
    found = []
    for site in glob.glob(os.path.join(ws, "devel", "lib", "python3*", "dist-packages")):
        for entry in sorted(os.listdir(site)):
            if entry.endswith((".egg-info", ".egg-link", ".pth")) or entry.startswith(("_", ".")):
                continue
            name = entry[:-3] if entry.endswith(".py") else entry
            if name in course_modules:
                if name in protected:
                    found.append(name)
            elif importlib.util.find_spec(name) is not None:
                found.append(name)
    return found


@functools.lru_cache(maxsize=None)
def package_dir(name: str) -> str:
    """The folder of the course package `name` (in the grader's own environment, the course's;
    looked up once: a RosPack crawls every package path)."""
    import rospkg
    return rospkg.RosPack().get_path(name)
