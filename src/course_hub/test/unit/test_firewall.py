"""The hub's API port closed to the network while the hub runs (course_hub.firewall)."""
from __future__ import annotations

import os
import shutil
import subprocess

import pytest

from course_hub import firewall


def test_loopback_and_the_bridges_pass_everything_else_is_dropped_and_closing_undoes_it():
    opened = firewall.open_commands(18081)
    chain = firewall.chain(18081)
    assert ["iptables", "-w", "-A", chain, "-i", "lo", "-j", "RETURN"] in opened
    assert ["iptables", "-w", "-A", chain, "-i", "podman+", "-j", "RETURN"] in opened
    assert opened[-2] == ["iptables", "-w", "-A", chain, "-j", "DROP"]  # after the two that pass
    assert opened[-1][3:] == ["INPUT", "-p", "tcp", "--dport", "18081", "-j", chain]
    assert firewall.close_commands(18081)[0][3:] == opened[-1][4:] or \
        firewall.close_commands(18081)[0][4:] == opened[-1][4:]


@pytest.mark.skipif(os.geteuid() != 0 or shutil.which("iptables", path="/usr/sbin:/sbin") is None,
                    reason="needs root and iptables")
def test_the_chain_is_added_once_and_removed_whole():
    port = 18000 + os.getpid() % 1000

    def rules() -> str:
        return subprocess.run(["iptables", "-w", "-S"], stdout=subprocess.PIPE, text=True, check=True).stdout

    try:
        firewall.guard(port)
        firewall.guard(port)  # again (a hub killed before its stop): still one jump, one chain
        assert rules().count("--dport %d -j %s" % (port, firewall.chain(port))) == 1
        assert "-A %s -j DROP" % firewall.chain(port) in rules()
    finally:
        firewall.remove(port)
    assert firewall.chain(port) not in rules()
