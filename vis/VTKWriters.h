// VTK XML writers (binary, zlib-compressed), each file written to a temporary name and renamed.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "vis/PointData.h"

namespace anode {

// What a .vtu holds. Full: Float64 and Int64 arrays in zlib blocks, every bit of a run's output.
// Picture: Float32 and Int32, uncompressed, the data a picture is drawn from (makeSprites draws
// the same from it as from Full), for files compressed whole afterwards (xz packs raw numbers
// tighter than zlib blocks): a value beyond Float32's or Int32's range is an error
// (std::runtime_error), reals below FLT_MIN become subnormal or 0.
enum class VTUData { Full, Picture };

// Particles as an unstructured grid of vertices (.vtu), opened directly by ParaView.
void writeParticlesVTU(const std::string& path, const ParticleData& data,
                       VTUData form = VTUData::Full);
// Grid nodes as image data (.vti).
void writeGridVTI(const std::string& path, const GridData& data);

// A distributed run's output of one time (ParaView's parallel formats): the pieces of the ranks
// that hold particles (.pvtu, over .vtu pieces of the arrays `sample` has) or nodes (.pvti over
// .vti pieces of extent `pieceExtents` x0 x1 y0 y1 z0 z1 in `wholeExtent`); `pieces` are
// relative to the file's folder.
void writeParticlesPVTU(const std::string& path, const std::vector<std::string>& pieces,
                        const ParticleData& sample);
void writeGridPVTI(const std::string& path, const std::vector<std::string>& pieces,
                   const std::vector<std::array<int, 6>>& pieceExtents,
                   const std::array<int, 6>& wholeExtent, const GridData& sample);

// A ParaView collection (.pvd) listing one file per output time.
class PVDSeries {
 public:
  void add(double time, const std::string& relativeFile) {
    entries_.emplace_back(time, relativeFile);
  }
  void write(const std::string& path) const;
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  // Drops the entries whose file (relative to `directory`) does not exist; returns how many.
  size_t dropMissing(const std::string& directory);

 private:
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace anode
