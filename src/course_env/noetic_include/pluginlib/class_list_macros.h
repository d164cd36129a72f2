// course_env's Noetic C++ compatibility: Noetic's pluginlib had <pluginlib/class_list_macros.h> beside
// <pluginlib/class_list_macros.hpp>; Debian 12's pluginlib has only the .hpp (see ../boost/bind/bind.hpp).
#ifndef COURSE_ENV_NOETIC_PLUGINLIB_CLASS_LIST_MACROS_H
#define COURSE_ENV_NOETIC_PLUGINLIB_CLASS_LIST_MACROS_H
#include <pluginlib/class_list_macros.hpp>
#endif
