// course_env's Noetic C++ compatibility: Noetic's pluginlib had <pluginlib/class_loader.h> beside
// <pluginlib/class_loader.hpp>; Debian 12's pluginlib has only the .hpp (see ../boost/bind/bind.hpp).
// Noetic's class_loader.hpp also included <ros/console.h> (pluginlib logged with ROS_DEBUG), so code
// written for it uses ROS_INFO after including only this header; Debian's logs with rcutils.
#ifndef COURSE_ENV_NOETIC_PLUGINLIB_CLASS_LOADER_H
#define COURSE_ENV_NOETIC_PLUGINLIB_CLASS_LOADER_H
#include <ros/console.h>
#include <pluginlib/class_loader.hpp>
#endif
