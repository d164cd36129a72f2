"""The course's JupyterHub plug-ins, CourseSpawner and CourseAuthenticator, made from configuration
as JupyterHub makes them: their traits, the course's config file, and the hub's start, which
gives the initial passwords that loading the configuration does not.

They import JupyterHub, DockerSpawner and FirstUseAuthenticator, which live in the hub's own venv
(.venv-hub) and not in the course's: hub_probe.py makes them there, from this checkout's
course_hub, and answers in JSON. No hub runs and no container engine is called."""
from __future__ import annotations

import json
import os
import re
import stat
import subprocess

import pytest
import yaml

from course_hub import defaults, passwords

UNIT = os.path.dirname(os.path.abspath(__file__))
PACKAGE_SRC = os.path.abspath(os.path.join(UNIT, "..", "..", "src"))
CHECKOUT = os.path.abspath(os.path.join(UNIT, "..", "..", "..", ".."))
HUB_PYTHON = os.path.join(CHECKOUT, ".venv-hub", "bin", "python3")
COURSE_CONFIG = os.path.join(CHECKOUT, "deploy", "jupyterhub", "jupyterhub_config.py")
KUBERNETES_VALUES = os.path.join(CHECKOUT, "deploy", "kubernetes", "values.yaml")
SPAWNER_TRAITS = ["data_dir", "image", "pull_policy", "cmd", "remove", "use_internal_ip", "mem_limit", "cpu_limit",
                  "pids_limit", "disk_limit", "home_limit", "userns", "start_timeout", "http_timeout",
                  "extra_host_config", "extra_create_kwargs", "object_name", "network_name", "volumes",
                  "read_only_volumes"]
AUTH_TRAITS = ["class_list", "data_dir", "allowed_users", "admin_users", "dbm_path", "create_users",
               "allow_existing_users", "failures_per_name"]

pytestmark = pytest.mark.skipif(not os.access(HUB_PYTHON, os.X_OK), reason="the hub's venv (.venv-hub) is not "
                                "there: make hub's set-up makes it (COURSE_HUB=1 bash setup/install.sh)")


class Probe:
    """hub_probe.py --serve, run by the hub's Python on this checkout's course_hub (the ROS
    workspace's Python path left out: the hub's venv has its own), started once for the module:
    JupyterHub's imports take seconds, a request milliseconds."""

    def __init__(self) -> None:
        clean = {k: v for k, v in os.environ.items()
                 if k not in ("PYTHONPATH", "PYTHONHOME") and not k.startswith("HUB_")}
        self.proc = subprocess.Popen([HUB_PYTHON, os.path.join(UNIT, "hub_probe.py"), "--serve"],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
                                     env=dict(clean, PYTHONPATH=PACKAGE_SRC))

    def ask(self, request, env=None):
        self.proc.stdin.write(json.dumps({"request": request, "env": env or {}}) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        assert line, "hub_probe.py ended (exit code %s)" % self.proc.wait(10)
        answer = json.loads(line)
        assert "crash" not in answer, answer["crash"]
        return answer

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(30)


@pytest.fixture(scope="module", autouse=True)
def hub_probe():
    started = Probe()
    PROBES.append(started)
    yield started
    PROBES.remove(started)
    started.close()


PROBES = []  # the module's running probe (hub_probe's fixture), for probe()


def probe(request, env=None):
    """hub_probe.py's answer to `request`, with the HUB_* variables of `env`."""
    return PROBES[-1].ask(request, env)


def made(config=None, config_file=None, user="alice", env=None, authenticator=True):
    """The classes made from `config` and/or `config_file` (the authenticator only when asked:
    it needs a class list): their traits, the JupyterHub section; no warning, no error."""
    answer = probe({"action": "traits", "config": config or {}, "config_file": config_file, "user": user,
                    "spawner_traits": SPAWNER_TRAITS, "authenticator_traits": AUTH_TRAITS if authenticator else []},
                   env)
    assert "error" not in answer, answer["error"]
    assert answer["warnings"] == []  # every option set is one the classes know
    return answer


@pytest.fixture
def class_list(tmp_path):
    roster = tmp_path / "class.csv"
    roster.write_text("username,role\nalice,student\njean_luc,student\ntom,ta\n")
    return str(roster)


def test_the_course_config_is_plain_jupyterhub_config_naming_the_course_classes(tmp_path, class_list):
    data = tmp_path / "data"
    answer = made(config_file=COURSE_CONFIG, user="jean_luc",
                  env={"HUB_DATA": str(data), "HUB_CLASS_LIST": class_list, "HUB_IMAGE": "img:1",
                       "HUB_URL": "http://127.0.0.1:8123", "HUB_API_PORT": "8124"})
    hub, spawner, auth = answer["jupyterhub"], answer["spawner"], answer["authenticator"]
    assert hub["spawner_class"] == "course_hub.spawner.CourseSpawner"
    assert hub["authenticator_class"] == "course_hub.auth.CourseAuthenticator"
    assert (hub["bind_url"], hub["subdomain_host"], hub["hub_ip"], hub["hub_port"]) == (
        "http://127.0.0.1:8123", "http://hub.localhost:8123", "0.0.0.0", 8124)
    assert hub["db_url"] == "sqlite:///%s/jupyterhub.sqlite" % data
    assert (spawner["data_dir"], spawner["image"]) == (str(data), "img:1")  # make's variables
    assert spawner["volumes"] == {str(data / "users" / "jean-luc" / "src"): {"bind": defaults.SRC_IN_CONTAINER,
                                                                               "mode": "rw,U"}}
    assert auth["allowed_users"] == ["alice", "jean_luc", "tom"] and auth["admin_users"] == ["tom"]
    assert auth["dbm_path"] == passwords.dbm_of(str(data))
    # loading the configuration and making the classes sets traits and nothing else: no data
    # folder, no password given (the hub's start does that: test_the_hubs_start_gives_...)
    assert not data.exists()


def test_idle_servers_are_culled_by_a_service_with_only_the_scopes_it_needs(tmp_path, class_list):
    hub = made(config_file=COURSE_CONFIG, env={"HUB_DATA": str(tmp_path), "HUB_CLASS_LIST": class_list})["jupyterhub"]
    (service,) = hub["services"]
    assert "jupyterhub_idle_culler" in service["command"]
    assert "--timeout=3600" in service["command"] and "--max-age=43200" in service["command"]  # activity cannot keep it
    (role,) = hub["load_roles"]
    assert role["services"] == [service["name"]] and "delete:servers" in role["scopes"]
    assert "admin:users" not in role["scopes"]


def test_the_config_files_commented_settings_are_the_traits_defaults(tmp_path, class_list):
    """What the config file shows commented out is what a course gets without it."""
    text = open(COURSE_CONFIG).read()
    shown = re.findall(r"^# (c\.Course(?:Spawner|Authenticator)\.\w+ = .*?)(?:\s+#.*)?$", text, re.M)
    assert len(shown) >= 8, shown
    uncommented = tmp_path / "uncommented.py"
    uncommented.write_text("c = get_config()\nload_subconfig(%r)\n%s\n" % (COURSE_CONFIG, "\n".join(shown)))
    env = {"HUB_DATA": str(tmp_path), "HUB_CLASS_LIST": class_list}
    default = made(config_file=COURSE_CONFIG, env=env)
    explicit = made(config_file=str(uncommented), env=env)
    assert (explicit["spawner"], explicit["authenticator"]) == (default["spawner"], default["authenticator"])


def test_each_student_a_hardened_container_named_as_everything_else_of_theirs(tmp_path):
    spawner = made({"CourseSpawner": {"data_dir": str(tmp_path)}}, user="jean_luc", authenticator=False)["spawner"]
    assert (spawner["image"], spawner["pull_policy"], spawner["remove"]) == (defaults.IMAGE, "never", True)
    assert spawner["cmd"] == list(defaults.SINGLEUSER_COMMAND)
    assert (spawner["mem_limit"], spawner["cpu_limit"]) == (2 * 2 ** 30, defaults.CPU_LIMIT)
    assert spawner["start_timeout"] == spawner["http_timeout"] == defaults.START_TIMEOUT_S
    host = spawner["extra_host_config"]
    assert host["auto_remove"] is False  # the spawner asks a stopped container why
    assert host["security_opt"] == ["no-new-privileges"] and host["cap_drop"] == ["ALL"] and host["read_only"]
    assert host["pids_limit"] == defaults.PIDS_LIMIT
    assert spawner["extra_create_kwargs"] == {"host_config": {"UsernsMode": "auto"}}  # a user namespace each
    assert (spawner["object_name"], spawner["network_name"]) == ("course-hub-jean-luc", "course-hub-net-jean-luc")
    assert spawner["read_only_volumes"] == {str(tmp_path / "users" / "jean-luc" / "grades"): "/home/student/grades"}


def test_a_course_sets_traits_and_extends_the_hardening_without_losing_it(tmp_path):
    config = tmp_path / "course.py"
    config.write_text('c = get_config()\n'
                      'c.CourseSpawner.mem_limit = "1G"\n'
                      'c.CourseSpawner.pids_limit = 99\n'
                      'c.CourseSpawner.home_limit = "64M"\n'
                      'c.CourseSpawner.extra_host_config.update({"shm_size": "64M"})\n')
    spawner = made(config_file=str(config), authenticator=False)["spawner"]
    host = spawner["extra_host_config"]
    assert spawner["mem_limit"] == 2 ** 30 and host["pids_limit"] == 99 and host["shm_size"] == "64M"
    assert host["cap_drop"] == ["ALL"] and host["tmpfs"]["/tmp"].startswith("size=64M,")


def test_a_size_nobody_can_read_is_refused_with_its_trait():
    answer = probe({"action": "traits", "config": {"CourseSpawner": {"disk_limit": "lots"}},
                    "spawner_traits": ["disk_limit"]})
    assert "CourseSpawner.disk_limit" in answer["error"] and "2G, 512M" in answer["error"]


def test_an_option_the_course_classes_do_not_know_is_reported():
    answer = probe({"action": "traits", "config": {"CourseSpawner": {"disk_limt": "2G"}}, "spawner_traits": []})
    assert any("disk_limt" in line for line in answer["warnings"]), answer["warnings"]


def test_the_authenticator_knows_the_class_list_and_keeps_passwords_in_the_data_folder(tmp_path, class_list):
    auth = made({"CourseAuthenticator": {"class_list": class_list, "data_dir": str(tmp_path)}})["authenticator"]
    assert auth["allowed_users"] == ["alice", "jean_luc", "tom"] and auth["admin_users"] == ["tom"]
    assert auth["create_users"] is False and auth["allow_existing_users"] is False  # off the list: no login
    assert auth["dbm_path"] == str(tmp_path / "passwords.dbm") and auth["failures_per_name"] == 5


def test_a_bad_class_list_or_none_stops_with_what_is_wrong(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("username,role\nalice,student\nBob!,student\n")
    answer = probe({"action": "traits", "config": {"CourseAuthenticator": {"class_list": str(bad)}},
                    "authenticator_traits": ["allowed_users"]})
    assert "line 3" in answer["error"], answer["error"]
    answer = probe({"action": "traits", "authenticator_traits": ["allowed_users"]})
    assert "CourseAuthenticator.class_list is not set" in answer["error"]


def test_before_its_container_the_spawner_mounts_the_users_disk_and_makes_their_network(tmp_path):
    answer = probe({"action": "spawn", "user": "jean_luc",
                    "config": {"CourseSpawner": {"data_dir": str(tmp_path / "data"), "disk_limit": "64M"}}})
    assert answer["gateway"] == "10.89.7.1"  # the container reaches the hub's API there
    assert answer["disks"] == [[str(tmp_path / "data" / "users" / "jean-luc"), 64 * 2 ** 20, 1000]]
    assert answer["networks"] == {"course-hub-net-jean-luc": {"driver": "bridge", "internal": True}}
    assert stat.S_IMODE(os.stat(tmp_path / "data" / "users").st_mode) == 0o700  # laid out, whatever it was


def test_the_hubs_start_gives_every_listed_user_an_initial_password_once(tmp_path, class_list):
    data = tmp_path / "data"
    config = tmp_path / "hub.py"
    config.write_text("c = get_config()\nload_subconfig(%r)\n" % COURSE_CONFIG)
    env = {"HUB_DATA": str(data), "HUB_CLASS_LIST": class_list}
    lines = probe({"action": "prepare", "config_file": str(config)}, env)["lines"]
    assert "3 new initial password(s) (alice, jean_luc, tom)" in " ".join(lines), lines
    sheet = passwords.handed_out(str(data))
    assert sorted(sheet) == ["alice", "jean_luc", "tom"]
    assert stat.S_IMODE(os.stat(data).st_mode) == 0o711 and stat.S_IMODE(os.stat(data / "users").st_mode) == 0o700
    assert "0 new initial password(s)" in " ".join(probe({"action": "prepare", "config_file": str(config)}, env)["lines"])
    assert passwords.handed_out(str(data)) == sheet  # nobody given another


def test_a_hub_with_another_authenticator_gets_no_initial_passwords(tmp_path, class_list):
    config = tmp_path / "hub.py"
    config.write_text('c = get_config()\nload_subconfig(%r)\nc.JupyterHub.authenticator_class = "dummy"\n' % COURSE_CONFIG)
    lines = probe({"action": "prepare", "config_file": str(config)},
                  {"HUB_DATA": str(tmp_path / "data"), "HUB_CLASS_LIST": class_list})["lines"]
    assert "no initial passwords: the hub's authenticator is <class 'jupyterhub.auth.DummyAuthenticator'>" in lines[0]
    assert not os.path.exists(passwords.sheet_of(str(tmp_path / "data")))


def test_a_plain_first_use_authenticator_gets_them_in_the_file_it_reads(tmp_path, class_list):
    """make hub-check's control swaps the course's authenticator for FirstUseAuthenticator: the
    listed names still have their initial passwords, in that authenticator's file."""
    config = tmp_path / "hub.py"
    other = tmp_path / "other.dbm"
    config.write_text('c = get_config()\nload_subconfig(%r)\n'
                      'c.JupyterHub.authenticator_class = "firstuseauthenticator.FirstUseAuthenticator"\n'
                      'c.FirstUseAuthenticator.dbm_path = %r\n' % (COURSE_CONFIG, str(other)))
    probe({"action": "prepare", "config_file": str(config)}, {"HUB_DATA": str(tmp_path / "data"), "HUB_CLASS_LIST": class_list})
    sheet = passwords.handed_out(str(tmp_path / "data"))
    assert passwords.check_password(str(other), "alice", sheet["alice"]) == passwords.RIGHT


def test_kubernetes_uses_the_same_authenticator_traits_and_start(tmp_path, class_list):
    """deploy/kubernetes/values.yaml: the chart passes hub.config's sections to JupyterHub as they
    are (c[section].update), runs hub.extraConfig's code, and its hub pod's init container gives
    the initial passwords: the same traits, hook and command as make hub's."""
    with open(KUBERNETES_VALUES) as f:
        hub = yaml.safe_load(f)["hub"]
    config = {k: v for k, v in hub["config"].items() if k != "KubeSpawner"}  # KubeSpawner: not in make hub's venv
    course = config["CourseAuthenticator"]
    assert config["JupyterHub"]["authenticator_class"] == "course_hub.auth.CourseAuthenticator"
    extra = tmp_path / "extra_config.py"
    extra.write_text("c = get_config()\n" + "\n".join(hub["extraConfig"].values()))
    answer = made(dict(config, CourseAuthenticator=dict(course, class_list=class_list)), config_file=str(extra))
    assert answer["authenticator"]["dbm_path"] == course["data_dir"] + "/passwords.dbm"
    assert answer["jupyterhub"]["subdomain_hook"].startswith("<function subdomain_hook")
    (init,) = hub["initContainers"]
    assert init["command"] == ["course-hub-passwords", "--data", course["data_dir"], "--class-list", course["class_list"]]
    assert init["image"] == "%s:%s" % (hub["image"]["name"], hub["image"]["tag"])  # the hub's own image
    folder = os.path.dirname(course["class_list"])
    for mounts in (hub["extraVolumeMounts"], init["volumeMounts"]):
        assert {"name": "classlist", "mountPath": folder, "readOnly": True} in mounts
    assert {"name": "pvc", "mountPath": course["data_dir"]} in init["volumeMounts"]  # the chart's hub volume
    # the command takes those arguments: what it gives, in a scratch folder
    args = init["command"][1:]
    args[1], args[3] = str(tmp_path / "data"), class_list
    assert passwords.main(args) == 0 and sorted(passwords.handed_out(str(tmp_path / "data"))) == ["alice", "jean_luc", "tom"]


LTI = "course_hub.lti.CourseLTIAuthenticator"
LTI_TRAITS = ["issuer", "client_id", "deployment_ids", "authorize_url", "jwks_endpoint", "data_dir", "username_key",
              "milestone_parameter", "allow_all", "ta_roles"]
LTI_ENV = {"HUB_AUTH": "lti", "HUB_LTI_ISSUER": "https://lms.example.edu", "HUB_LTI_CLIENT_ID": "42,43",
           "HUB_LTI_DEPLOYMENT_ID": "1:ros", "HUB_LTI_AUTHORIZE_URL": "https://lms.example.edu/auth",
           "HUB_LTI_JWKS_URL": "https://lms.example.edu/jwks"}


def made_lti(config=None, config_file=None, env=None):
    return probe({"action": "traits", "config": config or {}, "config_file": config_file,
                  "authenticator_class": LTI, "authenticator_traits": LTI_TRAITS}, env)


def test_a_class_with_an_lms_chooses_the_lti_login_in_the_config_file(tmp_path):
    answer = made_lti(config_file=COURSE_CONFIG, env=dict(LTI_ENV, HUB_DATA=str(tmp_path)))
    assert "error" not in answer and answer["warnings"] == [], answer
    assert answer["jupyterhub"]["authenticator_class"] == LTI
    auth = answer["authenticator"]
    assert (auth["issuer"], auth["client_id"], auth["deployment_ids"]) == ("https://lms.example.edu", ["42", "43"],
                                                                            ["1:ros"])
    assert auth["data_dir"] == str(tmp_path) and auth["username_key"] == "sub"  # the claim that never changes
    assert auth["milestone_parameter"] == "milestone" and auth["allow_all"] is True  # the LMS decides who
    assert not any("institution" in role for role in auth["ta_roles"])


def test_the_lti_login_without_its_registration_stops_with_what_is_missing(tmp_path):
    answer = made_lti(config_file=COURSE_CONFIG, env={"HUB_AUTH": "lti", "HUB_DATA": str(tmp_path)})
    assert "issuer, client_id, deployment_ids, authorize_url, jwks_endpoint not set" in answer["error"], answer


def test_the_lti_login_gives_no_initial_passwords_and_the_class_list_path_is_unchanged(tmp_path, class_list):
    config = tmp_path / "hub.py"
    config.write_text("c = get_config()\nload_subconfig(%r)\n" % COURSE_CONFIG)
    env = dict(LTI_ENV, HUB_DATA=str(tmp_path / "data"), HUB_CLASS_LIST=class_list)
    lines = probe({"action": "prepare", "config_file": str(config)}, env)["lines"]
    assert "no initial passwords: the hub's authenticator is <class '%s'>" % LTI in lines[0], lines
    assert not os.path.exists(passwords.sheet_of(str(tmp_path / "data")))
    hub = made(config_file=COURSE_CONFIG, env={"HUB_DATA": str(tmp_path), "HUB_CLASS_LIST": class_list})["jupyterhub"]
    assert hub["authenticator_class"] == "course_hub.auth.CourseAuthenticator"  # without HUB_AUTH=lti


def test_kubernetes_values_show_the_lti_login_with_the_same_traits(tmp_path):
    """values.yaml's commented CourseLTIAuthenticator section, uncommented, is a configuration
    the class accepts."""
    text = open(KUBERNETES_VALUES).read()
    block = re.search(r"^    # CourseLTIAuthenticator:\n((?:    #   .*\n)+)", text, re.M)
    assert block, "values.yaml shows no CourseLTIAuthenticator section"
    section = yaml.safe_load("\n".join(line[7:] for line in block.group(1).splitlines()))
    answer = made_lti({"CourseLTIAuthenticator": section})
    assert "error" not in answer and answer["warnings"] == [], answer
    assert answer["authenticator"]["data_dir"] == section["data_dir"] == "/srv/jupyterhub"
    assert "course_hub.lti.CourseLTIAuthenticator" in text
