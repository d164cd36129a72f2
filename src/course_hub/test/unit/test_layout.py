"""The hub's data folder's modes (course_hub.layout) and its public address (course_hub.origins)."""
from __future__ import annotations

import os
import stat

import pytest

from course_hub import layout, origins


def test_the_data_folder_lets_nobody_but_root_into_disks_snapshots_and_users(tmp_path):
    data = tmp_path / "data"
    (data / "users").mkdir(parents=True, mode=0o777)
    os.chmod(data / "users", 0o777)  # whatever it was: laid out again
    layout.lay_out(str(data))
    assert {p: stat.S_IMODE(os.stat(data / p).st_mode) for p in ("users", "disks", "snapshots", "grades", ".")} \
        == {"users": 0o700, "disks": 0o700, "snapshots": 0o700, "grades": 0o711, ".": 0o711}


def test_on_one_machine_each_server_has_an_origin_under_hub_localhost():
    assert origins.subdomain_host("http://127.0.0.1:8000") == "http://hub.localhost:8000"
    assert origins.subdomain_host("http://localhost:80") == "http://hub.localhost"
    assert origins.subdomain_host("https://[::1]:8443") == "https://hub.localhost:8443"


def test_a_hub_off_loopback_must_name_its_public_address():
    with pytest.raises(origins.HubConfigError, match="c.JupyterHub.subdomain_host"):
        origins.subdomain_host("http://0.0.0.0:8000")
