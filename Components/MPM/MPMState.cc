// MPM::saveState / loadState: what a restarted run needs to take the same steps as the run that
// wrote the checkpoint. Grid fields are not saved: every step rebuilds them from the particles.
#include <stdexcept>

#include "Components/MPM/MPM.h"

namespace anode {

void MPM::saveState(BinaryWriter& out) const {
  out.value<uint64_t>(materials_.size());
  for (const MPMMaterial& mat : materials_)
    mat.particles.forEachArray([&](const auto& array) { out.array(array); });
  out.value(nextParticleId_);
  if (diffusion_) diffusion_->saveState(materials_, out);
}

void MPM::loadState(BinaryReader& in) {
  if (in.value<uint64_t>() != materials_.size())
    throw std::runtime_error("the checkpoint has another number of materials than the input");
  for (size_t m = 0; m < materials_.size(); ++m) {
    ParticleSet& p = materials_[m].particles;
    // An array the input's setup creates must come back with the particle count, and one it
    // does not create must stay empty: otherwise the checkpoint is of another input.
    p.forEachArray([&](auto& array) {
      const bool used = !array.empty();
      in.array(array);
      if (used != !array.empty())
        throw std::runtime_error("material " + std::to_string(m) +
                                 ": the checkpoint's particle arrays do not match the input");
    });
    size_t n = p.count();
    p.forEachArray([&](const auto& array) {
      if (!array.empty() && array.size() != n)
        throw std::runtime_error("material " + std::to_string(m) +
                                 ": particle arrays of different lengths in the checkpoint");
    });
  }
  nextParticleId_ = in.value<int64_t>();
  if (diffusion_) diffusion_->loadState(materials_, in);
}

}  // namespace anode
