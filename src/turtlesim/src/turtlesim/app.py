"""Start-up of turtlesim_node: Qt (a window with a display, offscreen without), ROS, the ticker.

The order keeps launch-to-/spawn short (see turtlesim.startup): rospy first, then the Qt
modules this mode needs, the node, its services.
"""
from __future__ import annotations

import os
import signal
import sys

from turtlesim import startup
from turtlesim.constants import CANVAS_PX


def has_display() -> bool:
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def main(argv=None) -> int:
    argv = sys.argv if argv is None else argv
    show = has_display() and os.environ.get("QT_QPA_PLATFORM", "") != "offscreen"
    if not show:
        os.environ["QT_QPA_PLATFORM"] = "offscreen"
    rospy = startup.import_rospy()  # first: before anything imports genpy
    if show:
        from PyQt5.QtWidgets import QApplication as Application
    else:  # offscreen nothing needs widgets, the largest Qt module to load
        from PyQt5.QtGui import QGuiApplication as Application

    from course_rospy import quick_exit
    from turtlesim.node import TurtlesimNode

    app = Application(argv[:1])
    startup.init_node("turtlesim", argv)
    sim = TurtlesimNode()
    sim.start()
    if not show:
        quick_exit.spin()  # rospy.spin() would end up to 0.5 s after SIGINT
        sim.stop()
        return 0

    from PyQt5.QtCore import QTimer

    from turtlesim.window import CanvasWindow
    window = CanvasWindow(sim.render)
    window.setWindowTitle("TurtleSim")
    window.setFixedSize(CANVAS_PX, CANVAS_PX)
    window.show()
    timer = QTimer()
    timer.timeout.connect(lambda: app.quit() if rospy.is_shutdown() else window.update())
    timer.start(16)
    signal.signal(signal.SIGINT, lambda *_: rospy.signal_shutdown("SIGINT"))
    app.exec_()
    sim.stop()
    rospy.signal_shutdown("window closed")
    return 0
