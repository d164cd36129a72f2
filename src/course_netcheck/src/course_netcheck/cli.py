"""ros_net_check: explain what is wrong with this host's ROS_MASTER_URI / ROS_IP / ROS_HOSTNAME.

Checks the settings against this host's addresses, then (unless --offline) asks the master
for every node's URI and tries to connect to each. Prints one line per finding; exit 1 on an error.
"""
from __future__ import annotations

import argparse
import os
import socket
import subprocess
import sys
from typing import Dict, List, Optional, Set

from course_netcheck.diagnosis import (ERROR, Finding, NetworkSettings, diagnose_reachability, diagnose_settings, has_errors,
                                   parse_ip_addr)


def local_addresses() -> Set[str]:
    try:
        text = subprocess.run(["ip", "-o", "addr", "show"], stdout=subprocess.PIPE, text=True, check=True).stdout
        return parse_ip_addr(text)
    except (OSError, subprocess.CalledProcessError):
        return {"127.0.0.1"}


def resolve(name: str) -> List[str]:
    try:
        return sorted({info[4][0] for info in socket.getaddrinfo(name, None)})
    except socket.gaierror:
        return []


def can_connect(host: str, port: int, timeout_s: float = 2.0) -> bool:
    try:
        with socket.create_connection((host, port), timeout=timeout_s):
            return True
    except OSError:
        return False


def node_uris(master_uri: str) -> Dict[str, str]:
    """Every node the master knows, with the URI it registered."""
    import rosgraph
    master = rosgraph.Master("/ros_net_check", master_uri=master_uri)
    publishers, subscribers, services = master.getSystemState()
    names = {n for _, nodes in publishers + subscribers + services for n in nodes}
    uris = {}
    for name in names:
        try:
            uris[name] = master.lookupNode(name)
        except Exception:  # the node went away between the two calls
            continue
    return uris


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="ros_net_check", description=__doc__.splitlines()[0])
    parser.add_argument("--offline", action="store_true", help="only check the settings, do not contact the master")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    settings = NetworkSettings.from_environ(os.environ)
    findings = diagnose_settings(settings, local_addresses(), resolve)
    if not args.offline and settings.master_uri:
        socket.setdefaulttimeout(5.0)
        reach = diagnose_reachability(settings.master_uri, {}, can_connect)
        if not has_errors(reach):
            try:
                reach = diagnose_reachability(settings.master_uri, node_uris(settings.master_uri), can_connect)
            except Exception as err:
                reach.append(Finding(ERROR, "the master at %s did not answer: %s" % (settings.master_uri, err)))
        findings += reach
    for finding in findings:
        print(finding)
    return 1 if has_errors(findings) else 0
