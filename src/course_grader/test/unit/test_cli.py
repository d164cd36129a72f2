"""The command line: milestone names and submissions after --only."""
from course_grader.cli import main, parse, split_only


def test_only_takes_several_names_and_leaves_paths_to_the_submissions(tmp_path):
    names = {"chatter", "checkpoint1"}
    student = str(tmp_path)
    assert split_only(["chatter", "checkpoint1", student], names) == (["chatter", "checkpoint1"], [student])
    assert split_only(None, names) == (None, [])
    assert split_only(["nope"], names) == (["nope"], [])
    opts = parse(["a.zip", "--only", "chatter", "--only", "checkpoint1", "--jobs", "4"])
    assert opts.only == ["chatter", "checkpoint1"] and opts.jobs == 4 and opts.submissions == ["a.zip"]


def test_list_and_unknown_milestones(capsys):
    assert main(["--list"]) == 0
    assert "chatter" in capsys.readouterr().out
    assert main(["--only", "no_such_milestone"]) == 2


def test_without_submissions_or_reference_solutions_it_says_so(capsys, tmp_path):
    """The student image has no course solution/: `make grade` alone has nothing to grade."""
    course = tmp_path / "course"
    (course / "solution").mkdir(parents=True)  # a folder, but no package in it
    (course / "course.yaml").write_text("name: c\ntitle: C\nsolution: solution\nmilestones:\n  - id: m\n    title: M\n"
                                        "    text: T\n    steps:\n      - start: {rosrun: p n}\n")
    assert main(["--course", str(course), "--out", str(tmp_path / "grades")]) == 2
    assert "no reference solutions" in capsys.readouterr().err
