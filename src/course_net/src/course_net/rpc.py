"""XML-RPC (the ROS master's and every node's API) with a time limit (no ROS in here)."""
from __future__ import annotations

import xmlrpc.client


class TimedTransport(xmlrpc.client.Transport):
    """XML-RPC over HTTP whose connections give up after `timeout` seconds: a stuck master or node
    must not stall the caller (the lab page's server, the workbench's supervisor)."""

    def __init__(self, timeout: float) -> None:
        super().__init__()
        self.timeout = timeout

    def make_connection(self, host):
        connection = super().make_connection(host)
        connection.timeout = self.timeout
        return connection
