"""The hub's public address, under which each student's server has an origin of its own.

JupyterHub's `subdomain_host` puts every user's server on a host of its own, `<slug>.<domain>`
(course_hub.names.subdomain_hook), so a page a student serves cannot act with the hub's cookies
of a TA who opens it. On one machine the hub is `http://hub.localhost:<port>` (every name under
.localhost is loopback); a class sets its public address, with wildcard DNS and a wildcard TLS
certificate. A hub listening off loopback with no public address set would put every server on
the hub's own origin: `subdomain_host` refuses that with what to set.
"""
from __future__ import annotations

from urllib.parse import urlparse

from course_hub.defaults import LOCAL_DOMAIN

LOOPBACK = ("127.0.0.1", "localhost", "::1")


class HubConfigError(ValueError):
    """The hub's configuration cannot make a safe hub; the message says what to set."""


def subdomain_host(bind_url: str) -> str:
    """JupyterHub's `subdomain_host` for a hub whose proxy listens on `bind_url` on loopback:
    http://hub.localhost[:port]. HubConfigError when `bind_url` is off loopback: then the course
    sets its public address itself."""
    bound = urlparse(bind_url)
    if bound.hostname not in LOOPBACK:
        raise HubConfigError(
            "the hub listens on %s, not on loopback: set c.JupyterHub.subdomain_host to its public address "
            "(e.g. https://hub.example.org), with wildcard DNS (*.hub.example.org) and a wildcard TLS "
            "certificate, so that each student's server has its own origin (docs/hub.md)" % bind_url)
    default_port = 443 if bound.scheme == "https" else 80
    port = bound.port or default_port
    return "%s://%s%s" % (bound.scheme, LOCAL_DOMAIN, "" if port == default_port else ":%d" % port)
