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
