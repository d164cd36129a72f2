"""lab_view: the node behind `roslaunch course_web lab_view.launch`.

    rosrun course_web lab_view [--port 8080] [--address 127.0.0.1] [--token T] [--max-message-bytes N]
                               [--url-host H]

It serves the page and the rosbridge v2 websocket on one port and prints the URL to open.
"""
from __future__ import annotations

import argparse
import asyncio
import os
import signal
from typing import List, Optional

import rospkg
import rospy

from course_web import access
from course_web.protocol import DEFAULT_MAX_MESSAGE_BYTES
from course_web.ros_bridge import RosBridge, RosMaster
from course_web.server import Settings, application

DEFAULT_PORT = 8080
DEFAULT_ADDRESS = "127.0.0.1"
# The token may come from the environment, where other users cannot read it (a command line they can).
TOKEN_ENV = "LAB_VIEW_TOKEN"


def parse(argv: List[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="lab_view", description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", type=int, default=DEFAULT_PORT)
    parser.add_argument("--address", default=DEFAULT_ADDRESS,
                        help="where to listen; anything but loopback requires a token")
    parser.add_argument("--token", default=os.environ.get(TOKEN_ENV, ""),
                        help="the token to require (default: $%s, else none on loopback and a random one, "
                        "printed, otherwise)" % TOKEN_ENV)
    parser.add_argument("--max-message-bytes", type=int, default=DEFAULT_MAX_MESSAGE_BYTES)
    parser.add_argument("--www", default="", help="the page's folder (default: this package's www)")
    parser.add_argument("--url-host", default="", help="the host the printed URL names (in a container: "
                        "the address the host publishes the port on)")
    return parser.parse_args(argv)


def www_folder(given: str) -> str:
    return given or os.path.join(rospkg.RosPack().get_path("course_web"), "www")


async def serve(args: argparse.Namespace, token: Optional[str]) -> None:
    bridge = RosBridge()
    settings = Settings(bridge, www_folder(args.www), token, args.max_message_bytes, RosMaster(), rospy.logwarn)
    server = application(settings).listen(args.port, address=args.address)
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    rospy.on_shutdown(lambda: loop.is_closed() or loop.call_soon_threadsafe(stop.set))
    url = access.page_url(args.address, args.port, token, args.url_host)
    print("lab_view: open %s" % url, flush=True)
    rospy.loginfo("lab_view: serving the lab on %s", url)
    await stop.wait()
    server.stop()
    for socket in list(settings.sockets):
        socket.close(1001, "the lab_view server is stopping")
    if settings.status is not None:
        settings.status.stop()
    bridge.shutdown()


def main(argv: Optional[List[str]] = None) -> None:
    args = parse(rospy.myargv()[1:] if argv is None else argv)
    token = access.token_for(args.address, args.token)
    rospy.init_node("lab_view", disable_signals=True)
    try:
        asyncio.run(serve(args, token))
    finally:
        rospy.signal_shutdown("lab_view stopped")
