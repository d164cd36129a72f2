// Exported the way Noetic's pluginlib tutorial does, through <pluginlib/class_list_macros.h>:
// Debian 12's pluginlib only has the .hpp.
#include <cmath>

#include <pluginlib/class_list_macros.h>
#include <noetic_plugins/shape.h>

namespace noetic_plugins
{
class Square : public Shape
{
public:
  void initialize(double size) override { side_ = size; }
  double area() const override { return side_ * side_; }

private:
  double side_ = 0.0;
};

class Disc : public Shape
{
public:
  void initialize(double size) override { radius_ = size; }
  double area() const override { return M_PI * radius_ * radius_; }

private:
  double radius_ = 0.0;
};
}  // namespace noetic_plugins

PLUGINLIB_EXPORT_CLASS(noetic_plugins::Square, noetic_plugins::Shape)
PLUGINLIB_EXPORT_CLASS(noetic_plugins::Disc, noetic_plugins::Shape)
