"""is_loopback: the loopback ranges and the name localhost, nothing else."""
import ipaddress

from hypothesis import given, strategies as st

from course_net.addresses import is_loopback


def test_loopback_addresses_and_name():
    for host in ("localhost", "127.0.0.1", "127.1.2.3", "::1"):
        assert is_loopback(host), host


def test_other_hosts_are_not_loopback():
    for host in ("0.0.0.0", "192.168.1.5", "::", "example.org", "", "localhost.", "LOCALHOST1"):
        assert not is_loopback(host), host


@given(st.ip_addresses())
def test_agrees_with_ipaddress_for_every_address(address):
    assert is_loopback(str(address)) == address.is_loopback


@given(st.text(max_size=40))
def test_any_text_gives_a_bool(host):
    assert is_loopback(host) in (True, False)
