#include "ros/ros.h"
#include "std_msgs/String.h"

class Listener
{
public:
  explicit Listener(ros::NodeHandle &nh) : sub_(nh.subscribe("chatter", 10, &Listener::heard, this)) {}

private:
  void heard(const std_msgs::String &msg) { ROS_INFO_STREAM("I heard: [" << msg.data << "]"); }

  ros::Subscriber sub_;
};

int main(int argc, char **argv)
{
  ros::init(argc, argv, "listener");
  ros::NodeHandle nh;
  Listener listener(nh);
  ros::spin();
}
