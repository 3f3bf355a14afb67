// Readers of this code's own output, for tools that work from a finished run.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "vis/PointData.h"

namespace anode {

// The points of a particle .vtu (or .pvtu: its pieces in order) and those of the named point
// arrays it holds; other arrays are not read. Throws std::runtime_error if the file cannot be read.
ParticleData readParticlesVTU(const std::string& path, const std::vector<std::string>& arrays);

// The (time, file) entries of a .pvd collection, files as paths usable from the working directory.
std::vector<std::pair<double, std::string>> readPVD(const std::string& path);

}  // namespace anode
