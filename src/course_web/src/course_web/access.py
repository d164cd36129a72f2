"""Who may open the page: anyone on this machine by default, a token holder when it listens wider.

On 127.0.0.1 (the default) only local users reach the port, as with roscore. Listening on any
other address lets the network publish cmd_vel and call services, so a token is then required:
the one given, or a fresh random one printed at start as the URL to open. The page keeps the
token in the URL's query (?token=...) and hands it to its websocket.
"""
from __future__ import annotations

import hmac
import secrets
import socket
from typing import Optional

from course_net.addresses import is_loopback

TOKEN_PARAM = "token"
TOKEN_BYTES = 18


def token_for(address: str, given: Optional[str]) -> Optional[str]:
    """The token the server requires: None on loopback without one, the given one, or a new one."""
    if given:
        return given
    return None if is_loopback(address) else secrets.token_urlsafe(TOKEN_BYTES)


def allowed(required: Optional[str], presented: Optional[str]) -> bool:
    """True when no token is required or the presented one is it (constant-time compare)."""
    if required is None:
        return True
    return presented is not None and hmac.compare_digest(required.encode(), presented.encode())


def page_url(address: str, port: int, token: Optional[str], url_host: str = "") -> str:
    """The URL to open, token included; on `url_host` when given (in a container, the address
    the host publishes the port on), else on the address listened on (this machine's name for
    any address)."""
    host = url_host or (socket.gethostname() if address in ("0.0.0.0", "", "::") else address)
    if ":" in host:
        host = "[%s]" % host
    return "http://%s:%d/%s" % (host, port, "?%s=%s" % (TOKEN_PARAM, token) if token else "")
