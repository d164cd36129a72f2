"""The lab page (course_web's lab_view) behind JupyterLab's /roslab/, through jupyter-server-proxy:
behind Jupyter's login, its rosbridge websocket included; on a master and turtlesim of its own
until the student starts a master, then on the student's.

Each test has a workbench of its own (a fresh home, a student master URI on a free port)."""
from __future__ import annotations

import re
import urllib.error
import urllib.request
from typing import Tuple

import pytest

from course_testkit.jupyter import refused_websocket
from course_testkit.rosbridge import drive_turtle
from course_checks.waiting import wait_for
from course_testkit.workbench import Workbench

PAGE_TITLE = "<title>The lab in a browser</title>"


@pytest.fixture
def bench():
    with Workbench() as workbench:
        yield workbench


def open_page(bench: Workbench) -> Tuple[int, str]:
    status, data, _ = bench.request("GET", "/roslab/")
    return status, data.decode(errors="replace")


def test_the_lab_page_is_behind_jupyters_login_and_drives_its_own_turtle(bench):
    status, page = open_page(bench)
    assert status == 200 and PAGE_TITLE in page
    # without Jupyter's token: a redirect to its login page, never the page
    status, data, headers = bench.request("GET", "/roslab/", token=None, follow=False)
    assert status in (302, 403) and PAGE_TITLE not in data.decode(errors="replace")
    if status == 302:
        assert "/login" in headers.get("Location", "")
    status, _, _ = bench.request("GET", "/roslab/", token="not-the-token", follow=False)
    assert status in (302, 403)
    ws = "ws://127.0.0.1:%d/roslab/websocket" % bench.port
    assert refused_websocket(ws) == 403
    assert refused_websocket(ws + "?token=not-the-token") == 403
    # lab_view's own port (loopback) wants the token too: no way around Jupyter's login
    port = bench.lab_view_port()
    assert port is not None
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen("http://127.0.0.1:%d/" % port, timeout=10)
    assert refused.value.code == 403
    # no master of the student's yet: the page's own master and turtlesim, and the turtle moves
    assert bench.processes("turtlesim_node")
    before, after = drive_turtle(ws + "?token=" + bench.token)
    assert after - before > 1.0, (before, after)


def test_the_lab_page_follows_the_students_master_once_they_start_one_and_when_it_restarts(bench):
    status, _ = open_page(bench)  # the page first, on its own master
    assert status == 200
    own_masters = bench.processes("rosmaster")
    assert own_masters, "no master of the page's own"
    student_port = bench.master_uri.rsplit(":", 1)[1]
    with bench.terminal() as term:
        code, said = term.run("roscore -p %s > ~/roscore.log 2>&1 & "
                              "rosrun turtlesim turtlesim_node > ~/turtlesim.log 2>&1 &" % student_port)
        assert code == 0, said
        # the page's lab_view registers with the student's master
        followed = wait_for(lambda: "/workbench_lab_view" in term.run("rosnode list 2>&1")[1], 60, 0.5)
        assert followed, term.run("rosnode list 2>&1; cat ~/roscore.log")[1]
        # ... and the page's own master and turtlesim are gone
        assert wait_for(lambda: [c for c in bench.processes("rosmaster") if student_port not in c] == [], 20), \
            bench.processes("rosmaster")
        assert wait_for(lambda: open_page(bench)[0] == 200, 30)
        before, after = drive_turtle("ws://127.0.0.1:%d/roslab/websocket?token=%s" % (bench.port, bench.token))
        assert after - before > 1.0, (before, after)
        code, said = term.run("rostopic echo -n1 /turtle1/pose/x")  # the student's own turtle moved
        assert code == 0, said
        x = float(re.search(r"-?\d+\.\d+", said).group(0))
        assert abs(x - after) < 0.5, (said, after)
        # the student restarts their master: lab_view registers with the new one
        term.run("kill %2; kill -INT %1; wait")
        assert term.run("rostopic list")[0] != 0
        code, said = term.run("roscore -p %s > ~/roscore2.log 2>&1 &" % student_port)
        assert code == 0, said
        again = wait_for(lambda: "/workbench_lab_view" in term.run("rosnode list 2>&1")[1], 60, 0.5)
        assert again, term.run("rosnode list 2>&1; cat ~/roscore2.log")[1]
        term.run("kill -INT %1; wait")
