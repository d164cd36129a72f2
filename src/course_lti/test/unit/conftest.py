"""What course_lti's unit tests share: the tool's key and a configuration file naming it."""
from __future__ import annotations

import os
from typing import Callable

import pytest
import yaml

from course_testkit.lti import rsa_key_pair


@pytest.fixture(scope="session")
def key_pair():
    """(private PEM, public PEM), made once: RSA key generation takes a moment."""
    return rsa_key_pair()


@pytest.fixture
def write_config(tmp_path, key_pair) -> Callable[..., str]:
    """write_config(**fields): an lti.yaml in tmp_path with a valid registration, `fields` over it
    (a field given None is left out); its path."""
    key = tmp_path / "tool.pem"
    key.write_bytes(key_pair[0])

    def write(**fields) -> str:
        data = {"issuer": "https://lms.test", "client_id": "tool", "token_url": "https://lms.test/token",
                "lineitems_url": "https://lms.test/ags/lineitems", "private_key": "tool.pem", "kid": "k1"}
        data.update(fields)
        path = os.path.join(str(tmp_path), "lti.yaml")
        with open(path, "w") as stream:
            yaml.safe_dump({k: v for k, v in data.items() if v is not None}, stream)
        return path
    return write
