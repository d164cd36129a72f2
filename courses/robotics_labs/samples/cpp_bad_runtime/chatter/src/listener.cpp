// listener: the ROS wiki's C++ subscriber, printing every message it hears on /chatter_talk.
#include "ros/ros.h"
#include "std_msgs/String.h"

#include <iostream>

void chatterCallback(const std_msgs::String::ConstPtr& msg)
{
  std::cout << "I heard: [" << msg->data << "]" << std::endl;
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "listener", ros::init_options::AnonymousName);
  ros::NodeHandle n;

  ros::Subscriber sub = n.subscribe("chatter_talk", 1000, chatterCallback);

  ros::spin();

  return 0;
}
