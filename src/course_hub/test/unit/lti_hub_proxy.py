"""A JupyterHub proxy that keeps its routes in memory and runs nothing, for test_lti.py's hub.

The LTI launch is all on the hub's own port (/hub/lti13/...), which the test calls directly: no
configurable-http-proxy (node) needs to run for it. JupyterHub imports this class by name
(`c.JupyterHub.proxy_class = "lti_hub_proxy.RoutesInMemory"`), from the PYTHONPATH the test
gives the hub's process.
"""
from __future__ import annotations

from typing import Any, Dict

from jupyterhub.proxy import Proxy
from traitlets import Bool


class RoutesInMemory(Proxy):
    """The routes JupyterHub adds, kept in a dict; nothing started, nothing proxied."""

    should_start = Bool(False)

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.routes: Dict[str, Dict[str, Any]] = {}

    async def add_route(self, routespec: str, target: str, data: Dict[str, Any]) -> None:
        self.routes[routespec] = {"routespec": routespec, "target": target, "data": data}

    async def delete_route(self, routespec: str) -> None:
        self.routes.pop(routespec, None)

    async def get_all_routes(self) -> Dict[str, Dict[str, Any]]:
        return dict(self.routes)
