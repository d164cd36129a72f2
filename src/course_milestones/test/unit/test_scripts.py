"""course_milestones.scripts: the one detector of scripts rosrun cannot start."""
from course_milestones.scripts import script_problems


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
