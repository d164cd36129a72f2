// param_demo: node param_declare declares ~robot_name (default "muto") and says "Hello <robot_name>!" every 2 s, reading the parameter each time.
#include <ros/ros.h>

#include <iostream>
#include <string>

class ParameterNode
{
public:
  ParameterNode() : private_nh_("~")
  {
    // "declare" the parameter: give it its default value if nobody set it yet
    if (!private_nh_.hasParam("robot_name"))
      private_nh_.setParam("robot_name", std::string("muto"));

    timer_ = nh_.createTimer(ros::Duration(2.0), &ParameterNode::timerCallback, this);
  }

private:
  void timerCallback(const ros::TimerEvent&)
  {
    std::string robot_name;
    private_nh_.param<std::string>("robot_name", robot_name, "muto");
    ROS_INFO("Hello %s!", robot_name.c_str());
  }

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  ros::Timer timer_;
};

int main(int argc, char **argv)
{
  ros::init(argc, argv, "param_declare");
  ParameterNode node;
  ros::spin();
  return 0;
}
