// mybot_teleop: reads the arrow keys from the terminal (raw mode, no Enter) and publishes a Twist on /turtle1/cmd_vel for each.
#include <ros/ros.h>
#include <geometry_msgs/Twist.h>

#include <signal.h>
#include <stdio.h>
#include <termios.h>
#include <unistd.h>

#define KEYCODE_UP    0x41
#define KEYCODE_DOWN  0x42
#define KEYCODE_RIGHT 0x43
#define KEYCODE_LEFT  0x44
#define KEYCODE_Q     0x71

int kfd = 0;
struct termios cooked, raw;

void quit(int sig)
{
  (void)sig;
  tcsetattr(kfd, TCSANOW, &cooked);  // give the terminal back as it was
  ros::shutdown();
  exit(0);
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "mybot_teleop");
  ros::NodeHandle nh;

  double linear_scale = 2.0;
  double angular_scale = 2.0;
  ros::Publisher twist_pub = nh.advertise<geometry_msgs::Twist>("turtle1/cmd_vel", 10);

  signal(SIGINT, quit);

  // put the terminal in raw mode: one key at a time, without Enter and without echo
  tcgetattr(kfd, &cooked);
  raw = cooked;
  raw.c_lflag &= ~(ICANON | ECHO);
  raw.c_cc[VEOL] = 1;
  raw.c_cc[VEOF] = 2;
  tcsetattr(kfd, TCSANOW, &raw);

  puts("Reading from keyboard");
  puts("---------------------------");
  puts("Use the arrow keys to move the turtle. 'q' to quit.");
  fflush(stdout);

  char c;
  while (ros::ok())
  {
    // blocks until a key is pressed
    if (read(kfd, &c, 1) <= 0)
      break;

    double linear = 0.0, angular = 0.0;
    bool dirty = false;
    switch (c)
    {
      case KEYCODE_UP:
        linear = 1.0;
        dirty = true;
        break;
      case KEYCODE_DOWN:
        linear = -1.0;
        dirty = true;
        break;
      case KEYCODE_LEFT:
        angular = 1.0;
        dirty = true;
        break;
      case KEYCODE_RIGHT:
        angular = -1.0;
        dirty = true;
        break;
      case KEYCODE_Q:
        quit(0);
        break;
    }

    if (dirty)
    {
      geometry_msgs::Twist twist;
      twist.linear.x = linear_scale * linear;
      twist.angular.z = angular_scale * angular;
      twist_pub.publish(twist);
    }
  }

  tcsetattr(kfd, TCSANOW, &cooked);
  return 0;
}
