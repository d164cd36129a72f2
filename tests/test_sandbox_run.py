"""The sandbox for real (bubblewrap, setpriv, prlimit): what student code inside a run can see,
write and signal, and that nothing of it survives the run, whatever it did."""
import os
import pwd
import shutil
import signal
import subprocess
import tempfile
import threading
from pathlib import Path

import pytest

from course_sandbox import levels, pids_cgroup, run
from course_sandbox.policy import DEFAULT_USER, Limits, Policy
from course_sandbox.run import RunSandbox, capture_oneshot
from course_checks.waiting import wait_for

ROOT = os.geteuid() == 0
LEVEL = levels.detect(DEFAULT_USER)
pytestmark = pytest.mark.skipif(not levels.uses_namespaces(LEVEL),
                                reason="this machine refuses namespaces (%s)" % LEVEL)


@pytest.fixture
def place():
    """An output folder with two students' work, a course folder, and the run's home for alice,
    in a folder the sandbox user can reach (pytest's own tmp_path is in a 0700 folder)."""
    tmp_path = Path(tempfile.mkdtemp(prefix="sandbox-test-"))
    os.chmod(tmp_path, 0o755)
    yield from _fill(tmp_path)
    shutil.rmtree(tmp_path, ignore_errors=True)


def _fill(tmp_path):
    out = tmp_path / "out"
    home = out / "_work" / "alice" / "runs" / "chatter" / "student"
    home.mkdir(parents=True)
    (out / "_work" / "bob").mkdir(parents=True)
    (out / "_work" / "bob" / "secret.py").write_text("bob's solution")
    course = tmp_path / "course"
    course.mkdir()
    (course / "check").write_text("the course's check")
    if ROOT:
        entry = pwd.getpwnam(DEFAULT_USER)
        os.chown(home, entry.pw_uid, entry.pw_gid)
    yield out, home, course


@pytest.fixture
def sandbox(place):
    out, home, course = place
    box = RunSandbox(Policy(LEVEL, DEFAULT_USER, [str(home)], [str(out)], [str(course)], str(home),
                            report=str(out / "sandbox.json")))
    yield box
    box.close()


def shell(box, script, timeout=20.0):
    code, out = box.run_captured(["sh", "-c", script], timeout)
    return code, out.decode()


def test_student_code_sees_only_its_own_processes_and_files(sandbox, place):
    out, home, course = place
    code, text = shell(sandbox, "id -un; ps -e -o pid= | wc -l; ls %s/_work; cat %s/_work/bob/secret.py; "
                                "cat %s/check; touch %s/check %s/x; touch %s/mine && echo wrote-home"
                       % (out, out, course, course, "/usr", home))
    lines = text.splitlines()
    assert code is not None
    if ROOT:
        assert lines[0] == DEFAULT_USER, "root's grader must not run student code as root"
    assert int(lines[1]) <= 4, "a sandbox sees its own processes only (init, sh, ps, wc): %s" % text
    assert "bob" not in text and "bob's solution" not in text
    assert "the course's check" in text, "the course stays readable"
    assert (course / "check").read_text() == "the course's check" and not os.path.exists("/usr/x")
    assert "wrote-home" in text and (home / "mine").exists()


def test_ctrl_c_reaches_the_node_and_its_exit_code_comes_back(sandbox, place):
    _, home, _ = place
    script = home / "node.py"
    # the handler writes with os.write: SIGINT may land while print('ready') is still inside
    # stdout's buffered writer (the line already read here), and a print there raises "reentrant call"
    script.write_text("import os, signal, sys, time\n"
                      "def bye(*_):\n    os.write(1, b'bye\\n')\n    sys.exit(3)\n"
                      "signal.signal(signal.SIGINT, bye)\nprint('ready', flush=True)\n"
                      "while True:\n    time.sleep(0.05)\n")
    argv, env, cwd = sandbox.prepare(["/usr/bin/python3", str(script)])
    proc = subprocess.Popen(argv, env=env, cwd=cwd, stdout=subprocess.PIPE, start_new_session=True)
    assert proc.stdout.readline() == b"ready\n"
    os.killpg(proc.pid, signal.SIGINT)
    assert proc.wait(10) == 3 and proc.stdout.read() == b"bye\n"
    proc.stdout.close()


def test_nothing_outlives_the_run_whatever_it_did(sandbox):
    helper = ("import os, signal, time\n"
              "if os.fork() == 0:\n    os.setsid()\n    if os.fork() == 0:\n"
              "        for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):\n"
              "            signal.signal(s, signal.SIG_IGN)\n"
              "        os.execve('/bin/sleep', ['sleep', '1000'], {})\n    os._exit(0)\n")
    code, text = shell(sandbox, "kill -9 -1; kill -9 1; echo still-here")
    assert "still-here" in text, "the sandbox's init survives what its processes send it"
    code, _ = sandbox.run_captured(["python3", "-c", helper])
    assert code == 0
    left = sandbox.processes()
    assert left, "the helper runs until the run ends"
    sandbox.close()
    for pid in left:
        assert not os.path.exists("/proc/%d" % pid) or open("/proc/%d/stat" % pid).read().split()[2] == "Z"


def test_a_fork_bomb_is_contained_noted_and_ended(place):
    out, home, course = place
    report = out / "sandbox.json"
    with RunSandbox(Policy(LEVEL, DEFAULT_USER, [str(home)], [str(out)], [str(course)], str(home),
                           limits=Limits(processes=64), report=str(report))) as box:
        code, text = box.run_captured(["python3", "-c",
                                       "import os, time\nn = 0\ntry:\n    while n < 10000:\n"
                                       "        if os.fork() == 0:\n            time.sleep(20)\n"
                                       "            os._exit(0)\n        n += 1\n"
                                       "except OSError as e:\n    print(n, e.errno, flush=True)\n"
                                       "time.sleep(20)\n"], timeout=15)
        assert text and int(text.split()[0]) < 64, "fork() must fail at the limit: %r" % text
        assert "processes" in box.hits.hits
        assert code is not None and code < 0, "the watcher ends a run at its process limit"
    assert "process limit" in report.read_text()


def test_a_limit_reached_just_before_the_end_is_still_noted(place, monkeypatch):
    """A run can end within a watch interval of its code reaching a limit (a fork bomb keeps the
    node from starting, the check fails at once): closing takes a last look."""
    monkeypatch.setattr(run, "WATCH_INTERVAL_S", 3600.0)  # the watcher never gets to look
    out, home, course = place
    report = out / "sandbox.json"
    box = RunSandbox(Policy(LEVEL, DEFAULT_USER, [str(home)], [str(out)], [str(course)], str(home),
                            limits=Limits(processes=32), report=str(report)))
    argv, env, cwd = box.prepare(["python3", "-c", "import os, time\nfor _ in range(64):\n    try:\n"
                                  "        if os.fork() == 0:\n            time.sleep(60)\n            os._exit(0)\n"
                                  "    except OSError:\n        break\ntime.sleep(60)\n"])
    proc = subprocess.Popen(argv, env=env, cwd=cwd, start_new_session=True)
    try:
        assert wait_for(lambda: len(box.processes()) >= 30, 20), "the forks fill the sandbox"
    finally:
        box.close()
    assert proc.wait(10) is not None
    assert "process limit" in report.read_text()


def _stopped_student(box):
    """A student process that stops itself; nsenter, outside, stops too (it passes job-control
    stops on) and would stay stopped once its child is killed."""
    argv, env, cwd = box.prepare(["sh", "-c", "kill -STOP $$; echo never"])
    proc = subprocess.Popen(argv, env=env, cwd=cwd, stdout=subprocess.DEVNULL, start_new_session=True)

    def state():
        try:
            return open("/proc/%d/stat" % proc.pid).read().rsplit(")", 1)[1].split()[0]
        except OSError:
            return None
    assert wait_for(lambda: state() == "T", 10), "nsenter passes its child's stop on to itself"
    return proc


def test_ending_a_stopped_process_ends_its_nsenter_too(sandbox):
    proc = _stopped_student(sandbox)
    sandbox.end_processes()
    assert proc.wait(10) == -signal.SIGKILL, "the run's command reports the kill"


def test_closing_a_run_with_a_stopped_process_leaves_nothing(sandbox):
    proc = _stopped_student(sandbox)
    left = sandbox.processes()
    sandbox.close()
    assert proc.wait(10) == -signal.SIGKILL
    assert wait_for(lambda: not any(os.path.exists("/proc/%d" % pid) for pid in left), 10)


def test_the_keeper_outlives_the_thread_that_started_it(sandbox):
    """bubblewrap dies with the thread that started it (--die-with-parent): a first student
    process started from a short-lived thread must not take the run's sandbox with it."""
    worker = threading.Thread(target=lambda: shell(sandbox, "true"))
    worker.start()
    worker.join()
    code, text = shell(sandbox, "echo alive")
    assert (code, text) == (0, "alive\n")


def test_a_build_sandbox_writes_only_its_workspace(place):
    out, home, course = place
    policy = Policy(LEVEL, DEFAULT_USER, [str(home)], [str(out)], [str(course)], str(home))
    code, text = capture_oneshot(policy, ["sh", "-c", "echo x > %s/built; echo y > %s/evil; ls %s/_work; echo done"
                                          % (home, course, out)], str(home), dict(os.environ))
    assert code == 0 and b"done" in text and b"bob" not in text
    assert (home / "built").exists() and not (course / "evil").exists()


# What a student's shell and Python say of the folder they start in (pwd -P and os.getcwd ask the kernel).
WHERE = "pwd -P; python3 -c 'import os; print(os.getcwd())'"


def _unlisted_work_folder(out):
    """The grader's work folder of a student is 0711 (course_grader.runner): the sandbox user
    passes through it to the run's home but cannot list it."""
    os.chmod(out / "_work" / "alice", 0o711)


def test_a_student_process_starts_in_its_home_as_the_sandbox_shows_it(sandbox, place):
    """A process the sandbox starts finds its working directory, whatever the folders above it
    allow: entered by nsenter --wd, it sat in the host's mount of its home, which the sandbox
    cannot name, and its shell began the student's log with `sh: 0: getcwd() failed`."""
    out, home, _ = place
    _unlisted_work_folder(out)
    argv, env, cwd = sandbox.prepare(["sh", "-c", WHERE + "; echo \"$PWD\""])
    done = subprocess.run(argv, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=30)
    text = done.stdout.decode()
    assert "getcwd" not in text and text.split() == [str(home)] * 3, text


def test_a_build_starts_in_its_workspace_as_the_sandbox_shows_it(place):
    out, home, course = place
    _unlisted_work_folder(out)
    policy = Policy(LEVEL, DEFAULT_USER, [str(home)], [str(out)], [str(course)], str(home))
    code, text = capture_oneshot(policy, ["sh", "-c", WHERE + " 2>&1"], str(home), dict(os.environ))
    assert code == 0 and text.decode().split() == [str(home)] * 2, text


# Forks until refused, keeps what it made, says how many, then holds them.
HOLDING_BOMB = ("import os, time\nn = 0\nwhile True:\n    try:\n        if os.fork() == 0:\n"
                "            time.sleep(60)\n            os._exit(0)\n        n += 1\n    except OSError:\n"
                "        break\nprint('refused after', n, flush=True)\ntime.sleep(60)\n")
THREADS = ("import threading, time\nn = 0\nfor _ in range(48):\n    try:\n"
           "        threading.Thread(target=time.sleep, args=(30,), daemon=True).start()\n        n += 1\n"
           "    except RuntimeError:\n        break\nprint('threads', n, flush=True)\n")


def _start(box, script):
    argv, env, cwd = box.prepare(["python3", "-u", "-c", script])
    return subprocess.Popen(argv, env=env, cwd=cwd, stdout=subprocess.PIPE, start_new_session=True)


@pytest.mark.parametrize("level", [LEVEL] + ([levels.USER] if ROOT and pids_cgroup.available() else []))
def test_fork_bombs_in_runs_at_once_each_meet_their_own_limit_only(place, monkeypatch, level):
    """Two runs' fork bombs at their limits at once, and a third run still starts its threads:
    a run's process limit is its own (its user namespace, or its pids cgroup where no namespace
    gives one: at isolation `user only`, RLIMIT_NPROC alone would be the sandbox user's, shared)."""
    monkeypatch.setattr(run, "WATCH_INTERVAL_S", 3600.0)  # the bombs hold their processes until closed
    out, home, course = place
    boxes = [RunSandbox(Policy(level, DEFAULT_USER, [str(home)], [str(out)], [str(course)], str(home),
                               limits=Limits(processes=64), report=str(out / ("sandbox%d.json" % i))))
             for i in range(3)]
    try:
        bombs = [_start(box, HOLDING_BOMB) for box in boxes[:2]]
        for bomb in bombs:
            made = bomb.stdout.readline().split()
            assert made[:2] == [b"refused", b"after"] and int(made[2]) < 64, made
        threads = _start(boxes[2], THREADS)
        assert threads.stdout.readline().split() == [b"threads", b"48"], "the third run's limit is its own"
        threads.wait(20)
    finally:
        for box in boxes:
            box.close()
    for i in range(2):
        assert "process limit" in (out / ("sandbox%d.json" % i)).read_text()
    assert "process limit" not in (out / "sandbox2.json").read_text()
    for bomb in bombs:
        assert bomb.wait(10) is not None


@pytest.mark.skipif(not (ROOT and pids_cgroup.available()), reason="no pids cgroup on this machine")
def test_a_refused_fork_is_noted_however_few_processes_remain(place, monkeypatch):
    """The kernel counts a run's refused forks: a run that reached its limit is noted even when
    no sample ever sees it near the limit (forks under way are not in /proc, a sample under a
    fork bomb lags). Here the bomb ends its own forks before the only look, at close."""
    monkeypatch.setattr(run, "WATCH_INTERVAL_S", 3600.0)
    out, home, course = place
    report = out / "sandbox.json"
    box = RunSandbox(Policy(LEVEL, DEFAULT_USER, [str(home)], [str(out)], [str(course)], str(home),
                            limits=Limits(processes=32), report=str(report)))
    try:
        proc = _start(box, "import os, signal\nkids = []\nwhile True:\n    try:\n        pid = os.fork()\n"
                           "    except OSError:\n        break\n    if pid == 0:\n        signal.pause()\n"
                           "    kids.append(pid)\nfor pid in kids:\n    os.kill(pid, 9)\n    os.waitpid(pid, 0)\n"
                           "print('alone again', flush=True)\nsignal.pause()\n")
        assert proc.stdout.readline() == b"alone again\n"
        assert box.counts_processes
        assert len(box.processes()) <= 3, "the forks are gone: nothing near the limit to see"
        cgroup = box._cgroup.path
    finally:
        box.close()
    assert "process limit" in report.read_text()
    assert not os.path.exists(cgroup), "the run's cgroup goes with it"
