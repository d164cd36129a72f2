"""MasterRelay forwards calls (answers and faults) to the master behind it, and holds the first
call its filter picks until released, without holding the others."""
import threading
import xmlrpc.client
from xmlrpc.server import SimpleXMLRPCServer

import pytest

from course_testkit.master_relay import MasterRelay


class FakeMaster:
    """Two master calls: an answer, and a fault for a name it does not know."""

    def getPid(self, caller_id):
        return [1, "", 4242]

    def lookupService(self, caller_id, service):
        if service != "/known":
            raise ValueError("unknown service [%s]" % service)
        return [1, "", "rosrpc://127.0.0.1:1/"]


@pytest.fixture
def master():
    server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
    server.register_instance(FakeMaster())
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield "http://127.0.0.1:%d/" % server.server_address[1]
    server.shutdown()
    server.server_close()


def test_calls_and_faults_pass_through(master):
    with MasterRelay(master, lambda method, params: False) as relay:
        proxy = xmlrpc.client.ServerProxy(relay.uri)
        assert proxy.getPid("/t") == [1, "", 4242]
        with pytest.raises(xmlrpc.client.Fault, match="unknown service"):
            proxy.lookupService("/t", "/other")
        assert not relay.held.is_set()


def test_the_chosen_call_waits_for_release(master):
    def lookup_known(method, params):
        return method == "lookupService" and params[1] == "/known"

    with MasterRelay(master, lookup_known) as relay:
        answers = []
        caller = threading.Thread(
            target=lambda: answers.append(xmlrpc.client.ServerProxy(relay.uri).lookupService("/t", "/known")))
        caller.start()
        assert relay.held.wait(10)
        assert relay.held_call == ("lookupService", ("/t", "/known"))
        assert xmlrpc.client.ServerProxy(relay.uri).getPid("/t")[2] == 4242  # others go on meanwhile
        assert answers == []
        relay.release()
        caller.join(10)
        assert answers == [[1, "", "rosrpc://127.0.0.1:1/"]]
