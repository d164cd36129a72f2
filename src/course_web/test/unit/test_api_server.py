"""The server's /api/... handler without ROS: a fake master, a broken one, none at all, and the
token. Every failure is a JSON {"error": ...} with a 4xx/5xx status; the server keeps answering."""
from __future__ import annotations

import asyncio
import json
import socket
import urllib.parse

import tornado.httpclient
import tornado.httpserver
from hypothesis import given, settings, strategies as st

from course_web import introspect
from course_web.protocol import Bridge
from course_web.server import Settings, application

TYPES = {"/turtle1/pose": "turtlesim/Pose"}


class FakeMaster:
    def system_state(self):
        return [[["/turtle1/pose", ["/turtlesim"]]], [], []]

    def topic_types(self):
        return dict(TYPES)

    def node_answers(self, name):
        return True


class DeadMaster:
    def system_state(self):
        raise introspect.ApiError("the ROS master at http://localhost:11311 does not answer: refused", 503)

    topic_types = system_state


class BuggyMaster:
    def system_state(self):
        raise KeyError("a bug")

    topic_types = system_state


def ask(master, paths, token=None):
    """(status, answer) for each path, from a server on a free port with `master`."""
    async def scenario():
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            port = probe.getsockname()[1]
        server = tornado.httpserver.HTTPServer(application(Settings(Bridge(), "/nonexistent", token, master=master)))
        server.listen(port, "127.0.0.1")
        client = tornado.httpclient.AsyncHTTPClient()
        answers = []
        try:
            for path in paths:
                reply = await client.fetch("http://127.0.0.1:%d%s" % (port, path), raise_error=False)
                body = reply.body.decode()
                answers.append((reply.code, json.loads(body) if body.startswith("{") else body))
        finally:
            server.stop()
        return answers
    return asyncio.run(scenario())


def test_answers_from_the_master():
    [(status, topics), (graph_status, graph), (plot_status, plot)] = ask(
        FakeMaster(), ["/api/topics", "/api/graph", "/api/plot?path=/turtle1/pose/x"])
    assert (status, topics) == (200, {"topics": [{"name": "/turtle1/pose", "type": "turtlesim/Pose"}]})
    assert graph_status == 200 and graph["nodes"] == ["/turtlesim"]
    assert plot_status == 200 and plot["fields"][0]["label"] == "/turtle1/pose/x"
    # the header's words: 200 with the state, the master down included
    [(status, health)] = ask(FakeMaster(), ["/api/health?topic=/turtle1/pose"])
    assert status == 200 and health["state"] == "ok" and health["publishers"] == ["/turtlesim"]
    [(status, health)] = ask(DeadMaster(), ["/api/health"])
    assert status == 200 and health["state"] == "no-master" and "does not answer" in health["says"]


def test_failures_are_json_errors_and_the_server_keeps_answering():
    assert ask(DeadMaster(), ["/api/topics"]) == [
        (503, {"error": "the ROS master at http://localhost:11311 does not answer: refused"})]
    [(status, answer)] = ask(BuggyMaster(), ["/api/graph"])
    assert status == 500 and "graph failed inside the server" in answer["error"]
    assert ask(None, ["/api/topics"]) == [(503, {"error": "this server has no ROS master to ask"})]
    statuses = [status for status, _ in ask(FakeMaster(), ["/api/plot?path=%00%ff", "/api/nothing", "/api/topics"])]
    assert statuses == [400, 404, 200]


def test_the_api_is_behind_the_token():
    answers = ask(FakeMaster(), ["/api/topics", "/api/topics?token=wrong", "/api/topics?token=sesame"], token="sesame")
    assert [status for status, _ in answers] == [403, 403, 200]


@settings(max_examples=15, deadline=None)
@given(st.lists(st.binary(max_size=40), min_size=1, max_size=40))
def test_any_bytes_in_a_plot_request_get_an_answer_never_a_crash(values):
    paths = ["/api/plot?path=" + urllib.parse.quote_from_bytes(value) for value in values] + ["/api/topics"]
    answers = ask(FakeMaster(), paths)
    for (status, answer), value in zip(answers, values):
        assert status in (200, 400), (value, status, answer)
        assert ("fields" in answer) if status == 200 else answer["error"]
    assert answers[-1][0] == 200  # still answering
