// listener: logs "I heard: [<data>]" for every std_msgs/String that arrives on chatter.
#include <ros/ros.h>
#include <std_msgs/String.h>

void heard(const std_msgs::String::ConstPtr &message)
{
  ROS_INFO("I heard: [%s]", message->data.c_str());
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "listener");
  ros::NodeHandle node;
  ros::Subscriber chatter = node.subscribe("chatter", 1000, heard);
  ros::spin();
  return 0;
}
