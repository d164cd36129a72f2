"""turtlesim.scene: the canvas as drawing commands for the lab page, and when ~image renders."""
import base64
import json

from PyQt5.QtGui import QImage

from turtlesim.canvas import Canvas
from turtlesim.constants import CENTRE, METER_PX, WORLD_SIZE
from turtlesim.frame import TurtleFrame
from turtlesim.pen import Pen
from turtlesim.scene import FrameGate, SceneLog, snapshot_json

RED = Pen(255, 0, 0, 5, True)


def test_nothing_changed_gives_no_update():
    log = SceneLog()
    log.record([], [("turtle1", 1.0, 2.0, 0.5, 3)])
    first = json.loads(log.take())
    assert first["seq"] == 1 and first["strokes"] == [] and first["clear"] is None
    assert first["turtles"] == [["turtle1", METER_PX * 1.0, round((WORLD_SIZE - 2.0) * METER_PX, 1), 0.5, 3]]
    log.record([], [("turtle1", 1.0, 2.0, 0.5, 3)])  # the turtle stood still
    assert log.take() is None and log.seq == 1


def test_strokes_keep_their_pen_and_order_and_a_lifted_pen_draws_nothing():
    log = SceneLog()
    log.record([(RED, [((1.0, 1.0), (2.0, 1.0))]), (Pen(on=False), [((3.0, 3.0), (4.0, 4.0))])], [])
    log.record([(RED.set(0, 255, 0, 0, 0), [((2.0, 1.0), (2.0, 2.0))])], [])
    update = json.loads(log.take())
    y1, y2 = round((WORLD_SIZE - 1.0) * METER_PX, 1), round((WORLD_SIZE - 2.0) * METER_PX, 1)
    assert update["strokes"] == [[255, 0, 0, 5, 45.0, y1, 90.0, y1], [0, 255, 0, 5, 90.0, y1, 90.0, y2]]
    assert json.loads(log.take() or "null") is None  # handed out once


def test_a_clear_drops_the_lines_drawn_before_it():
    log = SceneLog()
    log.record([(RED, [((1.0, 1.0), (2.0, 1.0))])], [])
    log.clear((10, 20, 30))
    log.record([(RED, [((5.0, 5.0), (6.0, 5.0))])], [])
    update = json.loads(log.take())
    assert update["clear"] == [10, 20, 30] and len(update["strokes"]) == 1 and update["strokes"][0][4] == 225.0


def test_the_snapshot_holds_the_path_image_and_the_last_number_it_includes():
    frame = TurtleFrame(Canvas())
    frame.spawn("turtle1", CENTRE, CENTRE, 0.0)
    frame.turtles["turtle1"].set_pen(255, 0, 0, 5, 0)
    frame.turtles["turtle1"].teleport_absolute(CENTRE + 2.0, CENTRE, 0.0)
    log = SceneLog()
    updates = frame.update(0.016, 0.0)
    log.record(((u.turtle.pen, u.result.segments) for u in updates),
               [(u.name, u.turtle.x, u.turtle.y, u.turtle.theta, u.turtle.icon) for u in updates])
    log.take()
    snapshot = json.loads(snapshot_json(log.state(), frame.canvas.path.copy(),
                                        [frame.canvas.icons.image(i) for i in range(len(frame.canvas.icons))]))
    assert snapshot["seq"] == 1 and snapshot["run"] == log.run and len(snapshot["icons"]) == len(frame.canvas.icons)
    paths = QImage.fromData(base64.b64decode(snapshot["paths"]), "PNG")
    middle = paths.pixel(round((CENTRE + 1.0) * METER_PX), round((WORLD_SIZE - CENTRE) * METER_PX))
    assert ((middle >> 16) & 0xFF, (middle >> 8) & 0xFF, middle & 0xFF) == (255, 0, 0)  # the red line
    assert snapshot["turtles"][0][0] == "turtle1"


def test_frames_render_only_for_a_subscriber_and_only_after_a_change():
    gate = FrameGate()
    nobody, one, two, other = frozenset(), frozenset({"a"}), frozenset({"a", "b"}), frozenset({"c"})
    assert not gate.due(nobody, 1) and not gate.due(nobody, 2)  # nobody watches: nothing rendered
    assert gate.due(one, 2)  # the first subscriber gets the canvas as it is
    assert not gate.due(one, 2) and not gate.due(one, 2)  # nothing changed since
    assert gate.due(one, 3)
    assert gate.due(two, 3)  # a second subscriber needs a first frame too
    assert gate.due(other, 3)  # one left and another came between two looks: it needs one as well
    assert not gate.due(nobody, 4) and gate.due(one, 4)  # all gone, then one back
    assert gate.renders == 5
