"""KeyMapSearch against simulated controllers: which keys it finds, in how many presses, and the
sentence a student reads when a direction is missing."""
import math

import pytest

from course_milestones import keymap as km

ARROWS = {"up": (2.0, 0.0), "down": (-2.0, 0.0), "left": (0.0, 2.0), "right": (0.0, -2.0)}
WASD = {"w": (1.0, 0.0), "s": (-1.0, 0.0), "a": (0.0, 1.0), "d": (0.0, -1.0)}


class FakeController:
    """Answers a press with the command its map gives; `line` controllers need Enter."""

    def __init__(self, keys, line=False, quits_on=None, continuous=False):
        self.keys, self.line, self.quits_on, self.continuous = keys, line, quits_on, continuous
        self.presses = []
        self.state = (0.0, 0.0)
        self.running = True

    def press(self, probe):
        self.presses.append(probe)
        if probe.key == self.quits_on:
            self.running = False
            return km.Outcome((), exited=True)
        command = self.keys.get(probe.key) if probe.enter == self.line else None
        if command is None:
            return km.Outcome((self.state,) * 3 if self.continuous else ())
        self.state = command
        return km.Outcome((command,) * (3 if self.continuous else 1))


def search(controller, **kwargs):
    s = km.KeyMapSearch(**kwargs)
    while True:
        probe = s.next_probe()
        if probe is None:
            return s.result()
        s.record(probe, controller.press(probe))


def test_arrows_found_in_four_presses():
    ctrl = FakeController(ARROWS)
    result = search(ctrl)
    assert result.complete
    assert result.keymap.keys == {km.FORWARD: "up", km.BACKWARD: "down", km.LEFT: "left", km.RIGHT: "right"}
    assert not result.keymap.enter
    assert len(ctrl.presses) == 4
    assert km.failure_message(result, "/turtle1/cmd_vel", "turtle1") is None


def test_wasd_with_enter_like_input():
    ctrl = FakeController(WASD, line=True)
    result = search(ctrl)
    assert result.complete and result.keymap.enter and result.keymap.layout == "w/a/s/d"
    assert result.keymap.describe() == "w/a/s/d + Enter (forward='w', backward='s', left='a', right='d')"
    # up, up+Enter, w, then w+Enter answers, and again when pressed once more; then s, a, d with Enter
    assert [(p.key, p.enter) for p in ctrl.presses[:5]] == [("up", False), ("up", True), ("w", False), ("w", True),
                                                            ("w", True)]
    assert result.presses == len(ctrl.presses) == 8


def test_wasd_with_x_backwards():
    keys = dict(WASD, x=(-1.0, 0.0))
    keys["s"] = (0.0, 0.0)  # s stops, as in turtlebot3_teleop_key
    result = search(FakeController(keys))
    assert result.complete and result.keymap.keys[km.BACKWARD] == "x"


def test_azerty_q_is_left_only_after_z_went_forward():
    keys = {"z": (1.0, 0.0), "s": (-1.0, 0.0), "q": (0.0, 1.0), "d": (0.0, -1.0)}
    ctrl = FakeController(keys)
    result = search(ctrl)
    assert result.complete and result.keymap.layout == "z/q/s/d"
    assert [p.key for p in ctrl.presses].index("q") > [p.key for p in ctrl.presses].index("z")


def test_ijkl_and_continuous_publishing():
    keys = {"i": (0.5, 0.0), ",": (-0.5, 0.0), "j": (0.0, 1.0), "l": (0.0, -1.0), "k": (0.0, 0.0)}
    result = search(FakeController(keys, continuous=True))
    assert result.complete and result.keymap.keys == {km.FORWARD: "i", km.BACKWARD: ",", km.LEFT: "j",
                                                      km.RIGHT: "l"}


def test_back_and_right_doing_nothing_fails_naming_the_keys():
    keys = {"up": (2.0, 0.0), "left": (0.0, 2.0)}
    ctrl = FakeController(keys)
    result = search(ctrl)
    assert not result.complete
    assert set(result.missing) == {km.BACKWARD, km.RIGHT}
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    assert "after pressing down, /turtle1/cmd_vel got no command with linear.x < 0" in message
    assert "no key made turtle1 turn right: after pressing right" in message
    # each silent key is pressed twice (a press can be lost while the node sets up its terminal)
    assert sum(1 for p in ctrl.presses if p.key == "down") == 2


def test_wrong_sign_is_reported_with_the_command_seen():
    keys = dict(ARROWS, right=(0.0, 2.0))  # right turns left
    result = search(FakeController(keys))
    message = km.failure_message(result, "/t/cmd_vel", "t")
    assert "turn right" in message and "angular.z < 0" in message and "angular.z=2" in message


def test_a_slow_answer_is_not_taken_for_the_next_key():
    class Slow(FakeController):
        """Answers 'up' one press late, as a node too slow for the probe window would."""

        def press(self, probe):
            self.presses.append(probe)
            late = len(self.presses) >= 2 and self.presses[-2].key == "up" and not self.presses[-2].enter
            return km.Outcome(((2.0, 0.0),) if late else ())
    ctrl = Slow({})
    result = search(ctrl)
    assert result.keymap is None  # up + Enter got up's answer once, but not again: not taken
    assert ctrl.presses[1] == ctrl.presses[2] == km.Probe(km.FORWARD, "up", True)


def test_nothing_goes_forward():
    ctrl = FakeController({})
    result = search(ctrl)
    assert result.keymap is None
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    assert message.startswith("no key made turtle1 go forward: after each of up, up + Enter, 'w'")
    assert len(ctrl.presses) == 2 * 2 * sum(len(layout.keys[km.FORWARD]) for layout in km.LAYOUTS)


def test_node_exiting_stops_the_search():
    ctrl = FakeController({"w": (1.0, 0.0)}, quits_on="up")
    result = search(ctrl)
    assert result.exited_after == km.Probe(km.FORWARD, "up", False)
    assert "exited after the key up" in km.failure_message(result, "/turtle1/cmd_vel", "turtle1")


def test_first_keymap_is_tried_first():
    first = km.KeyMap("w/a/s/d", {km.FORWARD: "w", km.BACKWARD: "s", km.LEFT: "a", km.RIGHT: "d"}, True)
    ctrl = FakeController(WASD, line=True)
    result = search(ctrl, first=first)
    assert result.complete and len(ctrl.presses) == 4


@pytest.mark.parametrize("direction,lin,ang,ok", [
    (km.FORWARD, 1.0, 0.0, True), (km.FORWARD, -1.0, 0.0, False), (km.BACKWARD, -0.1, 0.0, True),
    (km.LEFT, 0.0, 0.5, True), (km.LEFT, 1.0, 0.5, True), (km.RIGHT, 0.0, 0.5, False),
    (km.FORWARD, math.nan, 0.0, False),
])
def test_answers(direction, lin, ang, ok):
    assert km.answers(direction, lin, ang) is ok


def test_moved_along_heading_and_turns():
    start = (5.0, 5.0, math.pi / 2)
    assert km.moved(km.FORWARD, start, (5.0, 5.3, math.pi / 2), 0.05, 0.05)
    assert km.moved(km.BACKWARD, start, (5.0, 4.7, math.pi / 2), 0.05, 0.05)
    assert not km.moved(km.FORWARD, start, (5.3, 5.0, math.pi / 2), 0.05, 0.05)
    assert km.moved(km.LEFT, (0, 0, 3.1), (0, 0, -3.1), 0.05, 0.05)  # across the wrap
    assert km.moved(km.RIGHT, (0, 0, 0.2), (0, 0, 0.0), 0.05, 0.05)


def test_stale_bytes_risk_after_an_unanswered_arrow():
    up, w, w_line = km.Probe(km.FORWARD, "up", False), km.Probe(km.FORWARD, "w", False), km.Probe(km.FORWARD, "w", True)
    assert km.stale_bytes_risk([up], w) and km.stale_bytes_risk([up], w_line)
    assert not km.stale_bytes_risk([], w)
    assert not km.stale_bytes_risk([km.Probe(km.FORWARD, "up", True)], w)  # a line: Ctrl+U dropped it
    assert not km.stale_bytes_risk([up], km.Probe(km.BACKWARD, "down", False))


def test_skip_drops_the_next_probe_unpressed():
    s = km.KeyMapSearch()
    s.record(s.next_probe(), km.Outcome())  # up: nothing
    assert s.next_probe() == km.Probe(km.FORWARD, "up", True)
    s.skip()
    assert s.next_probe() == km.Probe(km.FORWARD, "w", False) and s.result().presses == 1
