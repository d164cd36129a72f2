"""gradebook.csv, Gradescope results.json, report.html and the build-failure summary."""
import json

from course_format.milestone import Milestone

from course_grader import gradebook, gradescope, report
from course_grader.verdict import Verdict

CHATTER = Milestone("chatter", "Example pub/sub", "002 section 2", "chatter.test", ("chatter",))
CP1 = Milestone("checkpoint1", "TimestampString", "002 checkpoint 1", "checkpoint1.test", ("my_chatter",), 20.0)
UNUSED = Milestone("arch", "Arch", "003", "arch.test", ("my_pkg",))
ORDER = [CHATTER, CP1, UNUSED]
VERDICTS = [Verdict("alice", CHATTER, True, ""), Verdict("alice", CP1, False, "no /user_messages <b>"),
            Verdict("bob", CP1, True, "")]


def test_gradebook_rows():
    assert gradebook.rows(VERDICTS, ORDER) == [["student", "chatter", "checkpoint1", "total", "max"],
                                               ["alice", "10", "0", "10", "30"],
                                               ["bob", "", "20", "20", "20"]]


def test_results_json_has_gradescopes_fields(tmp_path):
    path = tmp_path / "results.json"
    gradescope.write(str(path), VERDICTS[:2], 12.4, "packages found: chatter")
    results = json.loads(path.read_text())
    assert results["score"] == 10.0 and results["execution_time"] == 12
    assert set(results) >= {"score", "output", "tests", "visibility"}
    first, second = results["tests"]
    assert first["name"].startswith("chatter: ") and first["status"] == "passed"
    assert (second["score"], second["max_score"], second["status"]) == (0.0, 20.0, "failed")
    assert second["output"].startswith("FAILED: no /user_messages")
    assert all(t["visibility"] == "visible" and isinstance(t["output"], str) for t in results["tests"])


def test_report_escapes_and_links_canvases(tmp_path):
    student_dir = tmp_path / "alice" / "chatter"
    student_dir.mkdir(parents=True)
    (student_dir / "canvas.png").write_bytes(b"png")
    verdicts = [VERDICTS[0]._replace(artifacts_dir=str(student_dir)), VERDICTS[1]]
    page = report.render(verdicts, ORDER, str(tmp_path))
    assert 'src="alice/chatter/canvas.png"' in page
    assert "&lt;b&gt;" in page and "<b>" not in page.split("<body>")[1]


def test_shadowed_modules_protect_the_checks_but_not_the_reference(tmp_path):
    from course_grader.workspace import shadowed_modules
    site = tmp_path / "ws" / "devel" / "lib" / "python3" / "dist-packages"
    course = tmp_path / "course_site"
    for name in ("course_testkit", "rospy", "my_chatter", "student_helpers", "my_chatter-0.0.0.egg-info"):
        (site / name).mkdir(parents=True)
    for name in ("course_testkit", "my_chatter"):
        (course / name).mkdir(parents=True)
    (site / "json.py").write_text("")
    found = shadowed_modules(str(tmp_path / "ws"), {"course_testkit", "turtlesim"}, str(course))
    assert found == ["course_testkit", "json", "rospy"]
