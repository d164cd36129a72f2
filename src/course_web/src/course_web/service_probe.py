"""A service's type, asked of the service itself: the probe of TCPROS's service handshake.

The master does not know a service's type (it keeps only the service's address), so a
call_service that names no type (the page's `/turtlesim/canvas`, roslibjs and roslibpy calls)
needs the service node's own word: a TCPROS connection header with `probe: 1` makes the node
answer with its header (`type`, `md5sum`, ...) and close without serving a call. rosservice does
the same (get_service_type), but importing rosservice also imports rosmsg, genpy's code generator,
optparse and tempfile: about 0.6-1 MiB of resident memory in every student's lab_view, for these
few lines. rosgraph, which lab_view holds anyway (rospy's), provides the header format.
"""
from __future__ import annotations

import io
import socket
import urllib.parse
from typing import Dict, Tuple

import rosgraph.network

HEADER_BUFFER = 4096


class ServiceProbeError(OSError):
    """The service's node could not be reached, or did not answer with a header."""


def address(uri: str) -> Tuple[str, int]:
    """(host, port) of a rosrpc://host:port/ URI (what the master's lookupService answers)."""
    try:
        parts = urllib.parse.urlsplit(uri)
        scheme, host, port = parts.scheme, parts.hostname, parts.port
    except ValueError:  # a port that is not a number, a bracket left open
        scheme = host = port = None
    if scheme != "rosrpc" or not host or port is None:
        raise ValueError("not rosrpc://host:port: %r" % uri)
    return host, port


def probe_header(service: str, uri: str, caller_id: str, timeout_s: float) -> Dict[str, str]:
    """The connection header the service at `uri` (rosrpc://host:port, the master's lookupService
    answer) sends a probe, within `timeout_s` for the connection and for each read."""
    try:
        host, port = address(uri)
    except ValueError as err:
        raise ServiceProbeError("service %s has an address that is %s" % (service, err))
    try:
        with socket.create_connection((host, port), timeout=timeout_s) as sock:
            rosgraph.network.write_ros_handshake_header(
                sock, {"probe": "1", "md5sum": "*", "callerid": caller_id, "service": service})
            return rosgraph.network.read_ros_handshake_header(sock, io.BytesIO(), HEADER_BUFFER)
    except (OSError, rosgraph.network.ROSHandshakeException) as err:
        raise ServiceProbeError("service %s at %s does not answer: %s" % (service, uri, err))


def service_type(service: str, uri: str, caller_id: str, timeout_s: float) -> str:
    """The type ("pkg/Name") the service at `uri` says it has."""
    kind = probe_header(service, uri, caller_id, timeout_s).get("type", "")
    if not kind:
        raise ServiceProbeError("service %s at %s did not say its type" % (service, uri))
    return kind
