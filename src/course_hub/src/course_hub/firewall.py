"""The hub's API port, reachable from the machine itself and the students' containers only.

The containers call the hub's API on their own network's gateway (an internal bridge has no
other route), so JupyterHub must listen on every address of the host (`hub_ip` 0.0.0.0): it
cannot be told to listen on loopback and each bridge's gateway alone. So while the hub runs, a
chain of its own in the firewall's INPUT accepts its API port from loopback and from podman's
bridges (netavark names them podman0, podman1 ...) and drops it from anywhere else: the port is
as closed to the network as a loopback address, and open to the containers. `make hub` adds the
chain when it starts the hub and removes it when the hub stops.
"""
from __future__ import annotations

import subprocess
from typing import List

BRIDGES = "podman+"  # netavark's bridge interfaces (iptables' + is a prefix match)


def chain(port: int) -> str:
    return "COURSE-HUB-API-%d" % port


def open_commands(port: int) -> List[List[str]]:
    """iptables commands that let only loopback and the containers reach `port`."""
    name = chain(port)
    return [["iptables", "-w", "-N", name],
            ["iptables", "-w", "-A", name, "-i", "lo", "-j", "RETURN"],
            ["iptables", "-w", "-A", name, "-i", BRIDGES, "-j", "RETURN"],
            ["iptables", "-w", "-A", name, "-j", "DROP"],
            ["iptables", "-w", "-I", "INPUT", "-p", "tcp", "--dport", str(port), "-j", name]]


def close_commands(port: int) -> List[List[str]]:
    """iptables commands removing what open_commands added (each may fail: not there)."""
    name = chain(port)
    return [["iptables", "-w", "-D", "INPUT", "-p", "tcp", "--dport", str(port), "-j", name],
            ["iptables", "-w", "-F", name],
            ["iptables", "-w", "-X", name]]


def guard(port: int) -> None:
    """Add the chain for `port` (after removing one a killed hub left). RuntimeError if iptables
    refuses: the hub does not start with its API open to the network."""
    remove(port)
    for command in open_commands(port):
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False)
        if done.returncode != 0:
            remove(port)
            raise RuntimeError("cannot keep the hub's API port %d off the network: `%s`: %s" % (
                port, " ".join(command), done.stdout.strip()))


def remove(port: int) -> None:
    for command in close_commands(port):
        subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
