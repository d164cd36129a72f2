"""make hub's runner: which engine socket, and the hub's environment."""
from __future__ import annotations

from course_hub import runner


def test_the_socket_of_a_unix_docker_host():
    assert runner.socket_path("unix:///run/x/podman.sock") == "/run/x/podman.sock"
    assert runner.socket_path("tcp://10.0.0.1:2375") is None


def test_podman_serves_the_docker_api_with_the_runtime_cgroups_and_network_stack_this_machine_needs():
    command = runner.engine_command("/run/hub/podman.sock")
    assert command[:6] == ["podman", "--runtime", "runc", "--cgroup-manager=cgroupfs", "--network-backend", "netavark"]
    assert command[6:] == ["system", "service", "--time=0", "unix:///run/hub/podman.sock"]


def test_the_hub_runs_without_the_workspaces_python_path():
    env = runner.hub_env({"PYTHONPATH": "/ws/devel/lib/python3/dist-packages", "HOME": "/root"}, "unix:///s", 8123)
    assert env == {"HOME": "/root", "DOCKER_HOST": "unix:///s", "HUB_API_PORT": "8123"}


