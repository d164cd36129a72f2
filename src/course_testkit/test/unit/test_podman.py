"""course_testkit.podman and course_testkit.course_image without podman: the containers.conf it
needs, Gradescope's results.json format and the expected verdicts it checks, and the zip unpacked
with its modes as unzip does. (`make docker-check` and `make autograder-check`, tests/e2e/test_image.py,
run the real thing, as root, in minutes.)"""
import importlib.util
import zipfile

from course_testkit import course_image, podman


def test_containers_conf_gets_no_default_ulimits_once():
    fix = podman.without_default_ulimits
    assert fix("") == "[containers]\ndefault_ulimits = []\n"
    assert fix("[engine]\nx = 1") == "[engine]\nx = 1\n[containers]\ndefault_ulimits = []\n"
    assert fix("[containers]\nlog_size_max = -1\n\n[engine]\n") == \
        "[containers]\ndefault_ulimits = []\nlog_size_max = -1\n\n[engine]\n"
    done = "[containers]\ndefault_ulimits = [ ]\n"
    assert fix(done) == done and fix(fix("")) == fix("")


def results(status="passed", output="isolation: user only: ..."):
    return {"score": 10.0, "output": output, "tests": [
        {"name": "chatter: Example publisher and subscriber", "score": 10.0, "max_score": 10.0, "status": status,
         "output": "passed", "visibility": "visible"}]}


def test_results_json_is_checked_for_format_verdict_and_isolation():
    problems = course_image.results_problems
    assert problems(results(), True) == []
    assert problems(results("failed"), False) == []
    assert any("expected failed" in p for p in problems(results(), False))
    assert any("isolation" in p for p in problems(results(output="graded"), True))
    broken = results()
    broken["tests"][0]["score"] = "10"
    del broken["score"]
    found = problems(broken, True)
    assert any("score is not a number" in p for p in found) and any("score missing" in p for p in found)
    assert "no tests" in problems({"score": 0, "output": "isolation: none", "tests": []}, True)


def test_the_zip_is_unpacked_with_its_modes(tmp_path):
    archive = tmp_path / "autograder.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        info = zipfile.ZipInfo("setup.sh")
        info.external_attr = 0o100755 << 16
        zf.writestr(info, "#!/bin/bash\n")
        zf.writestr("src/readme.txt", "x")
    course_image.unpack_zip(archive, tmp_path / "source")
    assert (tmp_path / "source" / "setup.sh").stat().st_mode & 0o777 == 0o755
    assert (tmp_path / "source" / "src" / "readme.txt").read_text() == "x"


def test_the_image_tags_come_from_the_environment(monkeypatch):
    monkeypatch.setenv("COURSE_IMAGE", "localhost/ros-course-mine")
    monkeypatch.setenv("INSTRUCTOR_IMAGE", "localhost/ros-course-mine-instructor")
    spec = importlib.util.find_spec("course_testkit.podman")
    again = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(again)
    assert (again.COURSE_IMAGE, again.INSTRUCTOR_IMAGE) == ("localhost/ros-course-mine",
                                                            "localhost/ros-course-mine-instructor")
    assert podman.COURSE_IMAGE == "localhost/ros-course"  # the default, without them


def test_each_check_prints_one_line_and_any_failure_fails_them_all(capsys):
    check = course_image.Checks("jupyter")
    assert check(True, "a") and check.ok
    assert not check(False, "b") and not check.ok
    assert check(True, "c") and not check.ok
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[:2] for line in lines] == [["jupyter:", "ok"], ["jupyter:", "FAILED"], ["jupyter:", "ok"]]


def test_container_names_are_this_runs_own():
    import os
    name = podman.container_name("jupyter-check")
    assert name == "ros-course-jupyter-check-%d" % os.getpid()
