// user_pub: asks for a line of text again and again, publishes it with the time it was entered on /user_messages.
#include <ros/ros.h>
#include <my_chatter/TimestampString.h>

#include <iostream>
#include <string>

int main(int argc, char **argv)
{
  ros::init(argc, argv, "user_pub", ros::init_options::AnonymousName);
  ros::NodeHandle n;

  ros::Publisher pub = n.advertise<my_chatter::TimestampString>("/user_messages", 10);

  std::string line;
  while (ros::ok())
  {
    std::cout << "Please enter a line of text and press <Enter>:" << std::endl;
    if (!std::getline(std::cin, line))
      break;  // end of input (Ctrl+D)

    my_chatter::TimestampString msg;
    msg.message = line;
    msg.timestamp = ros::Time::now().toSec();
    pub.publish(msg);
  }

  ros::Duration(0.5).sleep();  // let the last message go out before the node ends
  return 0;
}
