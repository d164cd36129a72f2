#include <ros/ros.h>
#include <std_msgs/String.h>

void onChatter(const std_msgs::String::ConstPtr &in)
{
  ROS_INFO("I heard: [%s]", in->data.c_str());
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "listener");
  ros::NodeHandle nh;
  ros::Subscriber sub = nh.subscribe("chatter", 100, onChatter);
  ros::spin();
}
