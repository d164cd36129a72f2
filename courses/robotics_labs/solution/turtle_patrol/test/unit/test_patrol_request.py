"""Which patrol requests the server refuses (issue 9: vel/omega = 3e38 gave turtlesim theta 5.9e20)."""
import importlib.util
import math
from pathlib import Path

import pytest
from hypothesis import given, settings

from course_testkit.fuzz import FLOAT32_MAX, wild_floats
from turtlesim.constants import TICK, WORLD_SIZE

SCRIPT = Path(__file__).resolve().parents[2] / "src" / "patrol_server.py"


@pytest.fixture(scope="module")
def server():
    spec = importlib.util.spec_from_file_location("patrol_server", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_texts_requests_are_served(server):
    for request in [(2.0, 1.0, 5.5, 5.5, 0.0), (1.5, -1.0, 8.0, 8.0, -1.0), (0.0, 0.0, 0.0, WORLD_SIZE, 100.0)]:
        assert server.request_error(*request) is None


@pytest.mark.parametrize("vel, omega", [(3e38, 1.0), (1.0, 3e38), (-FLOAT32_MAX, 0.0), (1.0, -1e18)])
def test_huge_speeds_are_refused_with_the_limit(server, vel, omega):
    problem = server.request_error(vel, omega, 5.0, 5.0, 0.0)
    assert problem and "too fast" in problem and "must be <=" in problem


def test_limits_come_from_turtlesims_tick(server):
    assert (server.WORLD_SIZE, server.TICK) == (pytest.approx(WORLD_SIZE), TICK)
    assert server.MAX_VEL == pytest.approx(WORLD_SIZE / TICK)
    assert server.MAX_OMEGA == pytest.approx(math.pi / TICK)
    assert server.request_error(server.MAX_VEL, -server.MAX_OMEGA, 1.0, 1.0, 0.0) is None


@settings(max_examples=300, database=None)
@given(wild_floats(), wild_floats(), wild_floats(), wild_floats(), wild_floats())
def test_a_served_request_is_finite_and_drawable(server, vel, omega, x, y, theta):
    if server.request_error(vel, omega, x, y, theta) is None:
        assert all(math.isfinite(v) for v in (vel, omega, x, y, theta))
        assert abs(vel) * TICK <= WORLD_SIZE + 1e-9 and abs(omega) * TICK <= math.pi + 1e-9
        assert 0.0 <= x <= WORLD_SIZE and 0.0 <= y <= WORLD_SIZE
