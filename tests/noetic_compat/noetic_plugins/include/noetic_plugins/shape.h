#ifndef NOETIC_PLUGINS_SHAPE_H
#define NOETIC_PLUGINS_SHAPE_H

namespace noetic_plugins
{
// The plugins' base class: pluginlib makes them with the default constructor, then the loader
// gives the size.
class Shape
{
public:
  virtual ~Shape() {}
  virtual void initialize(double size) = 0;
  virtual double area() const = 0;

protected:
  Shape() {}
};
}  // namespace noetic_plugins

#endif
