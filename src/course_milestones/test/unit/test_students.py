"""students: the order executables are tried in and the names a failure message leaves out (no master needed)."""
from course_milestones import students
from course_milestones.discovery import Registration, own_names


def test_servers_first(tmp_path):
    client = tmp_path / "a_client.py"
    client.write_text("rospy.ServiceProxy('/x', T)\n")
    named = tmp_path / "b_server.py"
    named.write_text("print('hi')\n")
    serving = tmp_path / "c.py"
    serving.write_text("rospy.Service('/x', T, handle)\n")
    order = students.servers_first([str(client), str(named), str(serving), str(tmp_path / "missing.py")])
    assert [p.rsplit("/", 1)[-1] for p in order] == ["c.py", "b_server.py", "a_client.py", "missing.py"]


def test_own_names_leave_out_what_every_node_registers():
    reg = Registration("/talker", ("/rosout", "/chatter"), (), ("/talker/get_loggers", "/talker/set_logger_level",
                                                                   "/add"))
    assert own_names(reg.publishes + reg.subscribes + reg.services) == ["/chatter", "/add"]


def test_hinted_executables_first():
    assert students.hinted_first(["/p/b.py", "/p/teleop_key.py", "/p/a.py"], "teleop|key") == \
        ["/p/teleop_key.py", "/p/a.py", "/p/b.py"]


class _Exited:
    """A started executable's process that has exited with `code` after printing `output`."""

    def __init__(self, code, output=""):
        self.proc = type("Proc", (), {"returncode": code})()
        self._output = output

    def running(self):
        return False

    def output(self):
        return self._output


def test_a_node_that_registered_what_was_asked_then_exited_exited_early():
    """A subscriber without rospy.spin() subscribes and falls off the end: it never did what was
    asked (the class view must not say it did)."""
    keyboard = type("Keyboard", (), {"node": _Exited(0)})()
    subscribed = Registration("/pose_subscriber", ("/rosout",), ("/turtle1/pose",), ())
    attempt = students.describe_attempt("pose_subscriber", keyboard, [], [subscribed],
                                        lambda r: "/turtle1/pose" in r.subscribes)
    assert attempt == "pose_subscriber subscribed /turtle1/pose (node /pose_subscriber), then exited with status 0"
    assert attempt.left and attempt.cause == "exited_early"
