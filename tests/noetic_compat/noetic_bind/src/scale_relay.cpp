// Noetic style: ros/ros.h is the only ROS include, and boost::bind's _1 is used unqualified.
// On Ubuntu 20.04's Noetic, ros/node_handle.h included <boost/bind.hpp>, which put _1 in the
// global namespace; Debian 12's includes <boost/bind/bind.hpp>, which does not.
#include <ros/ros.h>
#include <std_msgs/Int32.h>

#include "scale.h"

static void on_number(const std_msgs::Int32::ConstPtr& msg, ros::Publisher* out, int factor)
{
  std_msgs::Int32 scaled;
  scaled.data = scale_value(msg->data, factor);
  out->publish(scaled);
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "scale_relay");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  int factor = private_nh.param("factor", 2);
  ros::Publisher out = nh.advertise<std_msgs::Int32>("scaled", 10);
  ros::Subscriber in = nh.subscribe<std_msgs::Int32>("numbers", 10, boost::bind(&on_number, _1, &out, factor));
  ROS_INFO("scale_relay: numbers -> scaled, times %d", factor);
  ros::spin();
  return 0;
}
