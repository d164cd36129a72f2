"""What the course's spawner asks of the container engine (course_hub.containers), against a
stand-in engine client: a user's own internal network, their mounts, the hardened settings of
every container, and a stopped container's reason in words."""
from __future__ import annotations

from course_hub import containers, names


class FakeEngine:
    """Docker's APIClient as far as course_hub.containers uses it."""

    def __init__(self):
        self.made = {}

    def networks(self, names):
        return [{"Name": n} for n in names if n in self.made]

    def create_network(self, name, driver, internal, labels):
        self.made[name] = {"driver": driver, "internal": internal}

    def inspect_network(self, name):
        return {"IPAM": {"Config": [{"Subnet": "10.89.7.0/24", "Gateway": "10.89.7.1"}]}}

    def remove_network(self, name):
        del self.made[name]


def test_each_user_gets_an_internal_network_named_by_one_function_made_once_removed_at_the_stop(tmp_path):
    place = names.places(str(tmp_path), "jean_luc")
    engine = FakeEngine()
    assert containers.ensure_network(engine, place) == "10.89.7.1"  # where the container reaches the hub
    assert engine.made == {"course-hub-net-jean-luc": {"driver": "bridge", "internal": True}}
    assert containers.ensure_network(engine, place) == "10.89.7.1"  # again: the same network, nothing made twice
    containers.remove_network(engine, place)
    assert engine.made == {}
    containers.remove_network(engine, place)  # gone already: nothing to say


def test_a_users_src_is_theirs_in_the_container_and_their_grades_read_only(tmp_path):
    place = names.places(str(tmp_path), "jean_luc")
    assert containers.mounts(place) == {
        "volumes": {str(tmp_path / "users" / "jean-luc" / "src"): {"bind": "/home/student/catkin_ws/src", "mode": "rw,U"}},
        "read_only_volumes": {str(tmp_path / "users" / "jean-luc" / "grades"): "/home/student/grades"}}


def test_every_container_is_hardened_and_bounded():
    host = containers.host_config(99, "64M")
    assert host["pids_limit"] == 99
    assert host["auto_remove"] is False  # the spawner asks a stopped container why
    assert host["security_opt"] == ["no-new-privileges"] and host["cap_drop"] == ["ALL"]
    assert host["read_only"] is True and set(host["tmpfs"]) == {"/home/student", "/tmp"}
    assert all(options.startswith("size=64M,") and "nosuid,nodev" in options for options in host["tmpfs"].values())


def test_a_stopped_server_is_explained_in_words():
    oom = containers.exit_reason({"ExitCode": 137, "OOMKilled": True}, "24M")
    assert "ran out of memory" in oom and "24M" in oom and "files are safe" in oom
    assert "limit is 8M" in containers.exit_reason({"ExitCode": 137, "OOMKilled": False}, "8388608")
    assert "exit code 2" in containers.exit_reason({"ExitCode": 2, "OOMKilled": False}, "2G")
    assert "could not start: no such file" in containers.exit_reason({"ExitCode": 127, "Error": "no such file"}, "2G")
