"""Ctrl+C for gzserver: the handlers only note the signal (the first one), never raise in the
interrupted code and never touch rospy; rospy shuts down later, from a thread holding no lock."""
import signal

import pytest

from mujoco_gazebo.ros.signals import SIGNALS, DeferredShutdown


@pytest.fixture
def restore_handlers():
    previous = {sig: signal.getsignal(sig) for sig in SIGNALS}
    yield
    for sig, handler in previous.items():
        signal.signal(sig, handler)


def test_nothing_noted_before_a_signal(restore_handlers):
    assert DeferredShutdown().install().signal is None


@pytest.mark.parametrize("sig", SIGNALS)
def test_a_signal_is_noted_not_raised(restore_handlers, sig):
    deferred = DeferredShutdown().install()
    signal.raise_signal(sig)  # no KeyboardInterrupt, no exit
    assert deferred.signal == sig


def test_the_first_signal_is_the_reason(restore_handlers):
    deferred = DeferredShutdown().install()
    signal.raise_signal(signal.SIGTERM)
    signal.raise_signal(signal.SIGINT)
    assert deferred.signal == signal.SIGTERM
