#!/usr/bin/env python3
"""Spawn/delete benchmark (figures, no assertions), issue 9: the real gazebo node in gazebo_ros's
empty world on a private master; ROUNDS times, spawn CANS coke cans then delete them all, and
print the gazebo process's RSS and each round's spawn and delete times. Memory and time must
stay flat (before the fix: RSS 68 -> 296 MB and a delete round 13 -> 48 s over 12 rounds of 200).
    python3 bench/spawn_bench.py [ROUNDS [CANS]]      (default 12 200)"""
import sys
import time
import xmlrpc.client

from course_testkit.benchmarks import private_master


def rss_mb(pid: int) -> float:
    with open("/proc/%d/status" % pid) as f:
        return next(int(line.split()[1]) for line in f if line.startswith("VmRSS:")) / 1024.0


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 12
    cans = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    with private_master() as ros:
        ros.start(["roslaunch", "gazebo_ros", "empty_world.launch", "gui:=false", "headless:=true",
                   "real_time_factor:=0"], "gazebo")
        import rosgraph
        import rospy
        from gazebo_msgs.srv import DeleteModel, SpawnModel
        from geometry_msgs.msg import Pose
        from mujoco_gazebo.engine import database
        rospy.init_node("spawn_bench", anonymous=True, disable_signals=True)
        rospy.wait_for_service("/gazebo/delete_model", 60)
        uri = rosgraph.Master("/spawn_bench").lookupNode("/gazebo")
        pid = xmlrpc.client.ServerProxy(uri).getPid("/spawn_bench")[2]
        spawn = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel, persistent=True)
        delete = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel, persistent=True)
        sdf = database.model_sdf("coke_can")
        print("start: gazebo RSS %.0f MB" % rss_mb(pid), flush=True)
        for r in range(1, rounds + 1):
            t0 = time.perf_counter()
            for i in range(cans):
                pose = Pose()
                pose.position.x, pose.position.y, pose.orientation.w = 0.2 * (i % 20), 0.2 * (i // 20), 1.0
                assert spawn("can%d" % i, sdf, "", pose, "").success
            t1 = time.perf_counter()
            for i in range(cans):
                assert delete("can%d" % i).success
            t2 = time.perf_counter()
            print("round %2d: %d cans spawned in %5.1f s, deleted in %5.1f s; gazebo RSS %.0f MB"
                  % (r, cans, t1 - t0, t2 - t1, rss_mb(pid)), flush=True)


if __name__ == "__main__":
    main()
