"""Half-sent TCPROS headers against turtlesim (issue 40, course_rospy.inbound_headers): 50 that
close cost nothing 1 s later; beside 500 left open its threads and files stay bounded, its CPU low,
and a new /turtle1/pose subscriber and a /clear call are each served within 1 s; an idle
connection blocks nothing. The checks and their bounds: course_testkit.half_headers."""
import pytest
from std_srvs.srv import Empty, EmptyRequest
from turtlesim.msg import Pose

from course_checks.nodes import find_executable
from course_checks.waiting import wait_for
from course_rospy.inbound_headers import MAX_WAITING_HEADERS
from course_testkit import half_headers, tcpros
from course_testkit.master import PrivateMaster

STARTUP_S = 30.0


@pytest.fixture(scope="module")
def turtlesim():
    with PrivateMaster() as master:
        sim = master.start([find_executable("turtlesim", "turtlesim_node")], "turtlesim",
                           env=dict(master.env, QT_QPA_PLATFORM="offscreen"))
        address = wait_for(lambda: tcpros.address_or_none(master.uri, "/turtlesim", "/turtle1/pose"), STARTUP_S)
        assert address, "turtlesim did not come up:\n%s" % sim.output()[-2000:]
        clear = tcpros.service_address(master.uri, "/clear")
        yield half_headers.NodeUnderTest(
            sim.proc.pid, address,
            subscribe=lambda timeout: tcpros.receive_one(address, "/turtle1/pose", Pose, timeout),
            call=lambda timeout: tcpros.call(clear, "/clear", Empty, EmptyRequest(), timeout))


def test_half_headers_that_close_cost_nothing_a_second_later(turtlesim):
    half_headers.check_half_headers_that_close(turtlesim)


def test_open_half_headers_are_bounded_and_block_nothing(turtlesim):
    half_headers.check_half_headers_left_open(turtlesim, MAX_WAITING_HEADERS)


def test_an_idle_connection_blocks_nothing(turtlesim):
    half_headers.check_idle_connection(turtlesim)
