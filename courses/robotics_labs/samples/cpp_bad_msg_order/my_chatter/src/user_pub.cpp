// Checkpoint 1's publisher in C++; its CMakeLists.txt does not make it wait for TimestampString.h.
#include <iostream>
#include <string>
#include "ros/ros.h"
#include "my_chatter/TimestampString.h"

int main(int argc, char **argv) {
  ros::init(argc, argv, "user_pub");
  ros::NodeHandle n;
  ros::Publisher pub = n.advertise<my_chatter::TimestampString>("user_messages", 10);
  std::string line;
  while (ros::ok()) {
    std::cout << "Please enter a line of text and press <Enter>:" << std::endl;
    if (!std::getline(std::cin, line)) break;
    my_chatter::TimestampString msg;
    msg.message = line;
    msg.timestamp = ros::Time::now().toSec();
    pub.publish(msg);
  }
  return 0;
}
