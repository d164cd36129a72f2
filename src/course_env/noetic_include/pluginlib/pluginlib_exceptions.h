// course_env's Noetic C++ compatibility: Noetic's pluginlib had <pluginlib/pluginlib_exceptions.h> beside
// <pluginlib/exceptions.hpp>; Debian 12's pluginlib has only the .hpp (see ../boost/bind/bind.hpp).
#ifndef COURSE_ENV_NOETIC_PLUGINLIB_PLUGINLIB_EXCEPTIONS_H
#define COURSE_ENV_NOETIC_PLUGINLIB_PLUGINLIB_EXCEPTIONS_H
#include <pluginlib/exceptions.hpp>
#endif
