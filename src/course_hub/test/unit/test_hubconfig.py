"""The hub's configuration as data: what deploy/jupyterhub's file gives JupyterHub, the spawner's
hooks against a stand-in engine client, the pins of the hub and the image agreeing."""
from __future__ import annotations

import asyncio
import os
import re
import types

from course_hub import hubconfig, passwords

CHECKOUT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))


class Section:
    """A section of JupyterHub's config object: any attribute may be set."""


class Config:
    def __getattr__(self, name):
        section = Section()
        setattr(self, name, section)
        return section


def applied(tmp_path):
    roster = tmp_path / "class.csv"
    roster.write_text("username,role\nalice,student\nbob,student\ntom,ta\n")
    settings = hubconfig.HubSettings(class_list=str(roster), data_dir=str(tmp_path / "data"), image="img:1",
                                     mem_limit="1G", cpu_limit=0.5, idle_timeout_s=600, password_rounds=4)
    c = Config()
    users = hubconfig.apply(c, settings)
    return c, users, settings


def test_accounts_come_from_the_class_list_and_tas_are_admins(tmp_path):
    c, users, _ = applied(tmp_path)
    assert c.Authenticator.allowed_users == {"alice", "bob", "tom"}
    assert c.Authenticator.admin_users == {"tom"}
    assert c.JupyterHub.authenticator_class == "firstuseauthenticator.FirstUseAuthenticator"
    assert c.FirstUseAuthenticator.create_users is False
    assert c.FirstUseAuthenticator.dbm_path.startswith(str(tmp_path / "data"))
    # nobody can claim a listed name by logging in first: each has an initial password already
    assert set(passwords.handed_out(str(tmp_path / "data"))) == {"alice", "bob", "tom"}


def test_each_student_a_container_with_limits_their_src_kept_and_grades_read_only(tmp_path):
    c, _, _ = applied(tmp_path)
    spawner = c.DockerSpawner
    assert c.JupyterHub.spawner_class == "course_spawner.CourseSpawner"
    assert spawner.extra_host_config["auto_remove"] is False  # the spawner asks a stopped container why
    assert (spawner.image, spawner.pull_policy, spawner.remove) == ("img:1", "never", True)
    assert (spawner.mem_limit, spawner.cpu_limit) == ("1G", 0.5)
    assert spawner.extra_host_config["pids_limit"] > 0
    data = str(tmp_path / "data")
    assert spawner.volumes == {data + "/users/{username}/src": "/home/student/catkin_ws/src"}
    assert spawner.read_only_volumes == {data + "/users/{username}/grades": "/home/student/grades"}
    assert spawner.cmd[-1].endswith("exec rosrun course_workbench workbench")


def test_idle_servers_are_culled_by_a_service_with_only_the_scopes_it_needs(tmp_path):
    c, _, _ = applied(tmp_path)
    (service,) = c.JupyterHub.services
    assert "--timeout=600" in service["command"] and "jupyterhub_idle_culler" in service["command"]
    (role,) = c.JupyterHub.load_roles
    assert role["services"] == [service["name"]] and "delete:servers" in role["scopes"]
    assert "admin:users" not in role["scopes"]


class FakeEngine:
    """Docker's APIClient as far as the hooks use it."""

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


def test_before_a_spawn_the_user_gets_folders_and_an_internal_network_the_hub_is_reached_through(tmp_path, monkeypatch):
    monkeypatch.setattr(os, "chown", lambda *args: None)
    settings = hubconfig.HubSettings(class_list="", data_dir=str(tmp_path))
    pre_spawn, post_stop = hubconfig.make_hooks(settings)
    engine = FakeEngine()
    spawner = types.SimpleNamespace(user=types.SimpleNamespace(name="alice"), client=engine,
                                    hub=types.SimpleNamespace(api_url="http://127.0.0.1:8123/hub/api"))
    asyncio.run(pre_spawn(spawner))
    assert spawner.network_name == "course-hub-net-alice"
    assert engine.made == {"course-hub-net-alice": {"driver": "bridge", "internal": True}}
    assert spawner.hub_connect_url == "http://10.89.7.1:8123"
    assert os.path.isdir(tmp_path / "users" / "alice" / "src")
    assert os.stat(tmp_path / "users" / "alice" / "grades").st_mode & 0o777 == 0o755
    asyncio.run(pre_spawn(spawner))  # again: the same network, nothing made twice
    asyncio.run(post_stop(spawner))
    assert engine.made == {}


def test_the_image_carries_jupyterhub_at_the_hubs_version():
    def pin(path):
        text = open(os.path.join(CHECKOUT, path)).read()
        return re.search(r"^jupyterhub==(\S+)", text, re.M).group(1)
    assert pin("requirements-jupyter.txt") == pin("requirements-hub.txt")


def test_a_stopped_server_is_explained_in_words():
    oom = hubconfig.exit_reason({"ExitCode": 137, "OOMKilled": True}, "24M")
    assert "ran out of memory" in oom and "24M" in oom and "files are safe" in oom
    assert "limit is 8M" in hubconfig.exit_reason({"ExitCode": 137, "OOMKilled": False}, "8388608")
    assert "exit code 2" in hubconfig.exit_reason({"ExitCode": 2, "OOMKilled": False}, "2G")
    assert "could not start: no such file" in hubconfig.exit_reason({"ExitCode": 127, "Error": "no such file"}, "2G")
