#!/usr/bin/env python3
"""Simulator benchmark (figures, no assertions). Run from a sourced workspace:
    python3 bench/sim_bench.py
1. engine only (World + lidar, no ROS): max real-time factor for RRBot and for the Burger with a 5 Hz scan;
2. the real node (roslaunch on a private master, headless): flat-out real-time factor with /scan subscribed,
   CPU% of the gazebo process at real-time factor 1, /gazebo/model_states rate, spawn latency."""
import json
import subprocess
import sys
import time
import xmlrpc.client
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
from course_testkit.benchmarks import cpu_seconds, private_master


def engine_rtf(urdf: Path, lidar_body: str = "", seconds: float = 20.0) -> float:
    from mujoco_gazebo.engine import database
    from mujoco_gazebo.engine.frames import Pose
    from mujoco_gazebo.engine.lidar import Lidar, ScanConfig
    from mujoco_gazebo.engine.world import World
    import mujoco
    w = World()
    w.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    w.spawn("robot", urdf.read_text(), Pose())
    lidar, bid = Lidar(ScanConfig()), -1
    if lidar_body:
        bid = mujoco.mj_name2id(w.model, mujoco.mjtObj.mjOBJ_BODY, "robot::" + lidar_body)
        for j in ("wheel_left_joint", "wheel_right_joint"):
            w.set_joint_velocity("robot", j, 3.0, 5.0, 10.0)
    t0, next_scan = time.perf_counter(), 0.0
    while w.time < seconds:
        w.step(5)
        if bid >= 0 and w.time >= next_scan:
            lidar.scan(w.model, w.data, bid)
            next_scan += 0.2
    return seconds / (time.perf_counter() - t0)


def camera_render_ms(urdf: Path, frames: int = 30) -> str:
    """Median time to render one RRBot camera frame (default 320x240), or why it cannot."""
    from mujoco_gazebo.engine import database
    from mujoco_gazebo.engine.camera import BodyCamera, CameraConfig, RenderUnavailable
    from mujoco_gazebo.engine.frames import Pose
    from mujoco_gazebo.engine.world import World
    import mujoco
    w = World()
    w.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    w.spawn("robot", urdf.read_text(), Pose())
    bid = mujoco.mj_name2id(w.model, mujoco.mjtObj.mjOBJ_BODY, "robot::camera_link")
    camera = BodyCamera(CameraConfig())
    try:
        camera.render(w.model, w.data, bid)  # GL context, shaders
        times = []
        for _ in range(frames):
            w.step(33)
            t = time.perf_counter()
            camera.render(w.model, w.data, bid)
            times.append(time.perf_counter() - t)
        return "%.1f ms (%s)" % (1000 * sorted(times)[frames // 2], camera.backend)
    except RenderUnavailable as exc:
        return "unavailable: %s" % exc
    finally:
        camera.close()


def node_figures(rtf: str, measure_s: float = 10.0) -> dict:
    with private_master() as ros:
        headless = {name: value for name, value in ros.env.items() if name != "DISPLAY"}
        ros.start(["roslaunch", "turtlebot3_gazebo", "turtlebot3_empty_world.launch", "gui:=false",
                   "real_time_factor:=%s" % rtf], "gazebo", env=headless)
        import rospy
        from gazebo_msgs.msg import ModelStates
        from gazebo_msgs.srv import DeleteModel, GetWorldProperties, SpawnModel
        from geometry_msgs.msg import Pose
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import LaserScan
        out = {}
        if not rospy.core.is_initialized():
            rospy.init_node("sim_bench", anonymous=True, disable_signals=True)
        rospy.wait_for_service("/gazebo/get_world_properties", 60)
        props = rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)
        while "turtlebot3_burger" not in props().model_names:
            time.sleep(0.1)
        import rosgraph
        uri = rosgraph.Master("/sim_bench").lookupNode("/gazebo")
        pid = xmlrpc.client.ServerProxy(uri).getPid("/sim_bench")[2]
        clock, scans, states = [0.0], [0], [0]
        rospy.Subscriber("/clock", Clock, lambda m: clock.__setitem__(0, m.clock.to_sec()))
        rospy.Subscriber("/scan", LaserScan, lambda m: scans.__setitem__(0, scans[0] + 1))
        rospy.Subscriber("/gazebo/model_states", ModelStates, lambda m: states.__setitem__(0, states[0] + 1))
        time.sleep(2.0)
        w0, s0, c0, n0, m0 = time.monotonic(), clock[0], cpu_seconds(pid), scans[0], states[0]
        time.sleep(measure_s)
        w1, s1, c1, n1, m1 = time.monotonic(), clock[0], cpu_seconds(pid), scans[0], states[0]
        out.update(rtf=(s1 - s0) / (w1 - w0), cpu=100 * (c1 - c0) / (w1 - w0), scan_hz=(n1 - n0) / (w1 - w0),
                   states_hz=(m1 - m0) / (w1 - w0))
        spawn = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)
        delete = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)
        sdf = open(ROOT / "src" / "mujoco_gazebo" / "models" / "coke_can" / "model.sdf").read()
        lat = []
        for i in range(10):
            t = time.perf_counter()
            spawn("can%d" % i, sdf, "", Pose(), "")
            lat.append(time.perf_counter() - t)
        for i in range(10):
            delete("can%d" % i)
        out["spawn_ms"] = 1000 * sorted(lat)[len(lat) // 2]
    return out


def run_node(rtf: str) -> dict:
    """Each measurement in its own process: rospy can join only one master per process."""
    out = subprocess.run([sys.executable, __file__, "--node", rtf], capture_output=True, text=True, timeout=240)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    if len(sys.argv) == 3 and sys.argv[1] == "--node":
        print(json.dumps(node_figures(sys.argv[2])))
        return
    rr = ROOT / "src" / "rrbot_description" / "urdf" / "rrbot.urdf"
    tb = ROOT / "src" / "turtlebot3_description" / "urdf" / "turtlebot3_burger.urdf.xacro"
    print("engine only, 1 ms step: RRBot max real-time factor %.0fx" % engine_rtf(rr))
    print("engine only, 1 ms step: Burger + 5 Hz 360-ray scan max real-time factor %.0fx" % engine_rtf(tb, "base_scan"))
    print("engine only: RRBot camera frame 320x240, median render time %s" % camera_render_ms(rr))
    flat = run_node("0")
    print("node, flat out, Burger with /scan subscribed: real-time factor %.1fx (scan %.1f Hz wall, "
          "model_states %.0f Hz wall), gazebo CPU %.0f%% of a core" % (flat["rtf"], flat["scan_hz"], flat["states_hz"], flat["cpu"]))
    one = run_node("1")
    print("node, real-time factor 1, Burger with /scan and model_states subscribed: rtf %.2f, gazebo CPU %.1f%% of a core, "
          "scan %.1f Hz, model_states %.0f Hz, spawn latency (coke_can, median of 10) %.1f ms"
          % (one["rtf"], one["cpu"], one["scan_hz"], one["states_hz"], one["spawn_ms"]))


if __name__ == "__main__":
    main()
