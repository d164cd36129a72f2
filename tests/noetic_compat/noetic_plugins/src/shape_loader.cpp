// Loads every declared shape by name and prints its area for the size given on the command
// line. Noetic's way: <pluginlib/class_loader.h>, and ROS_INFO without including ros/console.h
// (Noetic's class_loader.hpp included it).
#include <cstdlib>
#include <string>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <pluginlib/class_loader.h>
#include <noetic_plugins/shape.h>

int main(int argc, char** argv)
{
  double size = argc > 1 ? std::atof(argv[1]) : 1.0;
  pluginlib::ClassLoader<noetic_plugins::Shape> loader("noetic_plugins", "noetic_plugins::Shape");
  std::vector<std::string> names = loader.getDeclaredClasses();
  int failures = 0;
  for (const std::string& name : names)
  {
    try
    {
      boost::shared_ptr<noetic_plugins::Shape> shape = loader.createInstance(name);
      shape->initialize(size);
      ROS_INFO("area of %s: %.4f", name.c_str(), shape->area());
    }
    catch (pluginlib::PluginlibException& ex)
    {
      ROS_ERROR("%s did not load: %s", name.c_str(), ex.what());
      ++failures;
    }
  }
  ROS_INFO("%zu shapes declared, %d failed", names.size(), failures);
  return failures == 0 && !names.empty() ? 0 : 1;
}
