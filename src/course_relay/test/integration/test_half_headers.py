"""Half-sent TCPROS headers against the relay (issue 40, course_rospy.inbound_headers): 50 that
close cost nothing 1 s later; beside 500 left open its threads and files stay bounded, its CPU
low, and a new subscriber of its output and a call of its ~get_loggers are each served within 1 s;
an idle connection blocks nothing. `rostopic pub` feeds its input. The checks and their bounds:
course_testkit.half_headers."""
import pytest
from roscpp.srv import GetLoggers, GetLoggersRequest
from std_msgs.msg import String

from course_checks.nodes import find_executable
from course_checks.waiting import wait_for
from course_rospy.inbound_headers import MAX_WAITING_HEADERS
from course_testkit import half_headers, tcpros
from course_testkit.master import PrivateMaster

STARTUP_S = 30.0
NODE = "/half_headers_relay"


@pytest.fixture(scope="module")
def relay():
    with PrivateMaster() as master:
        node = master.start([find_executable("course_relay", "relay"), "/words", "__name:=" + NODE[1:]], "relay")
        master.start(["rostopic", "pub", "-r", "50", "/words", "std_msgs/String", "data: w", "__name:=words"], "words")
        address = wait_for(lambda: tcpros.address_or_none(master.uri, NODE, "/words_relay"), STARTUP_S)
        assert address, "the relay did not come up:\n%s" % node.output()[-2000:]
        loggers = tcpros.service_address(master.uri, NODE + "/get_loggers")
        yield half_headers.NodeUnderTest(
            node.proc.pid, address,
            subscribe=lambda timeout: tcpros.receive_one(address, "/words_relay", String, timeout),
            call=lambda timeout: tcpros.call(loggers, NODE + "/get_loggers", GetLoggers, GetLoggersRequest(), timeout))


def test_half_headers_that_close_cost_nothing_a_second_later(relay):
    half_headers.check_half_headers_that_close(relay)


def test_open_half_headers_are_bounded_and_block_nothing(relay):
    half_headers.check_half_headers_left_open(relay, MAX_WAITING_HEADERS)


def test_an_idle_connection_blocks_nothing(relay):
    half_headers.check_idle_connection(relay)
