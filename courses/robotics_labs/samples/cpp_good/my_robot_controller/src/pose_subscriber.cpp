// pose_subscriber: subscribes to /turtle1/pose and prints the turtle's X and Y every time a pose arrives.
#include <ros/ros.h>
#include <turtlesim/Pose.h>

#include <iostream>

void poseCallback(const turtlesim::Pose::ConstPtr& msg)
{
  ROS_INFO("Current Turtle Position - X: %.2f, Y: %.2f", msg->x, msg->y);
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "pose_subscriber");
  ros::NodeHandle n;
  int unused_count = 0;  // compiled with -Wall: a warning, which never fails a build

  ros::Subscriber sub = n.subscribe("/turtle1/pose", 10, poseCallback);
  std::cout << "Turtle Position Subscriber Node has been started!" << std::endl;

  ros::spin();

  return 0;
}
