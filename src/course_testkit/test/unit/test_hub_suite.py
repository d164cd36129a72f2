"""course_testkit.hub_suite without a hub: HUB_CHECK_ARGS' words, and the report's lines and count
(`make hub-check`, tests/e2e/test_hub.py, runs the real thing, as root, in minutes)."""
from course_testkit import course_image, hub_suite


def test_the_suites_read_their_make_variables_words():
    hub = hub_suite.options("--image localhost/ros-course-hub --no-build")
    assert (hub.image, hub.no_build, hub.keep, hub.extra_config) == ("localhost/ros-course-hub", True, False, "")
    assert hub_suite.options("").image == "localhost/ros-course"
    image = course_image.options("--rebuild --grade-class '/srv/a class'")
    assert (image.rebuild, image.skip_test, image.grade_class) == (True, False, "/srv/a class")


def test_the_report_prints_one_line_per_check_and_names_the_failures(capsys):
    report = hub_suite.Report()
    assert report.check("logins", True)
    assert not report.attempt("spawns", lambda: 1 // 0)
    assert report.attempt("origins", lambda: "alice's own")
    assert (report.passed, report.total, report.failed) == (2, 3, ["spawns"])
    assert capsys.readouterr().out.splitlines() == [
        "ok   logins", "FAIL spawns: ZeroDivisionError: integer division or modulo by zero", "ok   origins: alice's own"]
