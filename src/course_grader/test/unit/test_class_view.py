"""The class at a glance (class_view), results.json read back (gradescope.load), the class files
written again for a regrade (class_outputs.merged), and the report's first section."""
import csv
import json

from course_format import causes
from course_format.milestone import Milestone

from course_grader import class_outputs, class_view, gradescope, report
from course_grader.verdict import Verdict

CHATTER = Milestone("chatter", "Example pub/sub", "002 section 2", "chatter.test", ("chatter",))
CP1 = Milestone("checkpoint1", "TimestampString", "002 checkpoint 1", "checkpoint1.test", ("my_chatter",), 20.0)
ORDER = [CHATTER, CP1]
CLASS = [Verdict("ann", CHATTER, True, "", elapsed=10.0), Verdict("ann", CP1, False, "no /user_messages", elapsed=30.0,
                                                                 cause="wrong_topic"),
         Verdict("bob", CHATTER, False, "not linked", cause="not_linked"),
         Verdict("bob", CP1, False, "no /user_messages", elapsed=20.0, cause="wrong_topic"),
         Verdict("cy", CHATTER, False, "something", elapsed=12.0),
         Verdict("cy", CP1, True, "", elapsed=26.0)]


def test_milestone_stats_leave_out_runs_that_never_ran():
    stats = {s.milestone.name: s for s in class_view.milestone_stats(CLASS, ORDER)}
    assert (stats["chatter"].graded, stats["chatter"].passed, stats["chatter"].median_s) == (3, 1, 11.0)
    assert (stats["checkpoint1"].graded, stats["checkpoint1"].passed, stats["checkpoint1"].median_s) == (3, 1, 26.0)


def test_failures_group_on_their_cause_largest_first_unknown_per_milestone():
    groups = class_view.failure_groups(CLASS)
    assert [(g.milestone, g.cause, g.students) for g in groups] == [
        ("checkpoint1", "wrong_topic", ["ann", "bob"]), ("chatter", causes.CHECK_FAILED, ["cy"]),
        ("chatter", "not_linked", ["bob"])]
    assert groups[0].label == causes.label("wrong_topic")


def test_csvs_beside_the_gradebook(tmp_path):
    class_view.write_csvs(str(tmp_path), CLASS, ORDER)
    rows = list(csv.reader((tmp_path / "milestones.csv").open()))
    assert rows == [["milestone", "graded", "passed", "median_seconds"], ["chatter", "3", "1", "11.0"],
                    ["checkpoint1", "3", "1", "26.0"]]
    rows = list(csv.reader((tmp_path / "failure_groups.csv").open()))
    assert rows[:2] == [["milestone", "cause", "count", "students"], ["checkpoint1", "wrong_topic", "2", "ann bob"]]


def test_summary_names_the_largest_groups():
    lines = class_view.summary(CLASS, ORDER)
    assert lines[0].split()[:2] == ["chatter", "1/3"]
    assert lines[2].startswith("  2 x checkpoint1: %s (ann, bob)" % causes.label("wrong_topic"))


def test_a_finding_carries_its_cause_and_an_unknown_key_is_refused():
    made = causes.finding("not_linked", "hint: x is not linked")
    assert made == "hint: x is not linked" and causes.of(made) == "not_linked"
    assert causes.of("plain text", "dflt") == "dflt" and causes.of("%s" % made) == ""
    try:
        causes.finding("not_linkd", "x")
        raise AssertionError("a misspelt cause was accepted")
    except ValueError:
        pass


def test_checks_record_causes_and_a_forged_key_is_ignored(tmp_path):
    causes.record(str(tmp_path), "stopped_listening")
    causes.record(str(tmp_path), "timeout")
    assert causes.recorded(str(tmp_path)) == ["stopped_listening", "timeout"]
    (tmp_path / causes.RECORD_FILE).write_text('["<script>", 3, "timeout"]')
    assert causes.recorded(str(tmp_path)) == ["timeout"]
    (tmp_path / causes.RECORD_FILE).write_text("{not json")
    assert causes.recorded(str(tmp_path)) == []


def test_results_json_reads_back_as_the_verdicts(tmp_path):
    path = str(tmp_path / "results.json")
    written = [CLASS[0]._replace(logs="--- last lines of a.log ---\nx"), CLASS[1]]
    gradescope.write(path, written, 40.0)
    back = gradescope.load(path, "ann", {m.name: m for m in ORDER})
    assert [(v.milestone.name, v.passed, v.reason, v.elapsed, v.cause_key) for v in back] == [
        ("chatter", True, "", 10.0, ""), ("checkpoint1", False, "no /user_messages", 30.0, "wrong_topic")]
    assert back[0].logs == "--- last lines of a.log ---\nx"
    assert json.loads(open(path).read())["tests"][1]["extra_data"]["cause"] == "wrong_topic"


def test_a_regrade_keeps_everyone_elses_verdicts_and_the_order(tmp_path):
    out = str(tmp_path)
    for student in ("ann", "bob", "cy"):
        (tmp_path / student).mkdir()
        gradescope.write(str(tmp_path / student / "results.json"), [v for v in CLASS if v.student == student], 1.0)
    (tmp_path / "gradebook.csv").write_text("student,chatter,checkpoint1,total,max\ncy,,\nann,,\nbob,,\n")
    new = [Verdict("bob", CHATTER, True, "", elapsed=9.0), Verdict("bob", CP1, True, "", elapsed=21.0)]
    merged = class_outputs.merged(out, "bob", new, ORDER)
    assert [(v.student, v.milestone.name, v.passed) for v in merged] == [
        ("cy", "chatter", False), ("cy", "checkpoint1", True), ("ann", "chatter", True),
        ("ann", "checkpoint1", False), ("bob", "chatter", True), ("bob", "checkpoint1", True)]
    assert merged[1].cause_key == "" and merged[3].cause_key == "wrong_topic"


def test_report_shows_the_class_first_and_works_without_javascript(tmp_path):
    page = report.render(CLASS, ORDER, str(tmp_path))
    glance, verdicts = page.index("The class at a glance"), page.index("id='verdicts'")
    assert glance < page.index("Failures by cause") < verdicts
    assert "filterRows('checkpoint1:wrong_topic')" in page
    assert 'data-groups="checkpoint1:wrong_topic"' in page  # ann's row: what the filter matches
    assert "<input id='filter' hidden" in page  # shown by the script only: no dead input without it
    assert (tmp_path / class_view.HISTOGRAM_PNG).read_bytes().startswith(b"\x89PNG")


def test_the_plotting_imports_can_be_done_ahead_on_a_thread(tmp_path):
    """What the grader starts while the runs go on: afterwards pyplot and the Agg backend are
    loaded, and the histogram is drawn."""
    import subprocess
    import sys
    code = ("import sys\n"
            "from course_grader import class_view\n"
            "class_view.plotting_loader().join(120)\n"
            "import matplotlib\n"
            "print(all(m in sys.modules for m in ('matplotlib.pyplot', 'matplotlib.backends.backend_agg')),"
            " matplotlib.get_backend().lower())\n"
            "print(class_view.histogram(%r, []) is not None)\n"
            % str(tmp_path / "scores.png"))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=180)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["True agg", "True"], done.stdout
    assert (tmp_path / "scores.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
