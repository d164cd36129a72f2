"""course_milestones.scripts: the one detector of scripts rosrun cannot start."""
from course_format import causes
from course_milestones.scripts import output_problems, script_problems


def test_script_problems_name_missing_chmod_and_crlf(tmp_path):
    pkg = tmp_path / "chatter"
    (pkg / "scripts").mkdir(parents=True)
    (pkg / "scripts/talker.py").write_text("#!/usr/bin/env python3\nprint(1)\n")
    crlf = pkg / "scripts/listener.py"
    crlf.write_bytes(b"#!/usr/bin/env python3\r\nprint(1)\r\n")
    crlf.chmod(0o755)
    helper = pkg / "scripts/helper.py"
    helper.write_text("def f():\n    pass\n")
    problems = script_problems(str(pkg))
    assert len(problems) == 2
    assert "chatter/scripts/listener.py has Windows line endings" in problems[0] and "python3\\r" in problems[0]
    assert "chatter/scripts/talker.py starts with #! but is not executable" in problems[1]


def test_build_folders_and_big_files_are_not_read(tmp_path):
    pkg = tmp_path / "chatter"
    (pkg / "build").mkdir(parents=True)
    (pkg / "build/gen.py").write_text("#!/usr/bin/env python3\n")
    (pkg / "data.bin").write_bytes(b"#!" + b"x" * (2 * 1024 * 1024))
    assert script_problems(str(pkg)) == []


def test_an_executable_script_without_a_shebang_and_python_2_are_named_from_the_files(tmp_path):
    pkg = tmp_path / "chatter"
    (pkg / "scripts").mkdir(parents=True)
    bare = pkg / "scripts/talker.py"
    bare.write_text("import rospy\nrospy.init_node('talker')\n")
    bare.chmod(0o755)
    (pkg / "scripts/old.py").write_text("#!/usr/bin/env python3\nprint 'hello'\n")
    (pkg / "scripts/catch.py").write_text("#!/usr/bin/env python3\ntry:\n    pass\nexcept ValueError, e:\n    pass\n")
    (pkg / "scripts/compat.py").write_text("try:\n    input = raw_input\nexcept NameError:\n    pass\n")
    (pkg / "scripts/module.py").write_text("x = 1\n")  # no #! and not executable: a module, fine
    for name in ("old.py", "catch.py"):
        (pkg / "scripts" / name).chmod(0o755)
    problems = script_problems(str(pkg))
    assert [causes.of(p) for p in problems] == ["python2", "python2", "no_shebang"], problems
    assert "chatter/scripts/catch.py line 4: `except ValueError, e:` is Python 2" in problems[0]
    assert "write `except ValueError as e:`" in problems[0]
    assert "chatter/scripts/old.py line 2: `print 'hello'` is Python 2's print statement" in problems[1]
    assert "chatter/scripts/talker.py has no #! line, so rosrun runs it with sh" in problems[2]


def test_what_the_process_printed_names_its_cause():
    said = output_problems("/opt/ros/x/talker.py: 2: import: not found\n"
                           "Traceback...\nNameError: name 'raw_input' is not defined\n"
                           "TypeError: list indices must be integers or slices, not float\n"
                           "/usr/bin/env: 'python': No such file or directory\n")
    assert [causes.of(s) for s in said] == ["no_shebang", "python2", "python2", "python2"]
    assert "write #!/usr/bin/env python3" in said[1] and "write input(...)" in said[2] and "//" in said[3]
    assert output_problems("all fine\n") == []


def test_a_script_catkin_install_python_lists_needs_no_executable_bit(tmp_path):
    """catkin's devel space relays each script catkin_install_python lists (devel/lib/PKG/NAME, an
    executable running the source): rosrun starts it without chmod +x, so it is no problem."""
    pkg = tmp_path / "chatter"
    (pkg / "scripts").mkdir(parents=True)
    (pkg / "nodes").mkdir()
    for name in ("scripts/talker.py", "scripts/listener.py", "nodes/relay.py", "scripts/left_out.py"):
        (pkg / name).write_text("#!/usr/bin/env python3\nprint(1)\n")
    (pkg / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.0.2)\nproject(chatter)\n"
        "# catkin_install_python(PROGRAMS scripts/left_out.py DESTINATION x)  (a comment)\n"
        "catkin_install_python(PROGRAMS\n  scripts/talker.py \"scripts/listener.py\"\n"
        "  ${CMAKE_CURRENT_SOURCE_DIR}/nodes/relay.py\n  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})\n")
    problems = script_problems(str(pkg))
    assert len(problems) == 1 and "chatter/scripts/left_out.py starts with #! but is not executable" in problems[0]
    (pkg / "CMakeLists.txt").write_text("catkin_install_python(PROGRAMS scripts/talker.py)\n")  # no DESTINATION
    assert len(script_problems(str(pkg))) == 3
