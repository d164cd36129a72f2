// For each pair of angles (radians) on the command line: the first normalised to [-pi, pi) and
// the shortest turn from the first to the second, as angles computes them. No roscpp here.
#include <cstdio>
#include <cstdlib>

#include <angles/angles.h>

int main(int argc, char** argv)
{
  for (int i = 1; i + 1 < argc; i += 2)
  {
    double from = std::atof(argv[i]);
    double to = std::atof(argv[i + 1]);
    std::printf("%.6f %.6f\n", angles::normalize_angle(from), angles::shortest_angular_distance(from, to));
  }
  return 0;
}
