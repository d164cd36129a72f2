#include <string>

#include "ros/ros.h"
#include "std_msgs/String.h"

class Talker
{
public:
  explicit Talker(ros::NodeHandle &nh)
    : pub_(nh.advertise<std_msgs::String>("chatter", 10)),
      timer_(nh.createTimer(ros::Duration(0.05), &Talker::tick, this))
  {
  }

private:
  void tick(const ros::TimerEvent &)
  {
    std_msgs::String msg;
    msg.data = "hello world " + std::to_string(count_++);
    pub_.publish(msg);
  }

  ros::Publisher pub_;
  ros::Timer timer_;
  long count_ = 0;
};

int main(int argc, char **argv)
{
  ros::init(argc, argv, "talker");
  ros::NodeHandle nh;
  Talker talker(nh);
  ros::spin();
}
