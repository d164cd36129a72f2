"""The hub's configuration as data: what deploy/jupyterhub's file gives JupyterHub, the spawner's
hooks against a stand-in engine client, the pins of the hub and the image agreeing."""
from __future__ import annotations

import asyncio
import os
import re
import stat
import types

from course_hub import disks, hubconfig, names, passwords

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
    assert c.JupyterHub.authenticator_class == "course_hub.auth.CourseAuthenticator"
    assert c.FirstUseAuthenticator.create_users is False
    assert c.Authenticator.allow_existing_users is False  # taken off the list: no login any more
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
    host = spawner.extra_host_config
    assert host["pids_limit"] > 0
    assert host["security_opt"] == ["no-new-privileges"] and host["cap_drop"] == ["ALL"]
    assert host["read_only"] is True and set(host["tmpfs"]) == {"/home/student", "/tmp"}
    assert all("size=" in options for options in host["tmpfs"].values())
    assert spawner.cmd[-1].endswith("exec rosrun course_workbench workbench")
    assert spawner.extra_create_kwargs == {"host_config": {"UsernsMode": "auto"}}  # a user namespace each
    # no template of DockerSpawner's own: the hooks set the mounts from course_hub.names
    assert not hasattr(spawner, "volumes") and not hasattr(spawner, "name_template")


def test_the_data_folder_lets_nobody_but_root_into_disks_snapshots_and_users(tmp_path):
    applied(tmp_path)
    data = tmp_path / "data"
    assert {p: stat.S_IMODE(os.stat(data / p).st_mode) for p in ("users", "disks", "snapshots", "grades", ".")} \
        == {"users": 0o700, "disks": 0o700, "snapshots": 0o700, "grades": 0o711, ".": 0o711}


def test_idle_servers_are_culled_by_a_service_with_only_the_scopes_it_needs(tmp_path):
    c, _, _ = applied(tmp_path)
    (service,) = c.JupyterHub.services
    assert "--timeout=600" in service["command"] and "jupyterhub_idle_culler" in service["command"]
    assert "--max-age=%d" % hubconfig.HubSettings("").max_age_s in service["command"]  # activity cannot keep it
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


def test_before_a_spawn_the_user_gets_a_disk_and_an_internal_network_all_named_by_one_function(
        tmp_path, monkeypatch):
    ensured = []
    monkeypatch.setattr(disks, "ensure", lambda place, size, uid: ensured.append((place, size, uid)))
    settings = hubconfig.HubSettings(class_list="", data_dir=str(tmp_path), disk_limit="64M")
    pre_spawn, post_stop = hubconfig.make_hooks(settings)
    engine = FakeEngine()
    spawner = types.SimpleNamespace(user=types.SimpleNamespace(name="jean_luc"), client=engine,
                                    hub=types.SimpleNamespace(api_url="http://127.0.0.1:8123/hub/api"))
    asyncio.run(pre_spawn(spawner))
    place = names.places(str(tmp_path), "jean_luc")
    assert ensured == [(place, 64 * 2 ** 20, 1000)]
    assert spawner.network_name == place.network == "course-hub-net-jean-luc"
    assert engine.made == {place.network: {"driver": "bridge", "internal": True}}
    assert spawner.hub_connect_url == "http://10.89.7.1:8123"
    assert spawner.volumes == {place.src: {"bind": "/home/student/catkin_ws/src", "mode": "rw,U"}}
    assert spawner.read_only_volumes == {place.grades: "/home/student/grades"}
    assert place.src == str(tmp_path / "users" / "jean-luc" / "src")
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
