// Checkpoint 1's subscriber in C++.
#include <cstdio>
#include "ros/ros.h"
#include "my_chatter/TimestampString.h"

void on_message(const my_chatter::TimestampString::ConstPtr &msg) {
  printf("Message: %s, Sent at: %f, Received at: %f\n", msg->message.c_str(), msg->timestamp,
         ros::Time::now().toSec());
}

int main(int argc, char **argv) {
  ros::init(argc, argv, "user_sub");
  ros::NodeHandle n;
  ros::Subscriber sub = n.subscribe("user_messages", 10, on_message);
  ros::spin();
  return 0;
}
