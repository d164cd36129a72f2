#!/usr/bin/env python3
"""Relay benchmark: course_relay's Python relay against Debian's C++ topic_tools relay.

Publishes geometry_msgs/Twist (send time in linear.x, sequence in linear.y) through each
relay at 100 Hz, 1 kHz and flat out, and prints delivered counts, throughput and latency
p50/p99 side by side, with ours/topic_tools ratios. Starts its own master (no rosout) on a free
loopback port and stops everything it started. Run from a sourced workspace:
    python3 bench/relay_bench.py [--seconds 5]
"""
from __future__ import annotations

import argparse
import sys
import threading
import time

from course_testkit.benchmarks import private_master

from course_checks.nodes import NodeProcess

RELAYS = [("ours", "course_relay", "relay"), ("topic_tools", "topic_tools", "relay")]


def percentile(values, q):
    if not values:
        return float("nan")
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q / 100.0 * (len(values) - 1))))]


def measure(rospy, Twist, find, pkg, node_type, rate_hz, seconds, tag):
    in_topic, out_topic = "/bench_in_%s" % tag, "/bench_out_%s" % tag
    relay = NodeProcess([find(pkg, node_type)[0], in_topic, out_topic, "__name:=relay_%s" % tag])
    received = []
    lock = threading.Lock()

    def on_msg(msg):
        now = time.time()
        with lock:
            received.append((msg.linear.y, now - msg.linear.x))

    pub = rospy.Publisher(in_topic, Twist, queue_size=None)
    sub = rospy.Subscriber(out_topic, Twist, on_msg, tcp_nodelay=True, queue_size=100000)
    try:
        deadline = time.time() + 20
        probe = Twist()
        probe.linear.y = -1
        while time.time() < deadline and not received:  # the relay advertises OUT on its first message
            probe.linear.x = time.time()
            pub.publish(probe)
            time.sleep(0.05)
        time.sleep(0.5)
        with lock:
            received.clear()
        count = int(rate_hz * seconds) if rate_hz else 20000
        period = 1.0 / rate_hz if rate_hz else 0.0
        msg = Twist()
        start = time.perf_counter()
        first_send = time.time()
        for i in range(count):
            if period:
                target = start + i * period
                while True:
                    left = target - time.perf_counter()
                    if left <= 0:
                        break
                    time.sleep(left if left > 0.0005 else 0)
            msg.linear.x, msg.linear.y = time.time(), i
            pub.publish(msg)
        sent_for = time.time() - first_send
        settle = time.time() + 3.0
        while time.time() < settle:
            with lock:
                if len(received) >= count:
                    break
            time.sleep(0.05)
        with lock:
            data = [(seq, lat) for seq, lat in received if seq >= 0]
        latencies = [lat * 1000.0 for _, lat in data]
        return {"sent": count, "got": len(data), "rate": len(data) / max(sent_for, 1e-9),
                "p50": percentile(latencies, 50), "p99": percentile(latencies, 99)}
    finally:
        sub.unregister()
        pub.unregister()
        relay.stop(5)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=5.0, help="duration of the 100 Hz and 1 kHz runs")
    opts = parser.parse_args()
    with private_master(rosout=False):
        import rospy
        from geometry_msgs.msg import Twist
        from roslib.packages import find_node
        rospy.init_node("relay_bench", disable_signals=True)
        print("Twist through a relay; latency = publish -> receive through the relay (ms)")
        print("%-10s %-12s %8s %8s %10s %8s %8s" % ("rate", "relay", "sent", "got", "msgs/s", "p50", "p99"))
        for rate in (100, 1000, None):
            row = {}
            for name, pkg, node_type in RELAYS:
                r = measure(rospy, Twist, find_node, pkg, node_type, rate, opts.seconds,
                            "%s_%s" % (name, rate or "max"))
                row[name] = r
                print("%-10s %-12s %8d %8d %10.0f %8.3f %8.3f" % (
                    "%d Hz" % rate if rate else "flat out", name, r["sent"], r["got"], r["rate"], r["p50"], r["p99"]),
                    flush=True)
            ours, ref = row["ours"], row["topic_tools"]
            print("%-10s %-12s %8s %8s %10.2f %8.2f %8.2f" % (
                "", "ratio o/t", "", "", ours["rate"] / ref["rate"], ours["p50"] / ref["p50"], ours["p99"] / ref["p99"]))
        rospy.signal_shutdown("done")
    return 0


if __name__ == "__main__":
    sys.exit(main())
