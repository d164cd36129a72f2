// course_env's Noetic C++ compatibility: Boost.Bind's placeholders (_1 ... _9) in the global
// namespace, as ROS Noetic's headers gave them on its reference platform (Ubuntu 20.04).
//
// There, ros/node_handle.h, ros/publisher.h, message_filters, actionlib and tf2_ros included
// <boost/bind.hpp>, whose `using namespace boost::placeholders;` makes `boost::bind(&C::cb, this, _1)`
// compile in every roscpp file. Debian 12's ROS headers include <boost/bind/bind.hpp> instead,
// which leaves the placeholders in boost::placeholders. The env hook 30.course_noetic_cxx puts this
// folder on CPLUS_INCLUDE_PATH, so this file is found for <boost/bind/bind.hpp>: it includes
// Boost's own and adds the same using-directive <boost/bind.hpp> has. As with <boost/bind.hpp>,
// defining BOOST_BIND_NO_PLACEHOLDERS leaves the global namespace alone.
//
// The #include_next stands before the guard: with two course workspaces on CPLUS_INCLUDE_PATH (two
// copies of this file), the first copy's #include_next finds the second, which must still pass the
// include on to Boost's own rather than stop at its already-defined guard.
#include_next <boost/bind/bind.hpp>

#ifndef COURSE_ENV_NOETIC_BOOST_BIND_BIND_HPP
#define COURSE_ENV_NOETIC_BOOST_BIND_BIND_HPP

#ifndef BOOST_BIND_NO_PLACEHOLDERS
using namespace boost::placeholders;
#endif

#endif  // COURSE_ENV_NOETIC_BOOST_BIND_BIND_HPP
