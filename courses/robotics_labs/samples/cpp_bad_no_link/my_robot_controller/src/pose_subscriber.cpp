// A correct pose subscriber whose CMakeLists.txt forgets to link it with ${catkin_LIBRARIES}.
#include "ros/ros.h"
#include "turtlesim/Pose.h"

void on_pose(const turtlesim::Pose::ConstPtr &pose) {
  ROS_INFO("x: %.2f, y: %.2f", pose->x, pose->y);
}

int main(int argc, char **argv) {
  ros::init(argc, argv, "pose_subscriber");
  ros::NodeHandle node;
  ros::Subscriber sub = node.subscribe("/turtle1/pose", 10, on_pose);
  ros::spin();
  return 0;
}
