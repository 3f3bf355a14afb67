// Data handed from the driver to the writers: named arrays over points (particles or nodes).
// vis knows nothing of MPM; the driver decides what goes in.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace anode {

struct NamedArray {
  std::string name;
  int components = 1;
  std::vector<double> real;      // used when the array holds real numbers
  std::vector<int64_t> integer;  // used when the array holds integers
  bool isInteger() const { return !integer.empty() || real.empty(); }
};

struct ParticleData {
  std::vector<double> points;  // x0 y0 z0 x1 y1 z1 ...
  std::vector<NamedArray> arrays;
  size_t count() const { return points.size() / 3; }
};

struct GridData {
  double origin[3] = {0, 0, 0};
  double spacing[3] = {1, 1, 1};
  int dims[3] = {1, 1, 1};         // nodes in each direction
  int first[3] = {0, 0, 0};        // index of the first node from the origin (a rank's piece)
  std::vector<NamedArray> arrays;  // one value per node, x fastest
};

}  // namespace anode
