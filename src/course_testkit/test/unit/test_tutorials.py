"""course_testkit.tutorials' judgements, on made-up figures (the suite itself needs the tutorials'
sources, which are not in the repository: `make tutorials-check TUTORIALS=DIR`, tests/e2e/test_tutorials.py,
docs/noetic_cxx.md)."""
from course_testkit import tutorials


def samples(follow_distances, turtle2_end=(5.6, 9.5)):
    """A catch-up, a drive taking turtle1 2.4 m away, then turtle2 closing in over `follow_distances`."""
    rows = [["catch-up", 0.0, 5.54, 5.54, 4.0, 2.0, 3.7], ["catch-up", 0.5, 5.54, 5.54, 5.4, 5.1, 0.45],
            ["drive", 1.0, 5.54, 5.54, 5.41, 5.09, 0.48], ["drive", 2.0, 7.25, 6.52, 5.82, 5.44, 1.79],
            ["drive", 3.0, 7.31, 8.45, 6.54, 6.20, 2.37]]
    for i, d in enumerate(follow_distances):
        rows.append(["follow", 3.5 + i, 5.68, 9.54, 6.70 - (i + 1) * (6.70 - turtle2_end[0]) / len(follow_distances),
                     7.40 + (i + 1) * (turtle2_end[1] - 7.40) / len(follow_distances), d])
    rows.append(["end"] + rows[-1][1:])
    return rows


def test_a_turtle2_that_closes_in_passes():
    assert tutorials.judge(samples([2.37, 1.42, 0.84, 0.50, 0.30, 0.10])) == ""


def test_a_turtle2_left_behind_fails():
    assert tutorials.judge(samples([2.37, 2.2, 2.0, 1.9])).startswith("turtle2 did not follow: 1.90 m")


def test_a_turtle2_that_never_moved_fails_even_if_close():
    reason = tutorials.judge(samples([0.3, 0.3], turtle2_end=(6.70, 7.40)))
    assert reason.startswith("turtle2 did not follow") and "having moved 0.00 m" in reason


def test_a_drive_that_did_not_take_turtle1_away_fails():
    rows = [r if r[0] not in ("drive", "follow", "end") else r[:6] + [0.4] for r in samples([0.3, 0.2])]
    assert tutorials.judge(rows).startswith("turtle1's drive took it only 0.40 m")


def test_the_table_starts_at_the_drive_one_row_a_second():
    rows = tutorials.follow_table(samples([2.37, 1.42, 0.84]))
    assert rows[0].split() == ["t", "(s)", "phase", "turtle1", "(x,", "y)", "turtle2", "(x,", "y)", "distance", "(m)"]
    assert [r.split()[0] for r in rows[1:]] == ["0.0", "1.0", "2.0", "3.5", "4.5", "4.5"]
    assert rows[-1].split()[1] == "end"


def test_junit_failures_name_the_file_and_the_case(tmp_path):
    (tmp_path / "rospy_tutorials").mkdir()
    (tmp_path / "rospy_tutorials" / "rostest-a.xml").write_text(
        '<testsuite tests="2" failures="1"><testcase name="ok"/><testcase name="talks">'
        '<failure message="no"/></testcase></testsuite>')
    (tmp_path / "rospy_tutorials" / "rosunit-b.xml").write_text("<testsuite><testcase name=")
    assert tutorials.junit_failures(tmp_path) == ["rostest-a.xml: talks", "rosunit-b.xml: not valid XML"]
