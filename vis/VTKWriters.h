// VTK XML writers (binary, zlib-compressed), each file written to a temporary name and renamed.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "vis/PointData.h"

namespace anode {

// Particles as an unstructured grid of vertices (.vtu), opened directly by ParaView.
void writeParticlesVTU(const std::string& path, const ParticleData& data);
// Grid nodes as image data (.vti).
void writeGridVTI(const std::string& path, const GridData& data);

// A ParaView collection (.pvd) listing one file per output time.
class PVDSeries {
 public:
  void add(double time, const std::string& relativeFile) {
    entries_.emplace_back(time, relativeFile);
  }
  void write(const std::string& path) const;
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }

 private:
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace anode
