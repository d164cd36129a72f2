"""The generic check node `run_steps` running data milestones (course_milestones.steps) against
the reference packages built in solutions_ws: each primitive passes on a correct step list, and
fails on a wrong one with the cause it records (causes.json in the milestone's artifacts folder)
and a reason that says what was seen.

One course file holds every milestone; each rostest run holds several of them, one <test> each,
in sequence on one master (a milestone ends at its first failing step, so each failure is a
milestone of its own), with an artifacts folder per test. The runs go at once, on threads.
"""
from __future__ import annotations

import glob
import os
import re
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Dict, Iterator, Optional, Tuple
from xml.sax.saxutils import quoteattr

import pytest
import rospkg

from course_checks import junit
from course_checks.rostest_runner import RostestResult, run_rostest
from course_format import causes, course_file, schema

TIMEOUT_S = 900  # a guard against a hang: the runs take 10-60 s each on a quiet machine

COURSE = r"""
name: steps_test
title: The primitives of a data milestone, against the reference solutions
milestones:
  # -- chatter: example_pub.py publishes /chatter_talk at 10 Hz, example_sub.py prints what it hears
  - id: chatter_ok
    title: start (find), publishes, subscribes, prints
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter talker.py, find: {publishes: /chatter_talk}, as: talker}
      - publishes: {topic: /chatter_talk, type: std_msgs/String, node: talker, min_rate: 5, max_rate: 15, count: 3,
                    fields: {data: {matches: "^hello world [0-9.]+$", nonempty: true}}}
      - start: {rosrun: chatter example_sub.py, as: listener}
      - subscribes: {topic: /chatter_talk, node: listener}
      - prints: {node: listener, pattern: "I heard hello world"}
  - id: chatter_wrong_topic
    title: publishes on another topic
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter example_pub.py, find: {publishes: /chatter_talk}}
      - publishes: {topic: /chatter, within: 3}
  - id: chatter_wrong_type
    title: publishes another type
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter example_pub.py}
      - publishes: {topic: /chatter_talk, type: std_msgs/Int32}
  - id: chatter_wrong_rate
    title: an impossible rate
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter example_pub.py}
      - publishes: {topic: /chatter_talk, min_rate: 1000, within: 5}
  - id: chatter_wrong_value
    title: a field predicate that cannot hold
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter example_pub.py}
      - publishes: {topic: /chatter_talk, fields: {data: {matches: "^goodbye"}}}
  - id: chatter_not_subscribed
    title: a publisher subscribes to nothing
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter example_pub.py}
      - subscribes: {topic: /chatter_talk, within: 2}
  - id: chatter_not_printed
    title: a pattern that never appears
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter example_sub.py}
      - prints: {pattern: "never said", within: 2}
  - id: chatter_not_started
    title: a script that is not there
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter no_such_script.py}
  - id: chatter_course_error
    title: a type that does not exist
    text: test
    packages: [chatter]
    steps:
      - start: {rosrun: chatter example_pub.py}
      - publishes: {topic: /chatter_talk, type: std_msgs/NoSuchType}
  - id: publish_course_error
    title: a message that does not fit its type
    text: test
    packages: [chatter]
    steps:
      - publish: {topic: /words, type: std_msgs/String, message: {no_such_field: 1}}

  # -- pkg_param: param_demo's node /param_declare says Hello <~robot_name> every 2 s
  - id: param_ok
    title: running, prints, param_is, set_param
    text: test
    packages: [pkg_param]
    steps:
      - start: {rosrun: pkg_param param_demo}
      - running: {nodes: [/param_declare]}
      - prints: {pattern: "Hello muto"}
      - param_is: {name: /param_declare/robot_name, expect: {equals: muto}}
      - set_param: {name: /param_declare/robot_name, value: robot}
      - prints: {node: param_demo, pattern: "^.*Hello robot"}
      - param_is: {name: /param_declare/robot_name, expect: {matches: "^rob"}}
  - id: param_wrong_value
    title: a parameter with another value
    text: test
    packages: [pkg_param]
    steps:
      - start: {rosrun: pkg_param param_demo}
      - param_is: {name: /param_declare/robot_name, expect: {equals: robot}, within: 2}
  - id: not_running
    title: a node that is not there
    text: test
    packages: [pkg_param]
    steps:
      - running: {nodes: [/nobody], within: 1}

  # -- pkg_interfaces: Person.msg, Add.srv, Progress.action; add_server offers /add_two_ints
  - id: services_ok
    title: generated, start (find advertises), advertises, call
    text: test
    packages: [pkg_interfaces]
    steps:
      - generated: {messages: [pkg_interfaces/Person], services: [pkg_interfaces/Add], actions: [pkg_interfaces/Progress]}
      - start: {rosrun: pkg_interfaces add_server, find: {advertises: /add_two_ints}, as: server}
      - advertises: {service: /add_two_ints, type: pkg_interfaces/Add, node: server}
      - call: {service: /add_two_ints, request: {num1: 2, num2: 40}, expect: {sum: {equals: 42}}}
      # a client asks once and exits: it started all the same, and its output is there to read
      - start: {rosrun: pkg_interfaces add_client, args: [5, 37], as: client}
      - prints: {node: client, pattern: "^Result: 5 \\+ 37 = 42$"}
  - id: client_fails
    title: a client that exits with an error did not start
    text: test
    packages: [pkg_interfaces]
    steps:
      - start: {rosrun: pkg_interfaces add_client, args: [5]}
  - id: wrong_answer
    title: an answer the text does not give
    text: test
    packages: [pkg_interfaces]
    steps:
      - start: {rosrun: pkg_interfaces add_server, find: {advertises: /add_two_ints}}
      - call: {service: /add_two_ints, request: {num1: 2, num2: 40}, expect: {sum: {equals: 41}}}
  - id: service_exception
    title: a server that raises
    text: test
    packages: [pkg_interfaces]
    steps:
      - start: {rosrun: pkg_interfaces add_server, find: {advertises: /add_two_ints}}
      - call: {service: /add_two_ints, request: {num1: 2147483647, num2: 1}}
  - id: no_service
    title: a service that is not offered
    text: test
    packages: [pkg_interfaces]
    steps:
      - start: {rosrun: pkg_interfaces add_server, find: {advertises: /add_two_ints}}
      - advertises: {service: /add_three_ints, within: 2}
  - id: not_generated
    title: a message the package does not define
    text: test
    packages: [pkg_interfaces]
    steps:
      - generated: {messages: [pkg_interfaces/Person, pkg_interfaces/Nope]}

  # -- my_robot_controller on the course's turtlesim: pose_subscriber logs turtle1's X and Y
  - id: turtle_ok
    title: teleport, prints, publishes (the simulator's), publish, turtle_moves
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - start: {rosrun: my_robot_controller pose_subscriber, find: {subscribes: /turtle1/pose}}
      - subscribes: {topic: /turtle1/pose}
      - teleport: {x: 2.3, y: 8.7}
      - prints: {pattern: "X: 2.30, Y: 8.70"}
      - publishes: {topic: /turtle1/pose, type: turtlesim/Pose, node: /turtlesim, fields: {x: {approx: 2.3, tolerance: 0.01}}}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 2.0}}, duration: 1}
      - turtle_moves: {direction: forward, min_distance: 0.5}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {angular: {z: 2.0}}, duration: 1}
      - turtle_moves: {direction: left, min_distance: 0.5}
  - id: turtle_not_moving
    title: a turtle nothing drives
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 5, y: 5}
      - turtle_moves: {within: 1}
  - id: turtle_wrong_direction
    title: forward is not backward
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 5, y: 5}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 2.0}}, duration: 1}
      - turtle_moves: {direction: backward, within: 1}
  - id: teleop_ok
    title: type (arrow keys on the teleop's terminal)
    text: test
    packages: [mybot_teleop]
    world: [turtlesim]
    steps:
      - start: {rosrun: mybot_teleop teleop.py, find: {publishes: /turtle1/cmd_vel}, as: teleop}
      - teleport: {x: 3, y: 5}
      - type: {node: teleop, keys: "<up><up>", pause: 0.2}
      - turtle_moves: {direction: forward, min_distance: 0.3}
  - id: type_course_error
    title: keys typed on a node no step started
    text: test
    packages: [mybot_teleop]
    world: [turtlesim]
    steps:
      - type: {node: /rosout, keys: x}

  # -- drawing on the course's turtlesim: shapes driven by constant commands (turtlesim keeps the last
  # one for 1 s after it), a square by turtlesim's own draw_square (2 m sides), the pen's colour
  - id: circle_ok
    title: draws a circle (2 m/s turning 1 rad/s is a radius of 2 m), in_bounds around it
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 5.5, y: 3}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 2.0}, angular: {z: 1.0}},
                  duration: 7}
      - draws: {shape: circle, radius: 2}
      - in_bounds: {xmin: 3, xmax: 8, ymin: 2.5, ymax: 7.5, for: 9}
  - id: circle_wrong_radius
    title: a circle of radius 2 is not one of 1
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 5.5, y: 3}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 4.0}, angular: {z: 2.0}},
                  duration: 3.5}
      - draws: {shape: circle, radius: 1}
  - id: arc_ok
    title: draws an arc (1.5 m/s turning 1.5 rad/s for about 2 s)
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 2, y: 2}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 1.5}, angular: {z: 1.5}},
                  duration: 1}
      - draws: {shape: arc, angle: 2.9, radius: 1, tolerance: 0.2}
  - id: arc_wrong_angle
    title: an arc turned too far
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 2, y: 2}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 1.5}, angular: {z: 1.5}},
                  duration: 1}
      - draws: {shape: arc, angle: 1.57}
  - id: draws_not_moving
    title: a turtle nothing drives draws nothing
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 5, y: 5}
      - draws: {shape: circle, within: 1}
  - id: out_of_bounds
    title: a turtle driven into the wall
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 9, y: 5.5}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 3.0}}, duration: 1}
      - in_bounds: {for: 3}
  - id: square_ok
    title: draws a square (turtlesim's draw_square, from the centre its reset puts the turtle at)
    text: test
    packages: [turtlesim]
    world: [turtlesim]
    steps:
      - teleport: {x: 5.544445, y: 5.544445}
      - start: {rosrun: turtlesim draw_square, find: {publishes: /turtle1/cmd_vel}}
      - draws: {shape: square, side: 2, within: 45}
  - id: pen_ok
    title: pen_colour after set_pen
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 2, y: 8}
      - call: {service: /turtle1/set_pen, request: {r: 255, g: 0, b: 0, width: 3, 'off': 0}}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 1.0}}, duration: 0.5}
      - pen_colour: {r: 255, g: 0, b: 0}
  - id: pen_wrong_colour
    title: a blue pen is not red
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 2, y: 9}
      - call: {service: /turtle1/set_pen, request: {r: 0, g: 0, b: 255, width: 3, 'off': 0}}
      - publish: {topic: /turtle1/cmd_vel, type: geometry_msgs/Twist, message: {linear: {x: 1.0}}, duration: 0.5}
      - pen_colour: {r: 255, g: 0, b: 0, within: 2}

  # -- where a turtle comes to rest, and values a call saved: turtlesim's own teleport_relative moves or
  # turns turtle1 in one tick (then it stands still), its /spawn answers the name a later step uses
  - id: rest_ok
    title: stops_at and turns after turtlesim's teleport_relative
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 2, y: 5.5, theta: 0}
      - call: {service: /turtle1/teleport_relative, request: {linear: 2.0, angular: 0.0}}
      - stops_at: {x: 4, y: 5.5, tolerance: 0.01, heading: 0, heading_tolerance: 0.01}
      - call: {service: /turtle1/teleport_relative, request: {linear: 0.0, angular: -1.0}}
      - turns: {angle: -1.0, tolerance: 0.01, drift: 0.01}
      - stops_at: {heading: -1.0, heading_tolerance: 0.01}
  - id: saved_ok
    title: a name /spawn answered, saved and named by later steps
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - call: {service: /spawn, request: {x: 3, y: 4, theta: 0, name: ""}, save: {spawned: name},
               expect: {name: {matches: "^turtle[0-9]+$", differs: turtle1}}}
      - stops_at: {turtle: "${spawned}", x: 3, y: 4, tolerance: 0.01, within: 1}
      - publishes: {topic: "/${spawned}/pose", type: turtlesim/Pose, node: /turtlesim,
                    fields: {y: {approx: 4, tolerance: 0.01}}}
      - call: {service: /kill, request: {name: "${spawned}"}}
  - id: stops_at_wrong
    title: a turtle that stops short of the point
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 2, y: 5.5, theta: 0}
      - call: {service: /turtle1/teleport_relative, request: {linear: 1.0, angular: 0.0}}
      - stops_at: {x: 4, y: 5.5, tolerance: 0.1}
  - id: turns_wrong
    title: a turn that moves the turtle is no turn in place
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - teleport: {x: 5, y: 5, theta: 0}
      - call: {service: /turtle1/teleport_relative, request: {linear: 0.5, angular: 1.0}}
      - turns: {angle: 1.0, drift: 0.05}
  - id: spawned_outside
    title: a turtle spawned outside the box appeared there
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - call: {service: /spawn, request: {x: 1, y: 1, theta: 0, name: far}}
      - in_bounds: {turtle: far, xmin: 2, xmax: 9, ymin: 2, ymax: 9, for: 1}
  - id: differs_wrong
    title: a field compared with a value the same call saved
    text: test
    packages: [my_robot_controller]
    world: [turtlesim]
    steps:
      - call: {service: /spawn, request: {x: 5, y: 5, theta: 0, name: twin}, save: {asked: name},
               expect: {name: {differs: "${asked}"}}}

  # -- pkg_tf: turtle_following.launch starts turtlesim, two frame broadcasters and the follower
  - id: tf_ok
    title: start (roslaunch, find), tf_frame, tf_follows
    text: test
    packages: [pkg_tf]
    steps:
      - start: {roslaunch: pkg_tf following.launch, find: {node: /listener}, as: following}
      - tf_frame: {frame: turtle1, parent: world}
      - tf_follows: {frame: turtle2, target: turtle1, distance: 1.0, within: 40}
  - id: tf_no_frame
    title: a frame nobody broadcasts
    text: test
    packages: [pkg_tf]
    steps:
      - start: {roslaunch: pkg_tf turtle_following.launch}
      # the frame first, with any parent (a loaded machine starts the launch file slowly), then its parent
      - tf_frame: {frame: turtle1, within: 60}
      - tf_frame: {frame: turtle1, parent: map, within: 1}
  - id: tf_not_following
    title: a frame that does not come close enough
    text: test
    packages: [pkg_tf]
    steps:
      - start: {roslaunch: pkg_tf turtle_following.launch}
      - tf_follows: {frame: turtle2, target: turtle1, distance: 0.001, within: 3}
  - id: launch_not_started
    title: a launch file that is not there
    text: test
    packages: [pkg_tf]
    steps:
      - start: {roslaunch: pkg_tf nowhere.launch}
"""

# Which milestones each rostest run holds (in order), and the world it starts.
RUNS = {
    "chatter": ((), ("chatter_ok", "chatter_wrong_topic", "chatter_wrong_type", "chatter_wrong_rate",
                     "chatter_wrong_value", "chatter_not_subscribed", "chatter_not_printed", "chatter_not_started",
                     "chatter_course_error", "publish_course_error")),
    "params_services": ((), ("param_ok", "param_wrong_value", "not_running", "services_ok", "client_fails", "wrong_answer",
                             "service_exception", "no_service", "not_generated")),
    "turtle": (("turtlesim",), ("turtle_ok", "turtle_not_moving", "turtle_wrong_direction", "teleop_ok",
                                "type_course_error")),
    "drawing": (("turtlesim",), ("circle_ok", "circle_wrong_radius", "arc_ok", "arc_wrong_angle", "draws_not_moving",
                                 "out_of_bounds")),
    "square_pen": (("turtlesim",), ("square_ok", "pen_ok", "pen_wrong_colour")),
    "rest": (("turtlesim",), ("rest_ok", "saved_ok", "stops_at_wrong", "turns_wrong", "spawned_outside",
                              "differs_wrong")),
    "tf": ((), ("tf_ok", "tf_no_frame", "tf_not_following", "launch_not_started")),
}
# milestone -> None (passes) or (the cause it records, a regular expression its reason matches)
EXPECTED: Dict[str, Optional[Tuple[str, str]]] = {
    "chatter_ok": None,
    "chatter_wrong_topic": ("wrong_topic", r"node /talker_\S+ publishes /chatter_talk, not /chatter"),
    "chatter_wrong_type": ("wrong_type", r"publishes /chatter_talk of type std_msgs/String; the text's type is "
                                         r"std_msgs/Int32"),
    "chatter_wrong_rate": ("wrong_rate", r"publishes at (9|10|11)\.?\d* Hz; the text asks for at least 1000 Hz"),
    "chatter_wrong_value": ("wrong_value", r"message 1 of .* data is 'hello world [0-9.]+', expected it to match "
                                           r"'\^goodbye' \(the message: \{data: 'hello world"),
    "chatter_not_subscribed": ("not_subscribed", r"subscribes nothing: no subscriber on /chatter_talk"),
    "chatter_not_printed": ("not_printed", r"`rosrun chatter example_sub.py` printed no line matching 'never said' since it started "
                                           r"\(waited 2 s\); it printed nothing at all"),
    "chatter_not_started": ("not_started", r"package chatter has no executable no_such_script.py \(found: "
                                           r"example_pub.py, example_sub.py\)"),
    "chatter_course_error": ("check_failed", r"^course file error at .*course.yaml:\d+ .*std_msgs/NoSuchType"),
    "publish_course_error": ("check_failed", r"^course file error at .*no_such_field"),
    "param_ok": None,
    "param_wrong_value": ("wrong_value", r"parameter /param_declare/robot_name is 'muto', expected 'robot'"),
    "not_running": ("not_running", r"no node named /nobody is running \(running: none\)"),
    "services_ok": None,
    "client_fails": ("not_started", r"`rosrun pkg_interfaces add_client 5` started no node: add_client exited with "
                                    r"status 1, its output ending with 'usage: add_client A B'"),
    "wrong_answer": ("wrong_answer", r"/add_two_ints answered \{sum: 42\} to \{num1: 2, num2: 40\}: sum is 42, "
                                     r"expected 41"),
    "service_exception": ("wrong_answer", r"calling /add_two_ints with .* failed: .*does not fit in int32"),
    "no_service": ("no_service", r"offers no service /add_three_ints \(it offers /add_two_ints\)"),
    "not_generated": ("not_generated", r"pkg_interfaces/msg/Nope.msg is not generated"),
    "turtle_ok": None,
    "turtle_not_moving": ("not_moving", r"turtle1 after teleporting turtle1 to \(5, 5\): it moved 0.00 m"),
    "turtle_wrong_direction": ("not_moving", r"moved [1-5]\.\d+ m \([1-5]\.\d+ m along its heading\).*move 0.2 m "
                                             r"backward"),
    "teleop_ok": None,
    "type_course_error": ("check_failed", r"^course file error at .*node '/rosout' is not the `as` name"),
    "circle_ok": None,
    "circle_wrong_radius": ("wrong_value", r"turtle1 after publishing .*: it drew a circle of radius 2\.\d\d m; "
                                           r"the text asks 1 m"),
    "arc_ok": None,
    "arc_wrong_angle": ("wrong_value", r"it turned [1-3]\.\d\d rad; the text asks an arc of 1\.57 rad"),
    "draws_not_moving": ("not_moving", r"turtle1 after teleporting turtle1 to \(5, 5\): it turned 0\.00 rad of the "
                                       r"6\.28 a circle needs; it did not move"),
    "out_of_bounds": ("wrong_value", r"turtle1 left the box x 0\.\.11\.0889, y 0\.\.11\.0889 at \(11\.09, 5\.50\), "
                                     r"about 0\.\d s after publishing"),
    "square_ok": None,
    "pen_ok": None,
    "pen_wrong_colour": ("wrong_value", r"the pen of turtle1 draws \(0, 0, 255\).* here \(\d+\.\d\d, 9\.00\) after "
                                        r"publishing .*; the text asks \(255, 0, 0\)"),
    "rest_ok": None,
    "saved_ok": None,
    "stops_at_wrong": ("not_moving", r"^turtle1 after calling /turtle1/teleport_relative: it stands at "
                                     r"\(3\.00, 5\.50\), heading 0\.00 rad: 1\.00 m from \(4, 5\.5\), where the "
                                     r"text puts it \(within 0\.1 m\)$"),
    "turns_wrong": ("not_moving", r"^turtle1 after calling /turtle1/teleport_relative: it turned 1\.00 rad left, "
                                  r"but it moved 0\.50 m from \(5\.00, 5\.00\), at \(5\.27, 5\.42\): a turn in "
                                  r"place stays within 0\.05 m$"),
    "spawned_outside": ("wrong_value", r"^far appeared at \(1\.00, 1\.00\) after calling /spawn, outside the box "
                                       r"x 2\.\.9, y 2\.\.9$"),
    "differs_wrong": ("wrong_answer", r"/spawn answered \{name: 'twin'\} to .*: name is 'twin', expected a value "
                                      r"other than 'twin'"),
    "tf_ok": None,
    "tf_no_frame": ("no_frame", r"TF frame turtle1 has the parent world; the text's parent is map"),
    "tf_not_following": ("check_failed", r"TF frame turtle2 came no closer than [0-9.]+ m to turtle1 within 3 s"),
    "launch_not_started": ("not_started", r"no launch file nowhere.launch in package pkg_tf \(found: "
                                          r"turtle_following.launch\)"),
}


def launch_xml(course_yaml: str, world, milestones, artifacts: str) -> str:
    """A rostest with `world`'s trusted nodes and one run_steps per milestone, each with its own
    artifacts folder (what the grader's rostest, course_file.test_launch, holds for one)."""
    lines = ['<?xml version="1.0"?>', "<launch>"]
    for name in world:
        package, kind = schema.WORLDS[name]
        lines.append("  <node pkg=%s type=%s name=%s/>" % (quoteattr(package), quoteattr(kind), quoteattr(name)))
    for name in milestones:
        lines += ['  <test test-name=%s name=%s pkg="course_milestones" type="run_steps" time-limit="240">'
                  % (quoteattr(name), quoteattr("run_steps_" + name)),  # no student node's name
                  "    <param name=\"course_file\" value=%s/>" % quoteattr(course_yaml),
                  "    <param name=\"milestone\" value=%s/>" % quoteattr(name),
                  "    <env name=\"COURSE_ARTIFACTS_DIR\" value=%s/>" % quoteattr(os.path.join(artifacts, name)),
                  "  </test>"]
    return "\n".join(lines + ["</launch>", ""])


class Outcome:
    """One milestone's result in a run: whether it passed, its reason, the causes it recorded."""

    def __init__(self, run: RostestResult, artifacts: str, name: str) -> None:
        files = glob.glob(os.path.join(run.results_dir, "ros_home", "test_results", "*", "rosunit-%s.xml" % name))
        suite = junit.parse_file(files[0]) if files else None
        self.ran = suite is not None and len(suite.cases) >= 1
        self.reasons = [c.message for c in suite.failed] if suite is not None else []
        self.passed = self.ran and not self.reasons
        self.causes = causes.recorded(os.path.join(artifacts, name))
        self.output = run.output


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Dict[str, Outcome]]:
    folder = tmp_path_factory.mktemp("course_steps")
    course_yaml = folder / "course.yaml"
    course_yaml.write_text(COURSE)
    course_file.load(str(course_yaml))  # the course file itself is right: every failure below is a step's
    futures: Dict[str, Tuple[Future, str]] = {}
    with ThreadPoolExecutor(max_workers=len(RUNS)) as pool:
        for run, (world, milestones) in RUNS.items():
            artifacts = str(folder / ("artifacts-" + run))
            test_file = folder / ("%s.test" % run)
            test_file.write_text(launch_xml(str(course_yaml), world, milestones, artifacts))
            # a rostest file outside any package: rostest is told the package its results go under
            args = ["--package=course_milestones", "--pkgdir=" + rospkg.RosPack().get_path("course_milestones"),
                    "--results-filename=%s.xml" % run]
            futures[run] = (pool.submit(run_rostest, "", str(test_file), args, results_dir=str(folder / ("run-" + run)),
                                        timeout=TIMEOUT_S), artifacts)
        found = {}
        for run, (future, artifacts) in futures.items():
            result = future.result()
            for name in RUNS[run][1]:
                found[name] = Outcome(result, artifacts, name)
        yield found


def test_every_milestone_here_is_run_and_expected():
    listed = [name for _, names in RUNS.values() for name in names]
    assert sorted(listed) == sorted(EXPECTED) and len(set(listed)) == len(listed)


@pytest.mark.parametrize("name", sorted(n for n, e in EXPECTED.items() if e is None))
def test_a_correct_step_list_passes(name: str, outcomes: Dict[str, Outcome]) -> None:
    outcome = outcomes[name]
    assert outcome.passed, "%s: ran %s, failed with %s\n--- rostest output (end) ---\n%s" % (
        name, outcome.ran, outcome.reasons, outcome.output[-3000:])
    assert outcome.causes == []


@pytest.mark.parametrize("name", sorted(n for n, e in EXPECTED.items() if e is not None))
def test_a_wrong_step_list_fails_with_its_cause_and_reason(name: str, outcomes: Dict[str, Outcome]) -> None:
    outcome = outcomes[name]
    cause, reason = EXPECTED[name]
    assert outcome.ran and outcome.reasons, "%s did not fail\n%s" % (name, outcome.output[-3000:])
    assert outcome.causes == [cause], "%s: %s (%s)" % (name, outcome.causes, outcome.reasons)
    assert re.search(reason, outcome.reasons[0]), "%s's reason: %s" % (name, outcome.reasons[0])
    assert "Traceback" not in outcome.reasons[0]
