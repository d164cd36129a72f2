#include <ros/ros.h>
#include <std_msgs/String.h>

int main(int argc, char **argv)
{
  ros::init(argc, argv, "talker");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<std_msgs::String>("chatter", 100);
  ros::Rate r(10);
  int n = 0;
  while (ros::ok())
  {
    std_msgs::String out;
    out.data = "hello world " + std::to_string(n++);
    pub.publish(out);
    r.sleep();
  }
}
