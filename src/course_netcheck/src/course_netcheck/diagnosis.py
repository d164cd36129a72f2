"""Diagnose the ROS 1 network settings of this host: ROS_MASTER_URI, ROS_IP, ROS_HOSTNAME.

ROS 1 nodes tell the master a URI built from ROS_HOSTNAME (if set), else ROS_IP, else
the host name; every other node then connects to that URI. A wrong value fails silently
(topics connect, nothing flows). `diagnose` turns the usual mistakes into clear messages.
The probes (local addresses, name resolution, TCP connect) are passed in, so the logic is
tested without a network.
"""
from __future__ import annotations

import ipaddress
import re
from dataclasses import dataclass
from typing import Callable, List, Mapping, Optional, Sequence, Set
from urllib.parse import urlparse

from course_net.addresses import is_loopback

OK, WARNING, ERROR = "ok", "warning", "error"


@dataclass(frozen=True)
class Finding:
    level: str
    message: str

    def __str__(self) -> str:
        return "[%s] %s" % (self.level.upper(), self.message)


@dataclass(frozen=True)
class NetworkSettings:
    master_uri: Optional[str]
    ros_ip: Optional[str]
    ros_hostname: Optional[str]

    @classmethod
    def from_environ(cls, env: Mapping[str, str]) -> "NetworkSettings":
        def get(name: str) -> Optional[str]:
            value = env.get(name, "").strip()
            return value or None
        return cls(get("ROS_MASTER_URI"), get("ROS_IP"), get("ROS_HOSTNAME"))


def parse_ip_addr(text: str) -> Set[str]:
    """Addresses in the output of `ip -o addr show` (IPv4 and IPv6, without prefix length)."""
    found = set()
    for match in re.finditer(r"\binet6?\s+([0-9a-fA-F.:]+)/\d+", text):
        found.add(match.group(1))
    return found


def host_port(uri: str) -> Optional[tuple]:
    """(host, port) of an http URI, or None if it is not one."""
    parsed = urlparse(uri)
    if parsed.scheme != "http" or not parsed.hostname or parsed.port is None:
        return None
    return parsed.hostname, parsed.port


def diagnose_settings(settings: NetworkSettings, local_addresses: Set[str],
                      resolve: Callable[[str], List[str]]) -> List[Finding]:
    """Checks that need no master: is the master URI well formed, is the advertised address ours?"""
    findings: List[Finding] = []
    master = host_port(settings.master_uri) if settings.master_uri else None
    if settings.master_uri is None:
        findings.append(Finding(ERROR, "ROS_MASTER_URI is not set (e.g. export ROS_MASTER_URI=http://MASTER_HOST:11311)"))
    elif master is None:
        findings.append(Finding(ERROR, "ROS_MASTER_URI=%s is not of the form http://HOST:PORT" % settings.master_uri))
    ours = ", ".join(sorted(local_addresses)) or "none found"
    if settings.ros_ip and settings.ros_hostname:
        findings.append(Finding(WARNING, "both ROS_IP and ROS_HOSTNAME are set; ROS_HOSTNAME=%s wins, ROS_IP is ignored"
                                % settings.ros_hostname))
    if settings.ros_hostname:
        addresses = resolve(settings.ros_hostname)
        if not addresses:
            findings.append(Finding(ERROR, "ROS_HOSTNAME=%s does not resolve on this host; other machines will not "
                                    "resolve it either (use an address: ROS_IP, or add it to /etc/hosts)"
                                    % settings.ros_hostname))
        elif not set(addresses) & local_addresses:
            findings.append(Finding(ERROR, "ROS_HOSTNAME=%s resolves to %s, which is not an address of this host "
                                    "(its addresses: %s)" % (settings.ros_hostname, ", ".join(addresses), ours)))
        advertised = settings.ros_hostname
    elif settings.ros_ip:
        try:
            ipaddress.ip_address(settings.ros_ip)
        except ValueError:
            findings.append(Finding(ERROR, "ROS_IP=%s is not an IP address (use ROS_HOSTNAME for names)" % settings.ros_ip))
        else:
            if settings.ros_ip not in local_addresses:
                findings.append(Finding(ERROR, "ROS_IP=%s is not an address of this host (its addresses: %s); other "
                                        "nodes will try to reach this host's nodes at %s and fail. Set ROS_IP to "
                                        "this host's address on the network the master is on."
                                        % (settings.ros_ip, ours, settings.ros_ip)))
        advertised = settings.ros_ip
    else:
        advertised = None
        findings.append(Finding(WARNING, "neither ROS_IP nor ROS_HOSTNAME is set: nodes advertise this host's name, "
                                "which other machines may not resolve"))
    if advertised and master and is_loopback(advertised) and not is_loopback(master[0]):
        findings.append(Finding(ERROR, "this host advertises %s (loopback) but the master is at %s: nodes on other "
                                "machines cannot reach this host's nodes" % (advertised, master[0])))
    if not [f for f in findings if f.level == ERROR]:
        findings.append(Finding(OK, "settings: ROS_MASTER_URI=%s advertised address=%s"
                                % (settings.master_uri, advertised or "(host name)")))
    return findings


def diagnose_reachability(master_uri: str, node_uris: Mapping[str, str],
                          can_connect: Callable[[str, int], bool]) -> List[Finding]:
    """Checks against a master: can we reach it, and every node at the URI it registered?"""
    master = host_port(master_uri)
    if master is None or not can_connect(*master):
        return [Finding(ERROR, "cannot reach the master at %s (is roscore running there, and is ROS_MASTER_URI "
                        "right?)" % master_uri)]
    findings = [Finding(OK, "master reachable at %s" % master_uri)]
    for node, uri in sorted(node_uris.items()):
        target = host_port(uri)
        if target is None or not can_connect(*target):
            findings.append(Finding(ERROR, "node %s registered the URI %s, which is not reachable from this host: "
                                    "the machine running %s advertises a wrong address (check ROS_IP / "
                                    "ROS_HOSTNAME there)" % (node, uri, node)))
    if len(findings) == 1:
        findings.append(Finding(OK, "all %d nodes reachable at their registered URIs" % len(node_uris)))
    return findings


def has_errors(findings: Sequence[Finding]) -> bool:
    return any(f.level == ERROR for f in findings)
