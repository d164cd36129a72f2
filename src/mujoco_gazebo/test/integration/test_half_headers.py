"""Half-sent TCPROS headers against the simulator, gzserver (issue 40, course_rospy.inbound_headers):
50 that close cost nothing 1 s later; beside 500 left open its threads and files stay bounded, its
CPU low, and a new /clock subscriber and a /gazebo/get_world_properties call are each served within
1 s; an idle connection blocks nothing. The checks and their bounds: course_testkit.half_headers."""
import pytest
from gazebo_msgs.srv import GetWorldProperties, GetWorldPropertiesRequest
from rosgraph_msgs.msg import Clock

from course_checks.nodes import find_executable
from course_checks.waiting import wait_for
from course_rospy.inbound_headers import MAX_WAITING_HEADERS
from course_testkit import half_headers, tcpros
from course_testkit.master import PrivateMaster

STARTUP_S = 60.0
SERVICE = "/gazebo/get_world_properties"


@pytest.fixture(scope="module")
def gazebo():
    with PrivateMaster() as master:
        server = master.start([find_executable("mujoco_gazebo", "gzserver")], "gazebo")
        address = wait_for(lambda: tcpros.address_or_none(master.uri, "/gazebo", "/clock"), STARTUP_S)
        properties = wait_for(lambda: tcpros.service_address_or_none(master.uri, SERVICE), STARTUP_S)
        assert address and properties, "gzserver did not come up:\n%s" % server.output()[-2000:]
        yield half_headers.NodeUnderTest(
            server.proc.pid, address,
            subscribe=lambda timeout: tcpros.receive_one(address, "/clock", Clock, timeout),
            call=lambda timeout: tcpros.call(properties, SERVICE, GetWorldProperties, GetWorldPropertiesRequest(),
                                             timeout))


def test_half_headers_that_close_cost_nothing_a_second_later(gazebo):
    half_headers.check_half_headers_that_close(gazebo)


def test_open_half_headers_are_bounded_and_block_nothing(gazebo):
    half_headers.check_half_headers_left_open(gazebo, MAX_WAITING_HEADERS)


def test_an_idle_connection_blocks_nothing(gazebo):
    half_headers.check_idle_connection(gazebo)
