// pose_subscriber: meant to print turtle1's X and Y; the mistake: main returns right after subscribing (no ros::spin()), so the callback never runs.
#include <ros/ros.h>
#include <turtlesim/Pose.h>

#include <iomanip>
#include <iostream>

void poseCallback(const turtlesim::Pose::ConstPtr& msg)
{
  std::cout << std::fixed << std::setprecision(2)
            << "Current Turtle Position - X: " << msg->x << ", Y: " << msg->y << std::endl;
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "pose_subscriber");
  ros::NodeHandle n;

  ros::Subscriber sub = n.subscribe("/turtle1/pose", 10, poseCallback);
  std::cout << "Turtle Position Subscriber Node has been started!" << std::endl;

  return 0;
}
