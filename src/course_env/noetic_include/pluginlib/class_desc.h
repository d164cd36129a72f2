// course_env's Noetic C++ compatibility: Noetic's pluginlib had <pluginlib/class_desc.h> beside
// <pluginlib/class_desc.hpp>; Debian 12's pluginlib has only the .hpp (see ../boost/bind/bind.hpp).
#ifndef COURSE_ENV_NOETIC_PLUGINLIB_CLASS_DESC_H
#define COURSE_ENV_NOETIC_PLUGINLIB_CLASS_DESC_H
#include <pluginlib/class_desc.hpp>
#endif
