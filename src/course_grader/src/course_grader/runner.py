"""Grade submissions: unpack, build an overlay, run each selected milestone's rostest, isolated,
with `jobs` runs at once across submissions and, beside them, `builds` submissions unpacked and
built at once (a build keeps a core busy while most of a run waits on behaviour: building the
next submission while the last one's runs go on fills those waits; in one pool, every build came
first and the runs after); write each verdict's JUnit XML and each submission's results.json as
soon as it is complete. One submission's failure (even a crash of the grader on it) is that
submission's verdict and never stops the others.

`interrupt()` (the TA's Ctrl+C: SIGINT or SIGTERM, cli.py) stops a grading within seconds: no
build or run starts after it, the running ones are ended (every process below the grader,
frozen then killed: rostest, the checks, the simulators, the builds, the sandboxes' namespaces),
and every verdict not reached is "not graded (interrupted)"; a run that had passed before its
end keeps its verdict. Each submission still gets its results.json.

A grading's pid is in `<out>/_work/grading.pid` while it runs. A grader that finds the file of a
grading that is gone (killed: SIGKILL leaves no clean-up) removes that grading's work folders
(`_work/<student>`) before it starts; one that finds a live grading's refuses to start. What
a killed grading left running on the machine is ended by course_sandbox.leftovers.sweep, at
every start.""" 
from __future__ import annotations

import functools
import json
import os
import shutil
import sys
import tarfile
import threading
import time
import traceback
import zipfile
from concurrent.futures import ThreadPoolExecutor
from typing import Callable, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple

from course_format.milestone import Milestone
from course_format import causes, course_file
from course_milestones import unbuilt
from course_milestones.scripts import script_problems
from course_checks import junit
from course_checks.artifacts import ENV_VAR as ARTIFACTS_VAR
from course_checks.rostest_runner import run_etc_dir, run_rostest
from course_checks.run_gate import ENV_VAR as GATE_VAR

from course_sandbox import leftovers, procs
from course_sandbox.policy import ENV_VAR as POLICY_VAR, Limits

from course_grader import gradescope, ros2_packages, shared_builds, submissions, verdict, workspace
from course_grader.early_runs import GO, RESTART, EarlyRun
from course_grader.class_outputs import WORK_DIR
from course_grader.sandboxing import SandboxPlan
from course_grader.submissions import Package, Submission
from course_grader.student_files import copy_logs
from course_grader.verdict import Verdict

MILESTONE_PACKAGE = "course_milestones"
REFERENCE = "reference"
PID_FILE = "grading.pid"  # in WORK_DIR: the pid of the grading that writes this output folder
KEPT_IN_WORK = ("durations.json", PID_FILE)
# While interrupted: how often the processes below the grader are looked for and killed again.
INTERRUPT_POLL_S = 0.2
# In each run's work folder: the sandbox policy its check reads, and the sandbox's report.
POLICY_FILE = "sandbox_policy.json"
SANDBOX_REPORT = "sandbox.json"


def rostest_of(m: Milestone, run_dir: str) -> Tuple[str, str, List[str]]:
    """The package, rostest file and arguments that check `m`: its course's own checks/NAME.test, or,
    for a data milestone, the file written here that starts its world and the generic check node.
    Either is run by path, as course_milestones' (rostest looks its package up otherwise, and a
    course folder is none)."""
    path = m.test_file
    if not path:
        path = os.path.join(run_dir, "%s.test" % m.name)
        with open(path, "w") as f:
            f.write(course_file.test_launch(m))
    return "", path, ["--package=%s" % MILESTONE_PACKAGE, "--pkgdir=%s" % workspace.package_dir(MILESTONE_PACKAGE),
                      "--results-filename=%s.xml" % m.name]


class Busy(RuntimeError):
    """Another grading, still running, writes into this output folder."""


def claim_output(out: str) -> str:
    """Make `out` this grading's: refuse (Busy) while another live grading has it; where a
    grading that is gone (killed) had it, remove its work folders. Returns what was removed, in
    words ("" when nothing)."""
    work = os.path.join(out, WORK_DIR)
    os.makedirs(work, exist_ok=True)
    pid_file = os.path.join(work, PID_FILE)
    try:
        with open(pid_file) as f:
            previous = int(f.read().strip() or 0)
    except (OSError, ValueError):
        previous = 0
    removed = []
    if previous and previous != os.getpid():
        if leftovers.is_live_grader(previous):
            raise Busy("another grading (pid %d) is writing into %s" % (previous, out))
        for entry in sorted(os.listdir(work)):
            if entry not in KEPT_IN_WORK:
                shutil.rmtree(os.path.join(work, entry), ignore_errors=True)
                removed.append(entry)
    with open(pid_file, "w") as f:
        f.write(str(os.getpid()))
    return ("the work folders of a grading that was killed (pid %d): %s" % (previous, ", ".join(removed))
            if removed else "")


def release_output(out: str) -> None:
    try:
        os.remove(os.path.join(out, WORK_DIR, PID_FILE))
    except FileNotFoundError:
        pass


def longest_first(milestones: Sequence[Milestone], durations: Dict[str, float]) -> List[Milestone]:
    """The milestones, those that took longest last time first (unknown ones before all), so the
    last runs to start are short ones and the runs at once end together."""
    return sorted(milestones, key=lambda m: -durations.get(m.name, float("inf")))


def _load_json(path: str) -> Dict:
    try:
        with open(path) as f:
            return dict(json.load(f))
    except (OSError, ValueError, TypeError):
        return {}


def _run_cause(checks_passed: bool, timed_out: bool, first: Sequence[str], recorded: Sequence[str],
               hints: Sequence[str]) -> str:
    """A failed run's cause, in the order its reason tells them: the checks passed but a sandbox
    limit ended the run; what the build did not make; what the check recorded; a script rosrun
    cannot start; the run's time limit; else not known."""
    if checks_passed:
        return "sandbox_limit"
    known = [causes.of(h) for h in first] + list(recorded) + [causes.of(h) for h in hints]
    known = [k for k in known if k]
    return known[0] if known else "timeout" if timed_out else causes.CHECK_FAILED


class Options(NamedTuple):
    out: str
    jobs: int = 2
    only: Optional[Sequence[str]] = None  # grade just these milestones
    only_from: Optional[str] = None  # or: the milestones named (as keys) in this JSON file of each submission
    timeout: float = 240.0  # per milestone run
    verbose: bool = False
    sources: Sequence[str] = ()  # the submissions' own paths (the class folder): hidden from student code
    builds: int = 1  # submissions unpacked and built at once, beside the `jobs` runs
    disk_bytes: int = Limits().disk_bytes  # what one student's work folder may take on disk in total
    answers: Sequence[str] = ()  # the course's reference solution and samples: hidden from student code
    early: int = 0  # runs started while a submission builds, when no other run is under way (early_runs)
    typical: Mapping[str, float] = {}  # the course's typical run times (course_file.typical_durations)
    share_builds: bool = False  # submissions with the same build inputs built once (shared_builds; course-lint's)


class _Progress:
    """Verdicts of one submission as they come in."""

    def __init__(self, submission: Submission) -> None:
        self.submission = submission
        self.started = time.monotonic()
        self.expected: Optional[int] = None
        self.verdicts: List[Verdict] = []
        self.note = ""


_SAY_LOCK = threading.Lock()


def say_line(line: str) -> None:
    """Print one line whole: the runs' threads report at once, and print() writes a line and its
    newline separately, so two lines could come out as one (a verdict line a reader misses)."""
    with _SAY_LOCK:
        sys.stdout.write(line + "\n")
        sys.stdout.flush()


class Grader:
    def __init__(self, milestones: Sequence[Milestone], options: Options,
                 say: Callable[[str], None] = say_line) -> None:
        self.milestones = list(milestones)
        self.options = options
        self.say = say
        self._lock = threading.Lock()
        self._idle = threading.Condition(self._lock)
        self._pending = 0
        self._runs_pending = 0  # in the run pool: queued or running
        self._progress: Dict[str, _Progress] = {}
        self._done = 0
        self.verdicts: List[Verdict] = []
        # Packages a student may not replace: everything the course and the system provide,
        # except the packages the texts make students write.
        students = {p for m in self.milestones for p in m.packages}
        self._protected = workspace.course_packages() - students
        self._durations_path = os.path.join(options.out, WORK_DIR, "durations.json")
        self._durations = dict(options.typical, **_load_json(self._durations_path))
        self._stop = threading.Event()
        self._pool = ThreadPoolExecutor(max(1, options.jobs), thread_name_prefix="grade")
        self._builds = ThreadPoolExecutor(max(1, options.builds), thread_name_prefix="build")
        self._setup = workspace.course_setup()
        self._shared = shared_builds.BuildShare() if options.share_builds else None
        self.sandbox = SandboxPlan(options.out, workspace.course_root(self._setup), options.sources,
                                   reference=workspace.reference_folders(self._setup) + [
                                       a for a in options.answers if a],
                                   limits=Limits(disk_bytes=options.disk_bytes))

    # -- scheduling -------------------------------------------------------------------------
    def _submit(self, fn, *args, pool: Optional[ThreadPoolExecutor] = None) -> None:
        runs = pool is None
        with self._lock:
            self._pending += 1
            self._runs_pending += runs

        def task():
            try:
                fn(*args)
            finally:
                with self._lock:
                    self._pending -= 1
                    self._runs_pending -= runs
                    self._idle.notify_all()
        (pool or self._pool).submit(task)

    def grade(self, subs: Sequence[Submission], reference: bool = False) -> List[Verdict]:
        for sub in subs:
            self._progress[sub.name] = _Progress(sub)
            self._submit(self._prepare, sub, reference, pool=self._builds)
        with self._lock:
            while self._pending:
                self._idle.wait(INTERRUPT_POLL_S)
                if self._stop.is_set():
                    self._lock.release()
                    try:
                        self._end_running()
                    finally:
                        self._lock.acquire()
        self._pool.shutdown()
        self._builds.shutdown()
        self.sandbox.end_leftovers()
        if self._stop.is_set():
            self._end_running()
            leftovers.sweep()  # the ended checks' pids cgroups
        self._durations.update({v.milestone.name: round(v.elapsed, 1) for v in self.verdicts if v.elapsed})
        os.makedirs(os.path.dirname(self._durations_path), exist_ok=True)
        with open(self._durations_path, "w") as f:
            json.dump(self._durations, f, indent=1, sort_keys=True)
        return self.verdicts

    def interrupt(self) -> None:
        """Stop the grading (safe in a signal handler: it only sets a flag; grade() does the rest)."""
        self._stop.set()

    @property
    def interrupted(self) -> bool:
        return self._stop.is_set()

    def _end_running(self) -> None:
        """Kill every process below the grader: the runs and builds under way, and their sandboxes."""
        leftovers.end_all(lambda: procs.descendants(os.getpid()))

    # -- one submission ---------------------------------------------------------------------
    def _student_dir(self, student: str, *parts: str) -> str:
        return os.path.join(self.options.out, student, *parts)

    def _work_dir(self, student: str, *parts: str) -> str:
        return os.path.join(self.options.out, WORK_DIR, student, *parts)

    def _private_folders(self, student: str) -> None:
        """Where the sandbox hides nothing (isolation `user only`: one user for every student),
        file modes keep other students' code out: a student's outputs and unpacked files are the
        grader's alone; its work folder lets the sandbox user through to the workspace and run
        homes, without listing it."""
        for folder, mode in ((self._student_dir(student), 0o700), (self._work_dir(student), 0o711)):
            os.makedirs(folder, exist_ok=True)
            os.chmod(folder, mode)

    def _only_for(self, files: Optional[str]) -> Optional[List[str]]:
        if self.options.only:
            return list(self.options.only)
        if self.options.only_from and files:
            path = os.path.join(files, self.options.only_from)
            if os.path.isfile(path):
                with open(path) as f:
                    return list(json.load(f))
        return None

    def _prepare(self, sub: Submission, reference: bool) -> None:
        progress = self._progress[sub.name]
        progress.started = time.monotonic()
        selected: List[Milestone] = []
        if self._stop.is_set():
            self._fail_all(sub, verdict.select(self.milestones, [], self._only_for(None), reference),
                           verdict.INTERRUPTED)
            return
        try:
            # The reference (the checkout's solutions/) is graded as a student's submission is:
            # copied, built as an overlay in the sandbox and run there; only its milestones are all.
            self._private_folders(sub.name)
            files = self._work_dir(sub.name, "files")
            try:
                submissions.unpack(sub, files)
                if not submissions.find_packages(files):
                    submissions.unpack_nested(files)
                os.chmod(files, 0o700)
            except (submissions.UnsafeArchive, OSError, ValueError, EOFError, zipfile.BadZipFile,
                    tarfile.TarError) as err:
                selected = verdict.select(self.milestones, [], self._only_for(None), False)
                self._fail_all(sub, selected, "the submission cannot be unpacked: %s" % err, "not_unpacked")
                return
            packages = submissions.find_packages(files)
            names = [p.name for p in packages if p.name]
            selected = verdict.select(self.milestones, names, self._only_for(None if reference else files), reference)
            progress.note = "packages found: %s" % (", ".join(names) or "none")
            self._expect(sub, len(selected))
            runnable = []
            for m in selected:
                missing = verdict.missing_package(m, packages, files)
                if missing:
                    self._record(Verdict(sub.name, m, False, missing, cause=causes.of(missing) or "package_missing"))
                else:
                    runnable.append(m)
            if not runnable:
                return
            ws = self._work_dir(sub.name, "ws")
            own = [p for p in packages if p.name not in self._protected]
            left_out = sorted({p.name for p in packages if p.name in self._protected})
            if left_out:
                progress.note += "\nleft out (the course provides them): %s" % ", ".join(left_out)
            if self._stop.is_set():
                self._fail_all(sub, runnable, verdict.INTERRUPTED)
                return
            ros2 = ros2_packages.problems([p.path for p in own], files)
            if ros2:  # catkin_make would stop on it with words about the workspace, not the package
                for m in runnable:
                    self._record(Verdict(sub.name, m, False, ros2_packages.reason(m.packages, ros2),
                                         cause="ros2_package"))
                return
            workspace.populate(ws, own)
            order = longest_first(runnable, self._durations)
            early = self._start_early(sub, order, ws)
            try:
                self._build_and_run(sub, runnable, order, packages, own, ws, early)
            finally:
                for run in early.values():  # those the build did not open or restart
                    run.void()
        except Exception:  # noqa: BLE001 - the grader's own failure is this submission's verdict
            if self._stop.is_set():
                self._fail_all(sub, selected or self.milestones[:1], verdict.INTERRUPTED)
            else:
                self._fail_all(sub, selected or self.milestones[:1], "the grader failed on this submission:\n%s"
                               % traceback.format_exc(limit=5), "grader_error")

    def _start_early(self, sub: Submission, order: Sequence[Milestone], ws: str) -> Dict[str, EarlyRun]:
        """The first `early` runs of `order`, started now if no run is under way (early_runs). Only
        the course's own checks (course_milestones': each passes its gate before anything else)."""
        with self._lock:
            if self.options.early <= 0 or self._runs_pending or self._stop.is_set():
                return {}
        early: Dict[str, EarlyRun] = {}
        for m in order[:self.options.early]:
            if m.test_file and os.path.isabs(m.test_file):
                continue  # a course's own rostest file: its check may not wait at the gate
            gate = self._work_dir(sub.name, "gates", m.name)
            os.makedirs(os.path.dirname(gate), exist_ok=True)
            if os.path.lexists(gate):
                os.remove(gate)
            # Its folders are made here, not in its thread: the build's verdicts may go into the
            # same artifacts folder while that thread starts.
            self._run_dirs(sub, m)
            early[m.name] = EarlyRun(gate)
            self._submit(self._run_early, sub, m, ws, early[m.name])
        return early

    def _build_and_run(self, sub: Submission, runnable: Sequence[Milestone], order: Sequence[Milestone],
                       packages: Sequence[Package], own: Sequence[Package], ws: str,
                       early: Dict[str, EarlyRun]) -> None:
        """Build the overlay and start (or open) every runnable milestone's run, or give the
        build's verdicts. `early`: the runs already started; those left in it are voided."""
        setup = self._setup
        built = self._build(sub, ws)
        if self._stop.is_set():  # the build may have been ended half-way
            self._fail_all(sub, runnable, verdict.INTERRUPTED)
            return
        if not built.ok:
            for m in runnable:
                self._record(Verdict(sub.name, m, False, verdict.build_failed(built.summary),
                                     cause=causes.of(built.summary, causes.BUILD_FAILED)))
            return
        shadowed = workspace.shadowed_modules(ws, self._protected, workspace.course_site(setup))
        if shadowed:
            for m in runnable:
                self._record(Verdict(sub.name, m, False, "the submission installs Python modules the course "
                                     "provides, which would replace them: %s (rename them)" % ", ".join(shadowed),
                                     cause="shadows_course"))
            return
        # Read from the grader's own copy of each built package (ws/src is the student's to change).
        unmade = {p.name: unbuilt.problems(p.path, p.name, os.path.join(ws, "devel")) for p in own if p.name}
        for m in order:
            hints = [h for p in packages if p.name in m.packages for h in script_problems(p.path)]
            first = [h for name in m.packages for h in unmade.get(name, [])]
            args = (built.env, hints, ws, built.student_env, first)
            run = early.pop(m.name, None)
            if run is not None and not run.stale() and not self._stop.is_set() and run.open(
                    hints, first, functools.partial(self._write_policy, sub, m, ws, built.student_env)):
                continue
            if run is not None and run.restart(args):
                continue
            self._submit(self._run, sub, m, *args)

    def _build(self, sub: Submission, ws: str) -> workspace.BuildResult:
        """catkin_make in `ws`; with share_builds, a copy of an earlier build of the same inputs
        (course_grader.shared_builds) when there is one."""
        home, log = self._work_dir(sub.name, "home"), self._work_dir(sub.name, "build.log")
        if self._shared is None:
            return workspace.build(ws, self._setup, self.sandbox, home, log)
        key = shared_builds.inputs_key(os.path.join(ws, "src"))
        first, donor = self._shared.claim(key, ws)
        if not first:
            copied = workspace.reuse(donor, ws, self.sandbox, home, log)
            if copied is not None:
                return copied
            return workspace.build(ws, self._setup, self.sandbox, home, log)
        built = None
        try:
            built = workspace.build(ws, self._setup, self.sandbox, home, log)
        finally:
            self._shared.done(key, ws, bool(built and built.ok))
        return built

    def _run_dirs(self, sub: Submission, m: Milestone) -> Tuple[str, str, str]:
        """A run's fresh folders: its work folder, the student's home in it (given to the sandbox
        user), and the artifacts the student is shown."""
        artifacts = self._student_dir(sub.name, m.name)
        shutil.rmtree(artifacts, ignore_errors=True)
        os.makedirs(artifacts)
        run_dir = self._work_dir(sub.name, "runs", m.name)
        shutil.rmtree(run_dir, ignore_errors=True)
        home = os.path.join(run_dir, "student")
        os.makedirs(os.path.join(home, "log"))
        self.sandbox.give(home)
        return run_dir, home, artifacts

    def _write_policy(self, sub: Submission, m: Milestone, ws: Optional[str],
                      student_env: Optional[Dict[str, str]]) -> str:
        """The run's sandbox policy, read by its check when it starts the student's processes."""
        run_dir = self._work_dir(sub.name, "runs", m.name)
        home = os.path.join(run_dir, "student")
        policy = self.sandbox.policy([p for p in (ws, home) if p], home, student_env,
                                     os.path.join(run_dir, SANDBOX_REPORT), disk_folder=self._work_dir(sub.name),
                                     readable=[run_etc_dir(run_dir)])
        return policy.write(os.path.join(run_dir, POLICY_FILE))

    def _rostest(self, m: Milestone, run_dir: str, env: Dict[str, str], artifacts: str, **extra: str):
        package, test_file, args = rostest_of(m, run_dir)
        run_env = dict(env, **{ARTIFACTS_VAR: artifacts, POLICY_VAR: os.path.join(run_dir, POLICY_FILE)}, **extra)
        return run_rostest(package, test_file, args=args, env=run_env, results_dir=run_dir,
                           timeout=self.options.timeout)

    def _run(self, sub: Submission, m: Milestone, env: Dict[str, str], hints: List[str], ws: Optional[str],
             student_env: Optional[Dict[str, str]], first: Sequence[str] = ()) -> None:
        """One milestone run: rostest (the master, the simulators, the check: trusted) with the
        student's processes in a sandbox the check starts from the policy written here."""
        if self._stop.is_set():
            self._record(Verdict(sub.name, m, False, verdict.INTERRUPTED))
            return
        try:
            run_dir, home, artifacts = self._run_dirs(sub, m)
            self._write_policy(sub, m, ws, student_env)
            result = self._rostest(m, run_dir, env, artifacts)
            self._judge(sub, m, result, ws, hints, first)
        except Exception:  # noqa: BLE001
            self._grader_failed(sub, m)

    def _run_early(self, sub: Submission, m: Milestone, ws: str, early: EarlyRun) -> None:
        """A run started while the submission builds (early_runs): its check waits at the gate;
        the build thread decides whether it counts, is void, or starts again."""
        result = None
        try:
            result = self._rostest(m, self._work_dir(sub.name, "runs", m.name), workspace.trusted_env(ws),
                                   self._student_dir(sub.name, m.name), **{GATE_VAR: early.gate})
        except Exception:  # noqa: BLE001 - judged below if the run counts
            pass
        outcome = early.ended()
        if outcome == RESTART:
            self._run(sub, m, *early.restart_args)
        elif outcome == GO:
            if result is None:
                self._grader_failed(sub, m)
                return
            try:
                self._judge(sub, m, result._replace(elapsed=max(0.0, result.elapsed - early.waited())), ws,
                            early.hints, early.first)
            except Exception:  # noqa: BLE001
                self._grader_failed(sub, m)

    def _grader_failed(self, sub: Submission, m: Milestone) -> None:
        if self._stop.is_set():
            self._record(Verdict(sub.name, m, False, verdict.INTERRUPTED))
        else:
            self._record(Verdict(sub.name, m, False, "the grader failed on this milestone:\n%s"
                                 % traceback.format_exc(limit=5), cause="grader_error"))

    def _judge(self, sub: Submission, m: Milestone, result, ws: Optional[str], hints: List[str],
               first: Sequence[str]) -> None:
        """The run's verdict. On a failure, `first` (what the package holds but its build did not
        make: the cause to fix) comes before the check's reason and `hints` after it, each only if
        the check did not say it."""
        run_dir = self._work_dir(sub.name, "runs", m.name)
        home = os.path.join(run_dir, "student")
        artifacts = self._student_dir(sub.name, m.name)
        with open(os.path.join(artifacts, "rostest.txt"), "w") as f:
            f.write(result.output)
        if self._stop.is_set() and not result.passed:  # ended by the interruption: no verdict
            self._record(Verdict(sub.name, m, False, verdict.INTERRUPTED, elapsed=0.0))
            return
        hits = verdict.sandbox_hits(os.path.join(run_dir, SANDBOX_REPORT))
        passed = result.passed and not verdict.ended_by_limit(hits)
        reason = "" if passed else verdict.ENDED_BY_LIMIT if result.passed else result.summary()
        if not result.passed:
            hints = hints + verdict.output_hints(artifacts, hints) + verdict.output_capped(artifacts)
            reason = "\n".join([h for h in first if h.split(" (")[0] not in reason] + [reason]
                               + [h for h in hints if h not in reason])
        copy_logs(os.path.join(home, "log"), os.path.join(artifacts, "ros_log"))
        verdict.trim_files(artifacts)
        verdict.trim_files(run_dir, skip=home)  # the student's home is theirs: never written by us
        # Its logs are copied: what the run wrote no longer counts in the student's disk bound.
        shutil.rmtree(home, ignore_errors=True)
        cause = "" if passed else _run_cause(result.passed, result.timed_out, first, causes.recorded(artifacts),
                                             hints)
        # what the student reads quotes their files from their package down, not the grader's folders
        hide = [os.path.join(ws, "src") if ws else "", self._work_dir(sub.name), self.options.out]
        self._record(Verdict(sub.name, m, passed, verdict.without_grader_paths(reason, hide),
                             verdict.without_grader_paths(verdict.log_tails(artifacts), hide),
                             result.elapsed, artifacts, verdict.sandbox_notes(hits), cause))

    # -- results ----------------------------------------------------------------------------
    def _expect(self, sub: Submission, count: int) -> None:
        with self._lock:
            self._progress[sub.name].expected = count
        if count == 0:
            self._finish(sub)

    def _fail_all(self, sub: Submission, selected: Sequence[Milestone], reason: str, cause: str = "") -> None:
        with self._lock:
            progress = self._progress[sub.name]
            progress.expected = len(progress.verdicts) + len([m for m in selected if m.name not in
                                                              {v.milestone.name for v in progress.verdicts}])
        for m in selected:
            if m.name not in {v.milestone.name for v in progress.verdicts}:
                self._record(Verdict(sub.name, m, False, reason, cause=cause))

    def _record(self, v: Verdict) -> None:
        folder = self._student_dir(v.student, v.milestone.name)
        os.makedirs(folder, exist_ok=True)
        case = junit.Case(v.milestone.name, v.student, v.elapsed, None if v.passed else "failure", v.output())
        junit.write(os.path.join(folder, "junit.xml"), v.student, [case])
        if self.options.verbose:
            self.say("    %-10s %-20s %-6s %6.1fs%s" % (v.student, v.milestone.name, "pass" if v.passed else "FAIL",
                                                      v.elapsed, "" if v.passed else "  " + v.reason.splitlines()[0]))
        with self._lock:
            progress = self._progress[v.student]
            progress.verdicts.append(v)
            self.verdicts.append(v)
            complete = progress.expected is not None and len(progress.verdicts) >= progress.expected
        if complete:
            self._finish(progress.submission)

    def _finish(self, sub: Submission) -> None:
        progress = self._progress[sub.name]
        order = {m.name: i for i, m in enumerate(self.milestones)}
        ordered = sorted(progress.verdicts, key=lambda v: order.get(v.milestone.name, len(order)))
        elapsed = time.monotonic() - progress.started
        os.makedirs(self._student_dir(sub.name), exist_ok=True)
        note = "\n".join(n for n in (progress.note, "isolation: " + self.sandbox.describe()) if n)
        gradescope.write(self._student_dir(sub.name, "results.json"), ordered, elapsed, note)
        with self._lock:
            self._done += 1
            done = self._done
        points = sum(v.points for v in ordered)
        self.say("[%d/%d] %s: %g/%g points, %d of %d milestones passed, %.1f s"
                 % (done, len(self._progress), sub.name, points, sum(v.milestone.points for v in ordered),
                    sum(v.passed for v in ordered), len(ordered), elapsed))
