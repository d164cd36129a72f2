"""The master's log as rostest's in-process master writes it: registrations in order, and all a
node ever registered, left or not."""
import os

from course_milestones.master_log import History, ever_registered, locate, parse

LOG = """[rosmaster.master][INFO] 2026-11-25 15:30:58,595: +PUB [/turtle1/pose] /turtlesim http://localhost:38217/
[rosmaster.master][INFO] 2026-11-25 15:30:58,599: +SUB [/turtle1/cmd_vel] /turtlesim http://localhost:38217/
[rosmaster.master][INFO] 2026-11-25 15:30:58,956: +PUB [/rosout] /pose_subscriber http://localhost:42129/
[rospy.client][INFO] 2026-11-25 15:30:58,957: init_node, name[/x], pid[1]
[rosmaster.master][INFO] 2026-11-25 15:30:58,962: +SUB [/turtle1/pose] /pose_subscriber http://localhost:42129/
[rosmaster.master][INFO] 2026-11-25 15:30:59,098: -SUB [/turtle1/pose] /pose_subscriber http://localhost:42129/
[rosmaster.master][INFO] 2026-11-25 15:30:59,100: +SERVICE [/pose_subscriber/get_loggers] /pose_subscriber rosrpc://localhost:4/
"""


def test_events_in_order_and_what_a_node_ever_registered():
    events = parse(LOG)
    assert [(e.added, e.kind, e.name, e.node) for e in events][3:5] == [
        (True, "subscribes", "/turtle1/pose", "/pose_subscriber"), (False, "subscribes", "/turtle1/pose", "/pose_subscriber")]
    ever = ever_registered(events, ["/pose_subscriber"])
    assert list(ever) == ["/pose_subscriber"]
    assert ever["/pose_subscriber"].subscribes == ("/turtle1/pose",)
    assert ever["/pose_subscriber"].services == ("/pose_subscriber/get_loggers",)
    assert set(ever_registered(events)) == {"/turtlesim", "/pose_subscriber"}


def test_history_reads_from_its_mark_and_the_log_is_rostests(tmp_path):
    path = tmp_path / ("rostest-host-%d.log" % os.getpid())
    path.write_text(LOG.splitlines(True)[0])
    assert locate(str(tmp_path), os.getpid()) == str(path)
    assert locate(str(tmp_path), os.getpid() + 1) is None
    history = History(str(path))
    history.mark()
    with open(path, "a") as f:
        f.write("".join(LOG.splitlines(True)[4:6]))
    assert [e.added for e in history.since()] == [True, False]
    assert History(str(tmp_path / "gone")).since() == [] and History("").since() == []
