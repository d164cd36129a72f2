"""Start-up of turtlesim_node: Qt (a window with a display, offscreen without), ROS, the ticker."""
from __future__ import annotations

import os
import signal
import sys

from turtlesim.constants import CANVAS_PX


def has_display() -> bool:
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def main(argv=None) -> int:
    argv = sys.argv if argv is None else argv
    show = has_display() and os.environ.get("QT_QPA_PLATFORM", "") != "offscreen"
    if not show:
        os.environ["QT_QPA_PLATFORM"] = "offscreen"
    from PyQt5.QtCore import QTimer
    from PyQt5.QtWidgets import QApplication

    import rospy
    from turtlesim.node import TurtlesimNode

    app = QApplication(argv[:1])
    rospy.init_node("turtlesim", argv=argv)
    sim = TurtlesimNode()
    sim.start()
    if not show:
        rospy.spin()
        sim.stop()
        return 0

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
