"""course_rospy.inbound_headers in turtlesim: one idle TCP connection to a node's TCPROS port blocks
(control: `rostopic pub`, a plain rospy node), but not turtlesim's, which installs it: with the
idle connection held, a new subscriber still gets /turtle1/pose and /spawn still answers."""
import socket

import pytest
from std_msgs.msg import String
from turtlesim.msg import Pose
from turtlesim.srv import Spawn, SpawnRequest

from course_testkit import tcpros
from course_testkit.master import PrivateMaster
from course_checks.nodes import find_executable
from course_checks.waiting import wait_for

STARTUP_S = 30.0
# Far more than a free node needs (milliseconds), far less than rospy's blocked accept waits
# (until the idle connection closes).
DEADLINE_S = 3.0


@pytest.fixture(scope="module")
def master():
    with PrivateMaster() as m:
        yield m


def publisher_address(master, node, topic, process):
    def found():
        try:
            return tcpros.topic_address(master.uri, node, topic)
        except (OSError, LookupError):
            return None
    address = wait_for(found, STARTUP_S)
    assert address, "%s did not come up:\n%s" % (node, process.output()[-2000:])
    return address


def test_an_idle_connection_blocks_a_plain_rospy_node(master):
    """The control: without inbound_headers, the next subscriber waits for the idle one."""
    pub = master.start(["rostopic", "pub", "-r", "10", "/control", "std_msgs/String", "data: x",
                        "__name:=control_pub"], "control_pub")
    address = publisher_address(master, "/control_pub", "/control", pub)
    assert tcpros.receive_one(address, "/control", String, DEADLINE_S).data == "x"  # free: it answers
    with socket.create_connection(address, timeout=DEADLINE_S):
        with pytest.raises(socket.timeout):
            tcpros.receive_one(address, "/control", String, DEADLINE_S)
    master.stop_node(pub)


def test_turtlesim_serves_new_clients_beside_an_idle_connection(master):
    sim = master.start([find_executable("turtlesim", "turtlesim_node")], "turtlesim",
                       env=dict(master.env, QT_QPA_PLATFORM="offscreen"))
    address = publisher_address(master, "/turtlesim", "/turtle1/pose", sim)
    with socket.create_connection(address, timeout=DEADLINE_S):  # connected, sends nothing
        pose = tcpros.receive_one(address, "/turtle1/pose", Pose, DEADLINE_S)
        assert pose.x == pytest.approx(5.544, abs=0.01)
        spawn = tcpros.service_address(master.uri, "/spawn")
        answer = tcpros.call(spawn, "/spawn", Spawn, SpawnRequest(2.0, 3.0, 0.0, "beside_idle"), DEADLINE_S)
        assert answer.name == "beside_idle"
    master.stop_node(sim)
