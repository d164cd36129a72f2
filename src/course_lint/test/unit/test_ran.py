"""`not run`, measured: the probe's records (course_lint.probe under coverage.py in a real Python
process, ended with SIGKILL as a check ends a node; exec_log.c compiled and loaded by the dynamic
linker), how course_lint.ran reads them, and which mutants they leave not run: a mutant on a line
the reference never ran needs no grading, one on a line that ran is graded, and so is every
mutant whose kind of file went unmeasured."""
import os
import shutil
import signal
import subprocess
import sys

from hypothesis import given, settings
from hypothesis import strategies as st

from course_lint import mutants, ran

PUBLISH_REMOVED = mutants.by_names(["publish_removed"])[0]
EXIT_AFTER_ONE = mutants.by_names(["exit_after_one"])[0]
PARAM_CHANGED = mutants.by_names(["param_changed"])[0]
SWAP_XY = mutants.by_names(["swap_xy"])[0]

NODE = '''#!/usr/bin/env python3
import sys


def publish(words):
    sys.stdout.write(words + "\\n")
    sys.stdout.flush()


def never(words):
    publish(words)


count = 41
publish("ready %d" % (count + 1))
sys.stdin.readline()
publish("after the kill")
'''


def measured(run_lines, programs=(), opened=(), python="", started=""):
    return ran.Ran({k: frozenset(v) for k, v in run_lines.items()}, frozenset(opened), frozenset(programs),
                   python, started)


def mutant(operator, path, text, package="talk"):
    return mutants.Mutant(package, operator, path, 0, "", text)


def test_a_line_run_just_before_a_kill_is_recorded_and_lines_never_run_are_not(tmp_path):
    """The node prints "ready" from a Python function, then blocks; it is killed (SIGKILL, no exit
    handler runs) as soon as the line is read: the lines up to that call are in the records (written
    when the function was entered, before it printed), the never-called function's body and the
    line after the kill are not."""
    src = tmp_path / "ws" / "src"
    script = src / "talk" / "scripts" / "node.py"
    script.parent.mkdir(parents=True)
    script.write_text(NODE)
    script.chmod(0o755)
    data = tmp_path / "data"
    data.mkdir()
    env = dict(os.environ, COURSE_LINT_DATA=str(data), COURSE_LINT_SRC=str(src),
               PYTHONPATH=os.pathsep.join([ran.probe_folder(), os.environ.get("PYTHONPATH", "")]))
    node = subprocess.Popen([sys.executable, str(script)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env)
    try:
        assert node.stdout.readline() == b"ready 42\n"
    finally:
        node.send_signal(signal.SIGKILL)
        node.wait()
    texts = [(p.name, p.read_text()) for p in data.iterdir()]
    record = ran.parse(texts, os.path.realpath(str(src)))
    lines = record.lines["talk/scripts/node.py"]
    assert {14, 15} <= lines  # count = 41; the call that prints "ready", written as publish() was entered
    assert not lines & {11, 17}, lines  # never()'s body; the line after the kill
    assert "talk/scripts/node.py" in record.opened
    assert record.python == "no Python process of the run was measured" or record.python == ""
    # the mutants: publish_removed in never() is not run; exit_after_one after line 14's publish runs
    in_never = NODE.replace('    publish(words)\n', '    pass\n')
    assert ran.not_run(mutant(PUBLISH_REMOVED, "scripts/node.py", in_never), NODE, record, "talk") == "line 11 never ran"
    after_publish = NODE.replace('publish("ready %d" % (count + 1))\n', 'publish("ready %d" % (count + 1))\nos._exit(0)\n')
    assert ran.not_run(mutant(EXIT_AFTER_ONE, "scripts/node.py", after_publish), NODE, record, "talk") == ""


def test_the_exec_log_records_each_program_a_process_starts(tmp_path):
    compiler = shutil.which("cc") or shutil.which("gcc")
    assert compiler, "no C compiler (make deps installs g++, which brings gcc)"
    library = tmp_path / "libexec_log.so"
    subprocess.run([compiler, "-shared", "-fPIC", "-O2", "-Wall", "-Werror", "-o", str(library),
                    os.path.join(ran.probe_folder(), "exec_log.c")], check=True)
    data = tmp_path / "data"
    data.mkdir()
    env = dict(os.environ, COURSE_LINT_DATA=str(data), LD_AUDIT=str(library))
    subprocess.run(["/bin/sh", "-c", "/bin/true one two; exec /bin/echo three"], env=env, check=True,
                   stdout=subprocess.DEVNULL)
    record = ran.parse([(p.name, p.read_text()) for p in data.iterdir()], str(tmp_path))
    assert {os.path.realpath("/bin/true"), os.path.realpath("/bin/echo")} <= record.programs
    assert record.started == ""
    words = [line.split("\t")[4] for p in data.iterdir() for line in p.read_text().splitlines()]
    assert "/bin/true\x1fone\x1ftwo" in words


def test_a_python_process_without_a_record_leaves_python_unmeasured():
    """Every Python interpreter the exec log saw start must have loaded the probe (a record of its
    own, same pid namespace and pid); else its lines are unknown and Python's mutants are graded."""
    src = "/w/src"
    start = "start\t7\t31\t1\t[\"/w/src/talk/a.py\"]\n"
    run_a = "exec\t7\t31\t/usr/bin/python3.11\tpython3\x1f/w/src/talk/a.py\n"
    shell = "exec\t7\t30\t/usr/bin/bash\tbash\x1f-c\x1fx\n"
    assert ran.parse([("py.7.31", start), ("exec.7.31", run_a + shell)], src).python == ""
    run_b = "exec\t7\t32\t/usr/bin/python3.11\tpython3\x1f-m\x1ftalk.b\n"
    missing = ran.parse([("py.7.31", start), ("exec.7.31", run_a + run_b)], src)
    assert missing.python == "a Python process of the run left no record of its lines (pid 32: python3 -m talk.b)"
    other_namespace = start.replace("\t7\t", "\t8\t")
    assert ran.parse([("py.8.31", other_namespace), ("exec.7.31", run_a)], src).python.startswith("a Python process")
    failed = ran.parse([("py.7.31", start + "error\tImportError: No module named 'coverage'\n")], src)
    assert failed.python.startswith("coverage.py failed in a process of the run: ImportError")
    nothing = ran.parse([], src)
    assert (nothing.python, nothing.started) == ("no Python process of the run was measured",
                                                 "the run left no exec log (LD_AUDIT)")
    assert ran.parse([("py.7.31", start)], src).python == ""  # no exec log: a measured process will do


def test_unmeasured_kinds_are_graded():
    text = "x = 1\n"
    python = mutant(PUBLISH_REMOVED, "a.py", "x = 2\n")
    assert ran.not_run(python, text, measured({}), "talk") == "a.py never ran"
    assert ran.not_run(python, text, measured({}, python="no Python process of the run was measured"), "talk") == ""
    launch = mutant(PARAM_CHANGED, "launch/two.launch", "<launch/>")
    assert ran.not_run(launch, "<launch></launch>", measured({}, opened={"talk/launch/one.launch"}), "talk") \
        == "two.launch was never launched"
    assert ran.not_run(launch, "<launch></launch>", measured({}, opened={"talk/launch/two.launch"}), "talk") == ""
    assert ran.not_run(launch, "<launch></launch>", measured({}, python="broken"), "talk") == ""


CMAKE = "add_executable(talker src/talker.cpp src/common.cpp)\nadd_executable(listener src/listener.cpp)\n"


def test_a_cpp_file_is_not_run_when_no_executable_built_from_it_started():
    listener = mutant(SWAP_XY, "src/listener.cpp", "y")
    common = mutant(SWAP_XY, "src/common.cpp", "y")
    header = mutant(SWAP_XY, "include/talk/common.h", "y")
    talker_ran = measured({}, programs={"/w/devel/lib/talk/talker", "/usr/bin/env"})
    assert ran.not_run(listener, "x", talker_ran, "talk", CMAKE) == "listener never started"
    assert ran.not_run(common, "x", talker_ran, "talk", CMAKE) == ""
    assert ran.not_run(header, "x", talker_ran, "talk", CMAKE) == ""  # which executables include it: not told
    renamed = measured({}, programs={"/w/devel/lib/talk/talker", "/w/devel/lib/talk/listener_node"})
    assert ran.not_run(listener, "x", renamed, "talk", CMAKE) == ""  # a program of the package no target names
    assert ran.not_run(listener, "x", measured({}, started="no exec log"), "talk", CMAKE) == ""
    build = mutant(mutants.by_names(["msg_left_out"])[0], "CMakeLists.txt", "")
    assert ran.not_run(build, CMAKE, measured({}), "talk", CMAKE) == ""  # the build always runs


SOURCE = '''import rospy


def talker(pub,
           rate):
    if rate:
        pub.publish(
            "hello")
    else:
        pass
'''


def test_a_line_ran_when_any_line_of_its_statement_did():
    assert ran.statements_of(SOURCE, [8]) == [(7, 8)]  # the second line of a call
    assert ran.statements_of(SOURCE, [5]) == [(4, 5)]  # a def's header, over two lines
    assert ran.statements_of(SOURCE, [9]) is None  # `else:` belongs to no statement: cannot be told
    assert ran.statements_of("x = (\n", [1]) is None  # does not parse
    changed = SOURCE.replace('"hello"', '"bye"')
    record = measured({"talk/a.py": {1, 4, 6, 7}})
    assert ran.not_run(mutant(PUBLISH_REMOVED, "a.py", changed), SOURCE, record, "talk") == ""
    assert ran.not_run(mutant(PUBLISH_REMOVED, "a.py", SOURCE.replace("pass", "x = 1")), SOURCE, record, "talk") \
        == "line 10 never ran"


lines_of_text = st.lists(st.text(alphabet="abc =()", min_size=1, max_size=6), min_size=1, max_size=12)


@settings(max_examples=200, deadline=None)
@given(lines_of_text, st.data())
def test_changed_lines_name_the_line_replaced_or_the_one_above_an_insertion(lines, data):
    at = data.draw(st.integers(0, len(lines) - 1))
    replaced = lines[:at] + [lines[at] + "!"] + lines[at + 1:]
    assert ran.changed_lines("\n".join(lines), "\n".join(replaced)) == [at + 1]
    inserted = lines[:at + 1] + ["!!"] + lines[at + 1:]
    assert ran.changed_lines("\n".join(lines), "\n".join(inserted)) == [at + 1]
    deleted = lines[:at] + lines[at + 1:]
    assert len(ran.changed_lines("\n".join(lines), "\n".join(deleted))) == 1  # one line, maybe a twin of it


def test_the_probe_package_is_laid_out_with_its_hook_and_files(tmp_path):
    folder = ran.lay_out(str(tmp_path))
    names = sorted(os.path.relpath(os.path.join(r, f), folder) for r, _, files in os.walk(folder) for f in files)
    assert names == ["CMakeLists.txt", "env-hooks/50.course_lint_probe.sh.in", "exec_log.c", "package.xml",
                     "site/sitecustomize.py"]
    hook = (tmp_path / "course_lint_probe" / "env-hooks" / "50.course_lint_probe.sh.in").read_text()
    for word in ("COURSE_LINT_DATA=", "COURSE_LINT_SRC=", "PYTHONPATH=", "LD_AUDIT="):
        assert word in hook
    assert os.path.isdir(os.path.join(folder, "data"))
