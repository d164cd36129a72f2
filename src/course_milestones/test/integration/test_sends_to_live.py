"""discovery.sends_to against real nodes: a rospy publisher (rostopic pub) and a roscpp one
(topic_tools relay) list a subscriber by its caller id once it is connected, and nobody else."""
import pytest

from course_milestones import discovery
from course_testkit import tcpros
from course_testkit.master import PrivateMaster
from course_checks.waiting import wait_for

STARTUP_S = 30.0


@pytest.fixture(scope="module")
def master():
    with PrivateMaster() as m:
        yield m


def node_uri(master, name):
    def found():
        try:
            return tcpros.node_api(master.uri, name)
        except (OSError, LookupError):
            return None
    uri = wait_for(found, STARTUP_S)
    assert uri, "%s did not register" % name
    return uri


def test_a_rospy_publisher_lists_its_subscriber(master):
    master.start(["rostopic", "pub", "-r", "5", "/said", "std_msgs/String", "data: x", "__name:=talker"], "talker")
    uri = node_uri(master, "/talker")
    assert discovery.sends_to(uri, "/said", "/listener") is False
    listener = master.start(["rostopic", "echo", "/said", "__name:=listener"], "listener")
    assert wait_for(lambda: discovery.sends_to(uri, "/said", "/listener"), STARTUP_S), listener.output()[-500:]
    assert discovery.sends_to(uri, "/said", "/somebody_else") is False
    assert discovery.sends_to(uri, "/other_topic", "/listener") is False


def test_a_roscpp_publisher_lists_its_subscriber(master):
    # topic_tools' relay (C++) advertises its output once its input has carried a message
    master.start(["rostopic", "pub", "-r", "5", "/relay_in", "std_msgs/String", "data: y",
                  "__name:=relay_source"], "relay_source")
    master.start(["rosrun", "topic_tools", "relay", "/relay_in", "/relay_out", "__name:=relay"], "relay")
    uri = node_uri(master, "/relay")
    listener = master.start(["rostopic", "echo", "/relay_out", "__name:=relay_listener"], "relay_listener")
    assert wait_for(lambda: discovery.sends_to(uri, "/relay_out", "/relay_listener"), STARTUP_S), \
        listener.output()[-500:]
    assert discovery.sends_to(uri, "/relay_out", "/listener") is False


def test_a_node_says_the_type_it_publishes_though_the_master_keeps_a_subscribers(master):
    # a Twist subscriber registers first: the master's type for the topic is then Twist
    master.start(["/usr/bin/python3", "-c", "import rospy; from geometry_msgs.msg import Twist; "
                  "rospy.init_node('typed_listener'); rospy.Subscriber('/typed_cmd', Twist, print); rospy.spin()"],
                 "typed_listener")
    node_uri(master, "/typed_listener")
    master.start(["rostopic", "pub", "-r", "5", "/typed_cmd", "std_msgs/Empty", "__name:=typed_talker"], "typed_talker")
    uri = node_uri(master, "/typed_talker")
    assert wait_for(lambda: discovery.published_type(uri, "/typed_cmd"), STARTUP_S) == "std_msgs/Empty"
    assert discovery.published_type(uri, "/nothing_here") is None
    assert discovery.published_type("http://127.0.0.1:9/", "/typed_cmd") is None  # no node answers there
