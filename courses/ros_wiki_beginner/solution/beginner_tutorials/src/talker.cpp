// talker: says "hello world <count>" on the topic chatter (std_msgs/String), ten times a second.
#include <sstream>

#include <ros/ros.h>
#include <std_msgs/String.h>

int main(int argc, char **argv)
{
  ros::init(argc, argv, "talker");
  ros::NodeHandle node;
  ros::Publisher chatter = node.advertise<std_msgs::String>("chatter", 1000);
  ros::Rate rate(10);
  for (int count = 0; ros::ok(); ++count)
  {
    std::stringstream words;
    words << "hello world " << count;
    std_msgs::String message;
    message.data = words.str();
    ROS_INFO("%s", message.data.c_str());
    chatter.publish(message);
    ros::spinOnce();
    rate.sleep();
  }
  return 0;
}
