// course_env's Noetic C++ compatibility: Noetic's pluginlib had <pluginlib/class_loader_base.h> beside
// <pluginlib/class_loader_base.hpp>; Debian 12's pluginlib has only the .hpp (see ../boost/bind/bind.hpp).
#ifndef COURSE_ENV_NOETIC_PLUGINLIB_CLASS_LOADER_BASE_H
#define COURSE_ENV_NOETIC_PLUGINLIB_CLASS_LOADER_BASE_H
#include <pluginlib/class_loader_base.hpp>
#endif
